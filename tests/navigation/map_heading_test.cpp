// When the compass re-aligns on a map's reading (navigation::realigns), on constructed readings.
#include "omninav/navigation/map_heading.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "omninav/core/angles.hpp"

namespace omninav::navigation {
namespace {

MapHeading reading(double heading_deg, double spread_deg) {
  return {3, deg_to_rad(heading_deg), deg_to_rad(spread_deg), 1.0};
}

TEST(Realigns, WhenTheMapIsSurerThanTheCompassAndAgreesWithIt) {
  const double compass = deg_to_rad(100.0);
  // Surer (spread 1° against the compass's 4°) and within 5 combined sigmas (5·4.1° = 20.6°).
  EXPECT_TRUE(realigns(reading(118.0, 1.0), compass, deg_to_rad(4.0), true));
  // Across the ±180° seam: 100° + 360° is the same heading.
  EXPECT_TRUE(realigns(reading(100.0 - 360.0 + 5.0, 1.0), compass, deg_to_rad(4.0), true));
  // Not surer than the compass: its sigma stands.
  EXPECT_FALSE(realigns(reading(101.0, 5.0), compass, deg_to_rad(4.0), true));
  // Beyond the gate: a look-alike place facing another way.
  EXPECT_FALSE(realigns(reading(125.0, 1.0), compass, deg_to_rad(4.0), true));
  EXPECT_TRUE(realigns(reading(125.0, 1.0), compass, deg_to_rad(4.0), true, {.gate_sigmas = 7.0}));
  // One recognised place alone has no spread: never.
  EXPECT_FALSE(realigns(reading(100.0, std::numeric_limits<double>::infinity()), compass,
                        deg_to_rad(50.0), true));
  EXPECT_FALSE(realigns(reading(100.0, std::numeric_limits<double>::infinity()), compass,
                        deg_to_rad(50.0), false));
  // A compass not in the map's frame yet takes any reading with a spread.
  EXPECT_TRUE(realigns(reading(-150.0, 3.0), compass, 0.0, false));
}

}  // namespace
}  // namespace omninav::navigation
