#pragma once
// Steering towards a place by its image, as teach-and-repeat robots steer by the image of the
// next place of the taught route (bearnav: Krajník et al. 2010) and visual homing steers by a
// snapshot (Möller 2009): the home vector from the robot's view to the place's stored thumbnail,
// by min-warping (compass/min_warping.hpp). It points at the place from wherever the robot
// stands, so a robot beside its route heads back to it, where the direction stored at the last
// place would carry it on alongside.

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "omninav/compass/min_warping.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::navigation {

// How views are matched with places' thumbnails: min-warping's parameters (compass.yaml's
// min_warping section) and the rows of the panoramas (camera.yaml's panorama section).
struct SteeringParams {
  compass::MinWarpingParams warping;
  PanoramaGeometry panorama;
};

// What steering by images needs from a map: min-warping, and every place's stored thumbnail
// (PNG; empty for a place without one), shared by the navigations on that map.
struct PlaceSnapshots {
  std::shared_ptr<const compass::MinWarping> warping;
  std::vector<std::vector<std::uint8_t>> thumbnails_png;
};

// One navigation's steering: each place's thumbnail prepared for min-warping the first time
// the robot heads for it (a navigation meets few of a map's places; preparing them all would
// hold the whole map's scale planes).
class PlaceSteering {
 public:
  explicit PlaceSteering(std::shared_ptr<const PlaceSnapshots> snapshots);

  // Where `place` lies seen from the robot whose view is `view`: counter-clockwise from its
  // front. None when the map keeps no thumbnails, the place has none or one narrower than
  // min-warping's search, or the view or the thumbnail is featureless. Throws InputError when
  // the view is not a panorama.
  std::optional<double> direction_to(int place, const cv::Mat& view);
  // Min-warping from `place`'s thumbnail to `view` (named `what` in messages): its cost tells how
  // well the two match. None in the same cases as direction_to.
  std::optional<compass::MinWarpingResult> match(int place, const cv::Mat& view,
                                                 const std::string& what);

 private:
  std::shared_ptr<const PlaceSnapshots> snapshots_;
  std::unordered_map<int, compass::MinWarpingView> prepared_;
};

}  // namespace omninav::navigation
