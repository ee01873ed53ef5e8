#pragma once
// The dissimilarities the lattice needs between the places of a visual memory (Eq. 2/6 of
// Menegatti et al. 2004, the map's own components and weights), without the n × n matrix of
// all pairs: 10,000 places would make that 10⁸ values (800 MB) and 5·10⁷ comparisons. The
// lattice needs each place's few most similar places (springs, motions, its local step), the
// pairs of consecutive places, and one statistic of all pairs (the plateau of Fig. 7).
//
// The map made by driving searches an index instead (most_similar_indexed): there, the most
// similar places propose springs and revisits that the pose graph may still reject, so a place
// missed now and then costs little, and no work grows with the square of the places.
//
// Storage: one contiguous row-major float matrix, a row per place holding its α_k·|F_y(k)|
// (27 MB for 10,000 places of 45 lines × 15 components). The most similar places are found by
// comparing every pair once, block of places against block, with vectorised L1 sums. We tried
// to prune pairs by lower bounds and measured how many were still compared on a rendered
// 787-place grid (24 places kept per place): the first two components' share of Eq. 2 (the
// first level of §2.3's hierarchy) ruled out 3 % of the pairs, the triangle inequality over
// 49 farthest-point pivots 10 %. Dissimilarity grows slowly enough with distance that a place's
// 24th most similar place is as unlike it as most of the map, so bounds rarely exclude a pair.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice {

struct SimilarPlace {
  int place = 0;
  double dissimilarity = 0.0;
};

// The first `count` places of a most-similar-first list (all of it when shorter, none for
// count ≤ 0).
inline std::span<const SimilarPlace> most_similar_first(const std::vector<SimilarPlace>& ranked,
                                                        int count) {
  return {ranked.data(), std::min<std::size_t>(std::max(count, 0), ranked.size())};
}

class PlaceDissimilarities {
 public:
  explicit PlaceDissimilarities(const memory::VisualMemory& memory);

  int place_count() const { return static_cast<int>(magnitudes_.rows()); }

  // Eq. 2/6 between places a and b (summed in single precision, as the localiser does).
  double operator()(int a, int b) const;

  // Each place's `count` most similar other places (fewer when the map has fewer), most similar
  // first, ties broken by the lower place index: exactly what ranking every pair would give.
  std::vector<std::vector<SimilarPlace>> most_similar(int count) const;

  // The same, searched without comparing every pair: an approximate nearest-neighbour index
  // (FLANN's randomised k-d trees, Muja & Lowe 2009, under Eq. 6's L1 distance) that compares
  // each place with a fixed number of others. A list may miss a few of the exact one's places
  // (then it holds the next most similar instead); its dissimilarities are operator()'s, and it
  // is the same for the same map.
  std::vector<std::vector<SimilarPlace>> most_similar_indexed(int count) const;

  // The `share` quantile (core/statistics.hpp's rank) of the dissimilarity of all pairs when
  // there are at most `max_pairs` of them, else of about `max_pairs` pairs spread evenly over
  // the map (every place paired at evenly spaced index offsets): the same for the same map.
  double pair_quantile(double share, std::size_t max_pairs) const;

 private:
  float distance(Eigen::Index a, Eigen::Index b) const;

  // n × columns, padded with zeros to whole SIMD packets (4 floats) so that every row starts on
  // a packet boundary and Eigen sums every row in the same order; zeros add nothing to L1.
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> magnitudes_;
};

}  // namespace omninav::lattice
