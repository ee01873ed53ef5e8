#include "omninav/evaluation/home_vectors.hpp"

#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/memory/thumbnail.hpp"

namespace omninav::evaluation {

HomeVector home_vector_to_place(const compass::MinWarping& warping, const memory::Place& place,
                                const std::string& place_name, const cv::Mat& query,
                                const std::string& query_name) {
  require_panorama(query, query_name);
  const cv::Mat snapshot = memory::decode_thumbnail(place.thumbnail_png, place_name);
  const compass::MinWarpingResult result =
      warping.estimate_resized(warping.prepare(snapshot, place_name), query, query_name);
  HomeVector home;
  home.featureless = result.featureless;
  if (result.featureless) return home;
  home.direction_rad = result.home_rad;
  home.rotation_rad = result.rotation_rad;
  if (place.heading_rad) {
    // From the query back to the place: the reverse of the place's travel direction.
    home.world_direction_rad = wrap_angle(result.travel_world_rad(*place.heading_rad) + kPi);
  }
  return home;
}

double HomeVectorErrors::median_deg() const {
  return errors_rad.empty() ? std::numeric_limits<double>::quiet_NaN()
                            : rad_to_deg(quantile(errors_rad, 0.5));
}

double HomeVectorErrors::p90_deg() const {
  return errors_rad.empty() ? std::numeric_limits<double>::quiet_NaN()
                            : rad_to_deg(quantile(errors_rad, 0.9));
}

HomeVectorErrors grid_home_vector_errors(const compass::MinWarping& warping,
                                         const std::vector<io::Frame>& frames, double spacing_m) {
  std::vector<compass::MinWarpingView> views;
  std::vector<const io::Frame*> placed;
  for (const io::Frame& frame : frames) {
    if (!frame.truth) continue;
    views.push_back(warping.prepare(frame.image, frame.source));
    placed.push_back(&frame);
  }
  // 1 to 3 spacings, with a margin for the grid's rounding.
  const double nearest_m = 0.99 * spacing_m, farthest_m = 3.01 * spacing_m;
  HomeVectorErrors errors;
  for (std::size_t a = 0; a < placed.size(); ++a) {
    for (std::size_t b = a + 1; b < placed.size(); ++b) {
      const CameraPose& home = *placed[a]->truth;
      const CameraPose& here = *placed[b]->truth;
      const double distance_m = std::hypot(home.x_m - here.x_m, home.y_m - here.y_m);
      if (distance_m < nearest_m || distance_m > farthest_m) continue;
      const compass::MinWarpingResult result = warping.estimate(views[a], views[b]);
      if (result.featureless) {
        ++errors.featureless;
        continue;
      }
      const double truth = std::atan2(home.y_m - here.y_m, home.x_m - here.x_m) - here.heading_rad;
      errors.errors_rad.push_back(std::abs(signed_difference(result.home_rad, truth)));
    }
  }
  return errors;
}

}  // namespace omninav::evaluation
