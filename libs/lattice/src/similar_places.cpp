#include "omninav/lattice/similar_places.hpp"

#include <algorithm>
#include <cstdint>
#include <opencv2/flann.hpp>
#include <tuple>

#include "omninav/core/best_k.hpp"
#include "omninav/core/statistics.hpp"

namespace omninav::lattice {
namespace {

// Places compared as one block: 64 rows of a few kilobytes each stay in the L2 cache.
constexpr Eigen::Index kBlockRows = 64;

// The index: FLANN's default of four randomised trees (Muja & Lowe 2009, whose experiments
// found 4-16 trees best), grown from a fixed seed.
constexpr int kIndexTrees = 4;
constexpr std::uint64_t kIndexSeed = 29;
// Leaves of the trees searched per place (FLANN's `checks`): of the exact 4 most similar places
// of each place on the benchmark's driven tours (700 and 1,900 places) it finds 85-89 % (32: 73-77
// %, 128: 93-96 % at 1.2 times the time); organise's lattice was the same within 0.02 spacings.
constexpr int kIndexChecks = 64;

// The order of "more similar": lower dissimilarity, then lower index.
bool more_similar(const SimilarPlace& x, const SimilarPlace& y) {
  return std::tie(x.dissimilarity, x.place) < std::tie(y.dissimilarity, y.place);
}

}  // namespace

PlaceDissimilarities::PlaceDissimilarities(const memory::VisualMemory& memory) {
  const auto count = static_cast<Eigen::Index>(memory.place_count());
  if (count == 0) return;
  const signature::ComponentWeights& weights = memory.parameters().weights;
  const int lines = memory.place(0).signature.lines();
  const int components = memory.place(0).signature.components;
  const Eigen::Index columns = static_cast<Eigen::Index>(lines) * components;
  magnitudes_ = decltype(magnitudes_)::Zero(count, (columns + 3) / 4 * 4);
  for (Eigen::Index place = 0; place < count; ++place) {
    const signature::Signature& signature = memory.place(place).signature;
    for (int line = 0; line < lines; ++line) {
      for (int k = 0; k < components; ++k) {
        // α_k·|a − b| = |α_k·a − α_k·b| for α_k ≥ 0: Eq. 6's weights folded into the magnitudes.
        const std::size_t at = signature.at(line, k);
        magnitudes_(place, static_cast<Eigen::Index>(at)) =
            static_cast<float>(weights[k]) * signature.magnitude[at];
      }
    }
  }
}

float PlaceDissimilarities::distance(Eigen::Index a, Eigen::Index b) const {
  return (magnitudes_.row(a) - magnitudes_.row(b)).cwiseAbs().sum();
}

double PlaceDissimilarities::operator()(int a, int b) const {
  return static_cast<double>(distance(a, b));
}

std::vector<std::vector<SimilarPlace>> PlaceDissimilarities::most_similar(int count) const {
  const Eigen::Index places = magnitudes_.rows();
  std::vector<std::vector<SimilarPlace>> best(static_cast<std::size_t>(places));
  const auto keep = static_cast<std::size_t>(
      std::clamp<Eigen::Index>(count, 0, std::max<Eigen::Index>(places - 1, 0)));
  if (keep == 0) return best;
  // Each place's `keep` most similar so far.
  using Kept = BestK<SimilarPlace, decltype(&more_similar)>;
  std::vector<Kept> kept(static_cast<std::size_t>(places), Kept(keep, &more_similar));
  const auto offer = [&](Eigen::Index a, Eigen::Index b, float dissimilarity) {
    kept[static_cast<std::size_t>(a)].offer(
        {static_cast<int>(b), static_cast<double>(dissimilarity)});
  };
  // Every pair once, block against block, so that the two blocks' rows stay in cache while
  // they are compared; each pair by distance(), so that a pair's value is the same here as from
  // operator().
  for (Eigen::Index rows = 0; rows < places; rows += kBlockRows) {
    const Eigen::Index rows_end = std::min(rows + kBlockRows, places);
    for (Eigen::Index columns = rows; columns < places; columns += kBlockRows) {
      const Eigen::Index columns_end = std::min(columns + kBlockRows, places);
      for (Eigen::Index a = rows; a < rows_end; ++a) {
        for (Eigen::Index b = std::max(columns, a + 1); b < columns_end; ++b) {
          const float dissimilarity = distance(a, b);
          offer(a, b, dissimilarity);
          offer(b, a, dissimilarity);
        }
      }
    }
  }
  for (std::size_t place = 0; place < best.size(); ++place) {
    best[place] = std::move(kept[place]).take_sorted();
  }
  return best;
}

std::vector<std::vector<SimilarPlace>> PlaceDissimilarities::most_similar_indexed(int count) const {
  const Eigen::Index places = magnitudes_.rows();
  std::vector<std::vector<SimilarPlace>> best(static_cast<std::size_t>(places));
  const int keep =
      static_cast<int>(std::clamp<Eigen::Index>(count, 0, std::max<Eigen::Index>(places - 1, 0)));
  if (keep == 0) return best;
  // A view of the magnitudes (cv::Mat has no constructor for const data; the index only reads).
  const cv::Mat features(static_cast<int>(places), static_cast<int>(magnitudes_.cols()), CV_32F,
                         const_cast<float*>(magnitudes_.data()));
  // FLANN draws its trees' split dimensions from this thread's cv::theRNG(): a fixed seed makes
  // the index, and so the lists, the same for the same map; the caller's generator is restored.
  const cv::RNG caller = cv::theRNG();
  cv::theRNG() = cv::RNG(kIndexSeed);
  cv::flann::Index index(features, cv::flann::KDTreeIndexParams(kIndexTrees),
                         cvflann::FLANN_DIST_L1);
  // One more than kept: each place finds itself (or a place with an identical signature).
  cv::Mat found, distances;
  index.knnSearch(features, found, distances, keep + 1, cv::flann::SearchParams(kIndexChecks));
  cv::theRNG() = caller;
  for (Eigen::Index a = 0; a < places; ++a) {
    std::vector<SimilarPlace>& list = best[static_cast<std::size_t>(a)];
    for (int rank = 0; rank <= keep; ++rank) {
      const int b = found.at<int>(static_cast<int>(a), rank);
      // The index's distances are summed in another order: each pair's value is distance()'s.
      if (b >= 0 && b != a) list.push_back({b, static_cast<double>(distance(a, b))});
    }
    std::sort(list.begin(), list.end(), more_similar);
    if (list.size() > static_cast<std::size_t>(keep)) list.resize(static_cast<std::size_t>(keep));
  }
  return best;
}

double PlaceDissimilarities::pair_quantile(double share, std::size_t max_pairs) const {
  return omninav::pair_quantile(static_cast<std::size_t>(magnitudes_.rows()), share, max_pairs,
                                [this](std::size_t a, std::size_t b) {
                                  return (*this)(static_cast<int>(a), static_cast<int>(b));
                                });
}

}  // namespace omninav::lattice
