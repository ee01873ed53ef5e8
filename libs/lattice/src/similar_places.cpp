#include "omninav/lattice/similar_places.hpp"

#include <algorithm>
#include <tuple>

#include "omninav/core/best_k.hpp"
#include "omninav/core/statistics.hpp"

namespace omninav::lattice {
namespace {

// Places compared as one block: 64 rows of a few kilobytes each stay in the L2 cache.
constexpr Eigen::Index kBlockRows = 64;

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

double PlaceDissimilarities::pair_quantile(double share, std::size_t max_pairs) const {
  return omninav::pair_quantile(static_cast<std::size_t>(magnitudes_.rows()), share, max_pairs,
                                [this](std::size_t a, std::size_t b) {
                                  return (*this)(static_cast<int>(a), static_cast<int>(b));
                                });
}

}  // namespace omninav::lattice
