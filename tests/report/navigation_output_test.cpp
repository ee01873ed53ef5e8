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
  step.recognised = true;
  result.steps.push_back(step);
  // The next view: the belief has spread (lost) while the robot homes.
  step.index = 4;
  step.recognised = false;
  step.lost = true;
  step.phase = navigation::NavigationPhase::kHoming;
  result.steps.push_back(step);

  std::ostringstream csv;
  write_navigation_steps_header(csv, false);
  write_navigation_steps(csv, result, 80.0 * M_PI / 180.0);
  EXPECT_EQ(csv.str(),
            "step,x_m,y_m,heading_deg,place,similarity,dissimilarity_per_value,"
            "heading_estimate_deg,heading_error_deg,turn_deg,jump,recognised,phase,lost\n"
            "3,0.5,-1.25,-90,12,812.5,0.25,-180,-10,30,0,1,route,0\n"
            "4,0.5,-1.25,-90,12,812.5,0.25,-180,-10,30,0,0,homing,1\n");
  // With the distance outside the mapped area, one value per step.
  std::ostringstream with_outside;
  write_navigation_steps_header(with_outside, true, true);
  write_navigation_steps(with_outside, result, 80.0 * M_PI / 180.0, 7, {0.0, 0.375});
  EXPECT_EQ(with_outside.str(),
            "trial,step,x_m,y_m,heading_deg,place,similarity,dissimilarity_per_value,"
            "heading_estimate_deg,heading_error_deg,turn_deg,jump,recognised,phase,lost,"
            "outside_m\n"
            "7,3,0.5,-1.25,-90,12,812.5,0.25,-180,-10,30,0,1,route,0,0\n"
            "7,4,0.5,-1.25,-90,12,812.5,0.25,-180,-10,30,0,0,homing,1,0.375\n");
}

}  // namespace
}  // namespace omninav::report
