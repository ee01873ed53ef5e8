// A navigation run's steps.csv against a hand-built run.
#include "omninav/report/navigation_output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace omninav::report {
namespace {

TEST(NavigationOutput, OneRowPerStepWithTheHeadingErrorInTheWorld) {
  navigation::NavigationResult result;
  navigation::NavigationStep step;
  step.index = 3;
  step.truth = CameraPose{0.5, -1.25, 1.0, -M_PI / 2, 0.0, 0.0};
  step.match = memory::PlaceMatch{};
  step.match->place = 12;
  step.match->similarity = 812.5;
  step.match->dissimilarity_per_value = 0.25;
  step.heading_estimate_rad = -M_PI;  // -180° in the lattice; +80° to the world: -100°
  step.turn_rad = M_PI / 6;
  result.steps.push_back(step);

  std::ostringstream csv;
  write_navigation_steps_header(csv, false);
  write_navigation_steps(csv, result, 80.0 * M_PI / 180.0);
  EXPECT_EQ(csv.str(),
            "step,x_m,y_m,heading_deg,place,similarity,dissimilarity_per_value,"
            "heading_estimate_deg,heading_error_deg,turn_deg,jump\n"
            "3,0.5,-1.25,-90,12,812.5,0.25,-180,-10,30,0\n");
}

}  // namespace
}  // namespace omninav::report
