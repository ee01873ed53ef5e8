#include "image_agreement.hpp"

#include <algorithm>
#include <string>

#include "omninav/core/statistics.hpp"
#include "omninav/memory/thumbnail.hpp"

namespace omninav::lattice {

namespace {

// Enough travelled links for a median that moves by little, few enough that a 10,000-place map
// pays for a few hundred thumbnails, not all of them.
constexpr std::size_t kSampledLinks = 200;

}  // namespace

ImageAgreement::ImageAgreement(const memory::VisualMemory& memory,
                               const std::vector<MeasuredLink>& travelled)
    : memory_(memory) {
  if (travelled.empty()) return;
  const std::size_t stride = std::max<std::size_t>(1, travelled.size() / kSampledLinks);
  std::vector<double> distances;
  for (std::size_t k = 0; k < travelled.size(); k += stride) {
    if (const std::optional<double> d =
            distance(travelled[k].places.first, travelled[k].places.second)) {
      distances.push_back(*d);
    }
  }
  if (!distances.empty()) unit_ = median(std::move(distances));
}

std::optional<double> ImageAgreement::ratio(int a, int b) {
  if (!available()) return std::nullopt;
  const std::optional<double> d = distance(a, b);
  if (!d) return std::nullopt;
  return *d / unit_;
}

std::optional<double> ImageAgreement::distance(int a, int b) {
  const compass::MinWarpingView* first = view(a);
  const compass::MinWarpingView* second = view(b);
  if (!first || !second || first->featureless() || second->featureless() ||
      first->size() != second->size()) {
    return std::nullopt;
  }
  return warping_.rotation_only(*first, *second).cost;
}

const compass::MinWarpingView* ImageAgreement::view(int place) {
  auto found = views_.find(place);
  if (found == views_.end()) {
    std::optional<compass::MinWarpingView> prepared;
    const std::vector<std::uint8_t>& png = memory_.place(place).thumbnail_png;
    if (!png.empty()) {
      const std::string name = "place " + std::to_string(place);
      const cv::Mat thumbnail = memory::decode_thumbnail(png, name);
      if (thumbnail.cols >= warping_.params().search_width_px) {
        prepared = warping_.prepare(thumbnail, name);
      }
    }
    found = views_.emplace(place, std::move(prepared)).first;
  }
  return found->second ? &*found->second : nullptr;
}

}  // namespace omninav::lattice
