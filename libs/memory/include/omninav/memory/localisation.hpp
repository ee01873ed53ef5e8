#pragma once
// Localising a query image in the visual memory (001_5bb151a4e28490b4.txt §2.2-2.3): the
// hierarchical search of signature/hierarchy.hpp over the map's places, then for the best
// places the query's heading relative to each (phases, Eq. 1) and, when the places have
// positions (lattice, else ground truth), a position estimate.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "omninav/memory/visual_memory.hpp"
#include "omninav/signature/hierarchy.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::memory {

struct LocalisationParams {
  signature::HierarchyParams hierarchy;
  int top_k = 5;  // best places reported at the finest level
};

// Reads the `localisation:` section of memory.yaml (levels, candidate_similarity, max_probes,
// top_k).
void load_localisation_params(const ConfigReader& section, LocalisationParams& params);

// One of the best places for a query, best first in Localisation::best.
struct PlaceMatch {
  PlaceIndex place = 0;
  double dissimilarity = 0.0;  // at the finest level
  double similarity = 0.0;     // Eq. 3, 0..1000
  // The finest level's dissimilarity (Eq. 2/6) per compared value (lines × components), grey
  // levels: unlike the similarity, which Eq. 3 rescales so that the best place always scores
  // 1000, it tells whether the query matches any place at all.
  double dissimilarity_per_value = 0.0;
  // heading(query) − heading(place), from the phases, counter-clockwise positive.
  double relative_heading_rad = 0.0;
  double heading_confidence = 0.0;
  // The query's heading in the map's frame, when the place has a heading.
  std::optional<double> heading_rad;
};

// Where the places' positions come from.
enum class PositionFrame { kLattice, kTruth };
std::string to_string(PositionFrame frame);

// Positions in `frame`: the lattice's or the world's (ground truth), metres either way.
struct PositionEstimate {
  PositionFrame frame = PositionFrame::kTruth;
  // The best place's own position (topological localisation, §2.2).
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  // The mean of the best places' positions weighted by how far their similarity exceeds the
  // finest threshold, a finer guess between places (§2.3, footnote 1).
  Eigen::Vector2d interpolated_position = Eigen::Vector2d::Zero();
};

struct Localisation {
  signature::SearchResult search;  // the candidate sets of every level
  std::vector<PlaceMatch> best;    // best first
  std::optional<PositionEstimate> position;
};

// The positions used for estimates and pictures: lattice positions when every place has one,
// else ground truth when every place has it, else none.
std::optional<std::pair<PositionFrame, std::vector<Eigen::Vector2d>>> place_positions(
    const VisualMemory& memory);

// The median distance from each point to its nearest other: a grid's spacing ("one grid
// spacing" of DESIGN.md's evaluation). 1 for fewer than two points.
double typical_spacing(const std::vector<Eigen::Vector2d>& points);

class Localiser {
 public:
  // Builds the search index of `memory` (which must outlive the localiser) for params'
  // levels. Throws UsageError when the finest level exceeds the map's components.
  Localiser(const VisualMemory& memory, LocalisationParams params);

  // Pruned, coarse-to-fine. Throws UsageError when the query's signature does not match the
  // map's layout.
  Localisation localise(const signature::Signature& query) const;
  // Every level over every place (the oracle).
  Localisation localise_exhaustive(const signature::Signature& query) const;

  const signature::SignatureIndex& index() const { return index_; }
  const VisualMemory& memory() const { return memory_; }
  const LocalisationParams& params() const { return params_; }

 private:
  Localisation finish(const signature::Signature& query, signature::SearchResult search) const;

  const VisualMemory& memory_;
  LocalisationParams params_;
  signature::SignatureIndex index_;
  std::optional<std::pair<PositionFrame, std::vector<Eigen::Vector2d>>> positions_;
};

}  // namespace omninav::memory
