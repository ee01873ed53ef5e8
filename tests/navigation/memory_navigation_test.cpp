// Navigation with real recognition (tests/support/room_navigation_map.hpp): whether an image
// matches a place of the map at all.
#include <gtest/gtest.h>

#include "omninav/core/errors.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::navigation {
namespace {

using testing::kRoomGridSpacing_m;
using testing::RoomNavigation;

TEST_F(RoomNavigation, MatchThresholdSeparatesTheRoomFromNoise) {
  // The limit: the ratio × the median link of the map (neighbouring places 30 cm apart, about
  // 2.1 grey levels per value).
  const double ratio = RouteParams{}.match_dissimilarity_ratio;
  EXPECT_GT(limit(), ratio * 1.8);
  EXPECT_LT(limit(), ratio * 2.4);
  // Views anywhere in the grid's area, between places and at any heading, match.
  double worst = 0.0;
  for (double x = 1.25; x < 3.9; x += 0.37) {
    for (double y = 1.05; y < 3.1; y += 0.29) {
      if (!map().world.is_free(x, y, 0.1)) continue;
      const cv::Mat view = map().renderer->render({x, y, 1.0, x * y, 0.0, 0.0});
      const memory::PlaceMatch match = match_image(map().localise, view, limit(), "view");
      worst = std::max(worst, match.dissimilarity_per_value);
      // ... and the place it matches is the nearest or next to it (8-neighbourhood).
      const CameraPose& place = map().grid[match.place].pose;
      EXPECT_LT(std::hypot(place.x_m - x, place.y_m - y), 1.5 * kRoomGridSpacing_m)
          << x << "," << y;
    }
  }
  EXPECT_LT(worst, 0.9 * limit());
  // Noise does not (about 1.65 links: with the zoo's ratio 1.5 by a tenth of the limit), and the
  // message names the image.
  cv::Mat noise(24, 180, CV_8UC3);
  cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 256);
  EXPECT_GT(map().localise(noise).best.front().dissimilarity_per_value, 1.05 * limit());
  try {
    match_image(map().localise, noise, limit(), "noise.png");
    ADD_FAILURE() << "noise matched a place";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("noise.png: matches no place"), std::string::npos)
        << error.what();
  }
  // A panorama of another height cannot be compared: an input error too, naming the image.
  try {
    match_image(map().localise, cv::Mat(30, 180, CV_8UC3, cv::Scalar::all(90)), limit(),
                "tall.png");
    ADD_FAILURE() << "a 30-row panorama matched a map of 24-row ones";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("tall.png: a panorama of 30 rows"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace omninav::navigation
