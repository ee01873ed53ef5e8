#pragma once
// Localising a query image in the visual memory (001_5bb151a4e28490b4.txt §2.2-2.3): the
// hierarchical search of signature/hierarchy.hpp over the map's places, then for the best
// places the query's heading relative to each (phases, Eq. 1) and, when the places have
// positions (lattice, else ground truth), a position estimate.

#include <opencv2/core.hpp>
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

struct PositionEstimate {
  PositionFrame frame = PositionFrame::kTruth;
  double x = 0.0;  // metres for ground truth, the lattice's unit otherwise
  double y = 0.0;
  // The best place's own position (topological localisation, §2.2) is (x, y); this is the
  // mean of the best places' positions weighted by how far their similarity exceeds the
  // finest threshold, a finer guess between places (§2.3, footnote 1).
  double interpolated_x = 0.0;
  double interpolated_y = 0.0;
};

struct Localisation {
  signature::SearchResult search;  // the candidate sets of every level
  std::vector<PlaceMatch> best;    // best first
  std::optional<PositionEstimate> position;
};

// The positions used for estimates and pictures: lattice positions when every place has one,
// else ground truth when every place has it, else none.
std::optional<std::pair<PositionFrame, std::vector<cv::Point2d>>> place_positions(
    const VisualMemory& memory);

// The median distance from each point to its nearest other: a grid's spacing ("one grid
// spacing" of DESIGN.md's evaluation). 1 for fewer than two points.
double typical_spacing(const std::vector<cv::Point2d>& points);

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
  std::optional<std::pair<PositionFrame, std::vector<cv::Point2d>>> positions_;
};

// Localisation against ground truth (DESIGN.md, Evaluation): the share of queries whose best
// place lies within one grid spacing of the truth; per level, the share whose candidate set
// contains the true nearest place and the mean size of the set; and the query heading's error
// when places have headings. Queries "between the grid points" are scored: those within half a
// cell's diagonal (spacing·√2/2) of a place. Others lie beyond the grid's edge or in a hole
// of it (furniture), where the nearest place can be a whole spacing away and its neighbours
// farther: they are counted apart and not scored.
class LocalisationScore {
 public:
  // `memory`'s places must all have ground truth (UsageError otherwise).
  explicit LocalisationScore(const VisualMemory& memory);

  struct Query {
    PlaceIndex nearest_place = 0;  // the place nearest the truth
    double nearest_m = 0.0;
    double error_m = 0.0;  // from the best place to the truth
    bool within_spacing = false;
    std::vector<bool> level_contains_nearest;
    std::optional<double> heading_error_rad;
    bool outside = false;  // farther than spacing·√2/2 from every place: not scored
  };
  Query add(const Localisation& result, const CameraPose& truth);

  std::size_t queries() const { return queries_; }  // scored ones
  std::size_t outside() const { return outside_; }
  double spacing_m() const { return spacing_m_; }
  double within_spacing_share() const;
  double nearest_share() const;  // the best place is the place nearest the truth
  double mean_error_m() const;   // from the best place to the truth
  std::vector<double> level_contains_share() const;
  std::vector<double> level_mean_size() const;
  // Median |heading error|, when any query had one.
  std::optional<double> median_heading_error_rad() const;
  // Lines like "localised 120 queries: 99.2% within one spacing (0.30 m) ...".
  std::string summary(const std::vector<int>& levels) const;

 private:
  std::vector<cv::Point2d> places_;
  double spacing_m_ = 1.0;
  std::size_t queries_ = 0;
  std::size_t outside_ = 0;
  std::size_t within_ = 0;
  std::size_t nearest_ = 0;
  double error_sum_m_ = 0.0;
  std::vector<std::size_t> contains_;
  std::vector<double> size_sum_;
  std::vector<double> heading_errors_;
};

}  // namespace omninav::memory
