#include "omninav/navigation/place_steering.hpp"

#include <string>
#include <utility>

#include "omninav/memory/thumbnail.hpp"

namespace omninav::navigation {

PlaceSteering::PlaceSteering(std::shared_ptr<const PlaceSnapshots> snapshots)
    : snapshots_(std::move(snapshots)) {}

std::optional<double> PlaceSteering::direction_to(int place, const cv::Mat& view) {
  const std::optional<compass::MinWarpingResult> result = match(place, view, "the robot's view");
  if (!result) return std::nullopt;
  return result->home_rad;
}

std::optional<compass::MinWarpingResult> PlaceSteering::match(int place, const cv::Mat& view,
                                                              const std::string& what) {
  if (!snapshots_ || !snapshots_->warping || place < 0 ||
      static_cast<std::size_t>(place) >= snapshots_->thumbnails_png.size() ||
      snapshots_->thumbnails_png[place].empty()) {
    return std::nullopt;
  }
  const compass::MinWarping& warping = *snapshots_->warping;
  auto prepared = prepared_.find(place);
  if (prepared == prepared_.end()) {
    const std::string name = "place " + std::to_string(place);
    const cv::Mat snapshot = memory::decode_thumbnail(snapshots_->thumbnails_png[place], name);
    // A thumbnail narrower than the search (memory.yaml's thumbnail_width_px below
    // min_warping.search_width_px) cannot be matched: the plan's directions steer instead.
    if (snapshot.cols < warping.params().search_width_px) return std::nullopt;
    prepared = prepared_.emplace(place, warping.prepare(snapshot, name)).first;
  }
  compass::MinWarpingResult result = warping.estimate_resized(prepared->second, view, what);
  if (result.featureless) return std::nullopt;
  return result;
}

}  // namespace omninav::navigation
