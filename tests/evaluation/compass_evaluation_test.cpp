// The statistics of Tables 3-4 of the compass paper (compass_evaluation.hpp).
#include "omninav/evaluation/compass_evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::evaluation {
namespace {

using compass::CompassEstimate;

// An estimate drifting at 0.5°/s while the camera moves at 0.2 m/s: the robust slopes are
// 0.5°/s and 2.5°/m, the error stays wrapped across the ±180° seam.
TEST(CompassEvaluation, SlopesAgainstTimeAndDistanceAndWrappedErrors) {
  std::vector<CompassEstimate> estimates;
  std::vector<CompassTruth> truth;
  for (int i = 0; i < 50; ++i) {
    const double t = 0.1 * i;
    const double truth_heading = deg_to_rad(170.0 + 20.0 * t);  // crosses 180°
    CompassEstimate estimate;
    estimate.frame_index = i;
    estimate.heading_rad = truth_heading + deg_to_rad(0.5 * t + (i == 20 ? 30.0 : 0.0));
    estimates.push_back(estimate);
    truth.push_back({wrap_angle(truth_heading), Eigen::Vector2d(0.2 * t, 1.0), t});
  }
  const CompassEvaluation evaluation = evaluate_compass(estimates, truth, 7);
  EXPECT_EQ(evaluation.reference_frames, 7);
  EXPECT_EQ(evaluation.total_frames, 50);
  ASSERT_TRUE(evaluation.slope_deg_per_s);
  ASSERT_TRUE(evaluation.slope_deg_per_m);
  EXPECT_NEAR(*evaluation.slope_deg_per_s, 0.5, 1e-9);  // the outlier at frame 20 ignored
  EXPECT_NEAR(*evaluation.slope_deg_per_m, 2.5, 1e-9);
  EXPECT_NEAR(evaluation.error_deg.max_abs, 31.0, 1e-9);
  EXPECT_NEAR(evaluation.final_error_deg, 0.5 * 4.9, 1e-9);
  EXPECT_NEAR(evaluation.distance_m.back(), 0.98, 1e-12);
  const std::string table = format_compass_table("TEST", "Atm 0.6", evaluation);
  EXPECT_NE(table.find("7 (50)"), std::string::npos) << table;
  EXPECT_NE(table.find("Theil-Sen"), std::string::npos) << table;
}

TEST(CompassEvaluation, OnTheSpotHasNoSlopePerMetreAndSizesMustMatch) {
  std::vector<CompassEstimate> estimates(3);
  std::vector<CompassTruth> truth(3);
  const CompassEvaluation evaluation = evaluate_compass(estimates, truth, 1);
  EXPECT_FALSE(evaluation.slope_deg_per_m);
  EXPECT_FALSE(evaluation.slope_deg_per_s);  // no times
  EXPECT_NE(format_compass_table("X", "Fx 0", evaluation).find("n/a"), std::string::npos);
  truth.pop_back();
  EXPECT_THROW(evaluate_compass(estimates, truth, 1), UsageError);
  EXPECT_THROW(evaluate_compass({}, {}, 0), UsageError);
}

}  // namespace
}  // namespace omninav::evaluation
