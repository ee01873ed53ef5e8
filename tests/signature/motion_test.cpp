#include "omninav/signature/motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "rendered_room.hpp"

namespace omninav::signature {
namespace {

using testing::render;

struct Pair {
  double x0, y0, h0_deg, x1, y1, h1_deg;
  // Direction of travel seen from the first pose, counter-clockwise from its front.
  double bearing_deg() const {
    return signed_difference_deg(rad_to_deg(std::atan2(y1 - y0, x1 - x0)), h0_deg);
  }
};

MotionEstimate estimate(const Pair& pair, int components = 15) {
  SignatureExtractor extractor({15, ColourMode::kLuminance});
  return estimate_motion(extractor.compute(render(pair.x0, pair.y0, pair.h0_deg)),
                         extractor.compute(render(pair.x1, pair.y1, pair.h1_deg)), components);
}

TEST(Motion, ForwardSidewaysAndBackwardSteps) {
  // 30 cm steps from one place in four directions relative to the robot, which keeps its
  // heading: ahead is 0, its left +90°.
  for (double relative_deg : {0.0, 90.0, 180.0, -90.0, 45.0}) {
    const double heading_deg = 20.0;
    const double direction = deg_to_rad(heading_deg + relative_deg);
    const Pair pair{2.6,
                    2.4,
                    heading_deg,
                    2.6 + 0.3 * std::cos(direction),
                    2.4 + 0.3 * std::sin(direction),
                    heading_deg};
    const MotionEstimate m = estimate(pair);
    EXPECT_TRUE(m.valid) << relative_deg;
    EXPECT_LT(std::fabs(signed_difference_deg(rad_to_deg(m.bearing_rad), pair.bearing_deg())), 30.0)
        << "moving " << relative_deg << " deg from the front";
    EXPECT_LT(std::fabs(rad_to_deg(m.turn_rad)), 3.0);
  }
}

TEST(Motion, RandomShortStepsWithTurns) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> x(1.0, 5.0), y(1.0, 4.0), angle(-180.0, 180.0),
      turn(-30.0, 30.0), step(0.2, 0.4);
  const sim::World& world = testing::room();
  std::vector<double> errors;
  int valid = 0;
  while (errors.size() < 40) {
    const double x0 = x(random), y0 = y(random), direction = deg_to_rad(angle(random));
    const double d = step(random);
    const Pair pair{
        x0, y0, angle(random), x0 + d * std::cos(direction), y0 + d * std::sin(direction), 0.0};
    Pair turned = pair;
    turned.h1_deg = pair.h0_deg + turn(random);
    if (!world.is_free(pair.x0, pair.y0, 0.2) || !world.is_free(pair.x1, pair.y1, 0.2)) continue;
    const MotionEstimate m = estimate(turned);
    if (m.valid) ++valid;
    errors.push_back(
        std::fabs(signed_difference_deg(rad_to_deg(m.bearing_rad), turned.bearing_deg())));
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  const double p90 = errors[errors.size() * 9 / 10];
  RecordProperty("median_error_deg", std::to_string(median));
  RecordProperty("p90_error_deg", std::to_string(p90));
  std::cout << "motion bearing error over " << errors.size() << " steps: median " << median
            << " deg, 90th percentile " << p90 << " deg, valid " << valid << "\n";
  // Measured 7.6° and 14.5° (seed 11); the paper reports about 10% (§3.4).
  EXPECT_LT(median, 12.0);
  EXPECT_LT(p90, 25.0);
}

TEST(Motion, RefusesMismatchedSignatures) {
  const Signature a = compute_signature(render(2.0, 2.0, 0.0), {15, ColourMode::kLuminance});
  const Signature b = compute_signature(render(2.0, 2.0, 0.0), {15, ColourMode::kPerChannel});
  EXPECT_THROW(estimate_motion(a, b), UsageError);
  EXPECT_THROW(estimate_motion(a, a, 1), UsageError);
}

TEST(Motion, NoTranslationIsNotAValidBearing) {
  const Signature a = compute_signature(render(2.5, 2.0, 10.0), {15, ColourMode::kLuminance});
  const Signature b = compute_signature(render(2.5, 2.0, 40.0), {15, ColourMode::kLuminance});
  const MotionEstimate m = estimate_motion(a, b);
  EXPECT_NEAR(rad_to_deg(m.turn_rad), 30.0, 0.5);
  EXPECT_LT(m.parallax_rad, 0.01);
  EXPECT_FALSE(m.valid);
}

}  // namespace
}  // namespace omninav::signature
