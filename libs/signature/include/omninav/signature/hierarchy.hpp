#pragma once
// Hierarchical localisation (Menegatti et al. 2004, §2.3, Figs. 9-10): comparing only the
// first few Fourier components matches a query with every place of a wide neighbourhood,
// comparing more narrows it down. Level l compares the first m_l components (e.g. 2, 5, 15);
// its candidate set is the places whose similarity (Eq. 3) reaches a threshold.
//
// Search is coarse-to-fine: level 1 compares the query with every place, each further level
// only with the previous level's candidates, adding the next components' terms to the sums
// already made (Eq. 2 is a sum over k, so Dis at m_l = Dis at m_{l−1} + the terms of
// m_{l−1} ≤ k < m_l). Storage is laid out for that: one contiguous row-major float matrix per
// level (a "band"), one row per place, holding α_k·|F_y(k)| for m_{l−1} ≤ k < m_l and every
// line y, so that a level is a vectorised L1 over a matrix block (Eq. 6's weights are folded
// into the stored magnitudes: α|a − b| = |αa − αb| for α ≥ 0).
//
// Similarity at a level rescales Dis over the whole reference set (Eq. 3, dissimilarity.hpp).
// At pruned levels the places outside the candidates were not compared: Min is taken over the
// candidates (the best place is among them unless pruning lost it) and Max over the candidates
// and a few "probes", the places most unlike the query at level 1, which are carried through
// every level for that purpose. The exhaustive search computes every level over every place
// and is the oracle the pruned one is tested against.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::signature {

struct HierarchyParams {
  // Components compared at each level, increasing; Menegatti et al. 2004, §2.1 Fig. 6 compares 2, 5
  // and 15 (and more); the finest must not exceed the map's signature components.
  std::vector<int> levels{2, 5, 15};
  // Similarity (Eq. 3, 0..1000) a place must reach at a level to be a candidate, the same at
  // every level: higher levels are more discriminating, so their sets shrink (Fig. 9).
  double candidate_similarity = 800.0;
  // Places carried through every level to estimate Max Dis (see above).
  int max_probes = 16;

  // The ranges of memory.yaml's localisation.levels (increasing, each ≥ 1),
  // candidate_similarity (0..1000) and max_probes (0..100000). Throws UsageError naming the key
  // (core/param_check.hpp); the loader and memory::Localiser's constructor call it.
  void check() const;
};

// Reads `levels` ("2,5,15"), `candidate_similarity` and `max_probes` of a `localisation:`
// section. Throws ConfigError naming the key.
void load_hierarchy_params(const ConfigReader& section, HierarchyParams& params);

// "2,5,15" → {2, 5, 15}; throws UsageError naming `where` unless strictly increasing and ≥ 1.
std::vector<int> parse_levels(const std::string& text, const std::string& where);

struct Candidate {
  std::uint32_t place = 0;  // index in the order places were added
  float dissimilarity = 0;  // Eq. 2/6 at this level
  float similarity = 0;     // Eq. 3, 0..1000
};

struct LevelResult {
  int components = 0;
  std::size_t evaluated = 0;     // places compared at this level
  double min_dissimilarity = 0;  // the Eq. 3 range used
  double max_dissimilarity = 0;
  std::vector<Candidate> candidates;  // similarity ≥ threshold, best (lowest Dis) first
};

struct SearchResult {
  std::vector<LevelResult> levels;
  // The best top_k places at the finest level among those compared there, best first.
  std::vector<Candidate> best;
};

class SignatureIndex {
 public:
  // Places' signatures have `rows` × `channels` lines and at least levels.back() components.
  SignatureIndex(int rows, int channels, std::vector<int> levels, ComponentWeights weights = {});

  // Appends a place; returns its index. Throws UsageError on a layout mismatch or too few
  // components.
  std::uint32_t add(const Signature& signature);
  void reserve(std::size_t places);

  std::size_t size() const { return size_; }
  const std::vector<int>& levels() const { return levels_; }
  int lines() const { return lines_; }

  // Coarse-to-fine (pruned) search. `top_k` ≥ 1.
  SearchResult search(const Signature& query, double candidate_similarity, std::size_t top_k,
                      int max_probes = 16) const;
  // Every level over every place (the oracle, and the pictures of Figs. 8-10).
  SearchResult search_exhaustive(const Signature& query, double candidate_similarity,
                                 std::size_t top_k) const;
  // Dis at level `level` (0-based) from the query to every place.
  Eigen::VectorXf dissimilarities(const Signature& query, std::size_t level) const;

  // Bytes held by the level matrices (capacity included).
  std::size_t bytes() const;

 private:
  using Band = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  void check(const Signature& signature, const char* what) const;
  // The query's weighted magnitudes laid out like band `level`.
  Eigen::RowVectorXf query_band(const Signature& query, std::size_t level) const;
  float band_distance(std::size_t level, const Eigen::RowVectorXf& q, std::uint32_t place) const;

  int rows_;
  int channels_;
  int lines_;
  std::vector<int> levels_;
  ComponentWeights weights_;
  std::vector<Band> bands_;  // capacity rows; the first size_ are places
  std::size_t size_ = 0;
};

}  // namespace omninav::signature
