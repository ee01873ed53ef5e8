#pragma once
// Localising a query image in the visual memory (Menegatti et al. 2004, §2.2-2.3): the
// hierarchical search of signature/hierarchy.hpp over the map's places, then for the best
// places the query's heading relative to each (phases, Eq. 1) and, when the places have
// positions (lattice, else ground truth), a position estimate.

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "omninav/memory/visual_memory.hpp"
#include "omninav/signature/hierarchy.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::memory {

struct LocalisationParams {
  signature::HierarchyParams hierarchy;
  int top_k = 5;  // best places reported at the finest level
  // Beyond the papers, the fine level: the best `fine_candidates` places of the finest level
  // re-ranked by their rotational dissimilarity to the query (signature/dissimilarity.hpp:
  // magnitudes and phases, at the turn the phases give) beside their magnitude dissimilarity,
  // each relative to the least among them; 0 = off, the finest level's order stands. On the
  // zoo it loses in no localisation row of the full suite and gains most in the field seen from
  // 10 cm, but the navigator, which localises every step, then lost a trial in the quick
  // suite's room and went farther off the field's map (docs/memory.md): off by default.
  int fine_candidates = 0;
  // The rotational term's weight in the fine level's score, beside the magnitudes' 1 (each over
  // the least among the candidates). Chosen across the zoo (docs/memory.md): 1 gains more in
  // the field but loses look-alike desks in the office; 0.5 loses nowhere.
  double fine_rotational_weight = 0.5;

  // The ranges of memory.yaml's localisation section (the hierarchy's too). Throws UsageError
  // naming the key (core/param_check.hpp); the loader and Localiser's constructor call it.
  void check() const;
};

// Reads the `localisation:` section of memory.yaml (levels, candidate_similarity, max_probes,
// top_k, fine_candidates, fine_rotational_weight).
void load_localisation_params(const ConfigReader& section, LocalisationParams& params);

// One of the best places for a query, best first in Localisation::best.
struct PlaceMatch {
  PlaceIndex place = 0;
  double dissimilarity = 0.0;  // Eq. 6 (the map's weights) at the finest level
  double similarity = 0.0;     // Eq. 3, 0..1000, of the finest level's Dis
  // The finest level's dissimilarity (Eq. 2/6) per compared value (lines × components), grey
  // levels: unlike the similarity, which Eq. 3 rescales so that the best place always scores
  // 1000, it tells whether the query matches any place at all.
  double dissimilarity_per_value = 0.0;
  // heading(query) − heading(place), from the phases, counter-clockwise positive.
  double relative_heading_rad = 0.0;
  double heading_confidence = 0.0;
  // The query's heading in the map's frame, when the place has a heading.
  std::optional<double> heading_rad;
  // The fine level's rotational dissimilarity (Σ over lines × components), when it ran.
  std::optional<double> rotational_dissimilarity;
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
  // finest threshold, a finer guess between places (§2.3, footnote 1). The navigator's
  // look-ahead reads it.
  Eigen::Vector2d interpolated_position = Eigen::Vector2d::Zero();
  // Beyond the papers, a better guess between places: the mean of the positions of the best
  // place and of the matches among the searched best (top_k or fine_candidates, the more) that
  // lie within 1.5 spacings of it, weighted by (least Dis / Dis)^3 (Eq. 6). On the zoo it
  // brings the median error from 11-15 cm (the best place's) to 6-11 cm, where the estimate
  // above gives 6-26 cm and loses a third of the queries within one spacing in the office
  // (docs/memory.md).
  Eigen::Vector2d between_places = Eigen::Vector2d::Zero();
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
// spacing" of docs/design.md's evaluation). 1 for fewer than two points.
double typical_spacing(const std::vector<Eigen::Vector2d>& points);

class Localiser {
 public:
  // Builds the search index of `memory` (which must outlive the localiser) for params'
  // levels. Throws UsageError when the finest level exceeds the map's components.
  Localiser(const VisualMemory& memory, LocalisationParams params);

  // Pruned, coarse-to-fine. Throws UsageError when the query's signature does not match the
  // map's layout.
  Localisation localise(const signature::Signature& query) const;
  // A query panorama (8-bit grey or BGR, cv::Mat): its signature as the map's places were made
  // (signature_of), then localise(). Not const: the extraction reuses the localiser's buffers.
  Localisation localise(const cv::Mat& panorama, const std::string& what = "query");
  // The signature of a query panorama with the map's signature parameters. Throws InputError
  // naming `what` for an image that is not a panorama, or whose rows differ from the map's.
  signature::Signature signature_of(const cv::Mat& panorama, const std::string& what = "query");
  // Every level over every place (the oracle).
  Localisation localise_exhaustive(const signature::Signature& query) const;

  const signature::SignatureIndex& index() const { return index_; }
  const VisualMemory& memory() const { return memory_; }
  const LocalisationParams& params() const { return params_; }

 private:
  std::size_t searched_top() const;  // top_k, or the fine level's candidates when more
  Localisation finish(const signature::Signature& query, signature::SearchResult search) const;

  const VisualMemory& memory_;
  LocalisationParams params_;
  signature::SignatureIndex index_;
  signature::SignatureExtractor extractor_;  // the map's signature parameters
  std::optional<std::pair<PositionFrame, std::vector<Eigen::Vector2d>>> positions_;
  double spacing_m_ = 1.0;  // typical_spacing of the positions
};

}  // namespace omninav::memory
