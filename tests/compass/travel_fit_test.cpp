// The turn fitted together with the parallax of a displacement (travel_fit.hpp), against
// rendered pairs with a known turn and displacement.
#include "omninav/compass/travel_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "compass_test_support.hpp"
#include "omninav/compass/pair_matcher.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::compass {
namespace {

struct Place {
  std::string world;
  double x_m, y_m, z_m;
  double step_m;  // the displacement: 8 cm, the camera at 1 m
};

// The turn from the first pose to the second, measured by the pair's match alone and refined by
// the fit, in degrees, for a displacement of `step_m` towards `travel_deg` (world frame).
struct PairErrors {
  double match_deg = 0.0;
  double fit_deg = 0.0;
};

PairErrors turn_errors(const sim::Renderer& renderer, const Place& place, double heading_deg,
                       double turn_deg, double step_m, double travel_deg) {
  const CameraPose first{place.x_m, place.y_m, place.z_m, deg_to_rad(heading_deg), 0.0, 0.0};
  CameraPose second = first;
  second.x_m += step_m * std::cos(deg_to_rad(travel_deg));
  second.y_m += step_m * std::sin(deg_to_rad(travel_deg));
  second.heading_rad += deg_to_rad(turn_deg);
  const CompassFrame a(renderer.render(first), 0);
  const CompassFrame b(renderer.render(second), 1);
  PairMatcherParams params;
  const PairMatcher matcher(params);
  const PairMatch match = matcher.match(a, b);
  const TravelFit fit = fit_turn_and_travel(
      a.image(), b.image(), matcher.distance_function(a.width()).mask(), match.subpixel_shift_px);
  PairErrors errors;
  errors.match_deg = rad_to_deg(signed_difference(match.rotation_rad, deg_to_rad(turn_deg)));
  errors.fit_deg = rad_to_deg(
      signed_difference(-rotation_of_shift_px(fit.shift_px, a.width()), deg_to_rad(turn_deg)));
  return errors;
}

// Three families, eight directions of travel relative to the heading, a displacement and a 7.3°
// turn (not a whole number of columns at 360): the fitted turn is within 0.5° of the truth
// whatever the direction, and never worse than the match alone by more than a tenth of a
// degree. (The match alone errs by up to 1.6°. Not met, so not tested here: the house at
// (1.5, 3.6), where a sideways step between a near and a far wall leaves 2.4° with the bands,
// and the field at an insect's 10 cm, 3 cm steps: 1.05° against the match's 0.36°;
// docs/compass.md.)
TEST(TravelFit, TurnWithinHalfADegreeWhateverTheDirectionOfTravel) {
  const std::vector<Place> places{{"room", 2.5, 2.9, 1.0, 0.08},
                                  {"office", 7.5, 7.05, 1.0, 0.08},
                                  {"field", 11.25, 10.05, 1.0, 0.08}};
  for (const Place& place : places) {
    const sim::World world = sim::load_world(place.world, sim::WorldsConfig{});
    const sim::Renderer renderer(world, testing::render_params(360, 45));
    double worst_match = 0.0, worst_fit = 0.0;
    for (int k = 0; k < 8; ++k) {
      const double heading_deg = 30.0;
      const double travel_deg = heading_deg + 45.0 * k;
      const PairErrors errors =
          turn_errors(renderer, place, heading_deg, 7.3, place.step_m, travel_deg);
      worst_match = std::max(worst_match, std::abs(errors.match_deg));
      worst_fit = std::max(worst_fit, std::abs(errors.fit_deg));
      EXPECT_LE(std::abs(errors.fit_deg), 0.5) << place.world << " travel " << travel_deg;
      EXPECT_LE(std::abs(errors.fit_deg), std::abs(errors.match_deg) + 0.1)
          << place.world << " travel " << travel_deg;
    }
    std::cout << "  " << place.world << ": worst |turn error| match " << worst_match << "°, fit "
              << worst_fit << "°\n";
  }
}

// A pure rotation: the fit leaves no parallax and the exact turn (rolled copies: whole and
// fractional turns of a rendered panorama).
TEST(TravelFit, PureRollHasNoParallax) {
  const cv::Mat base = testing::render_room(2.2, 1.6, 0.0);
  const ColumnMask mask = ColumnMask::front_back(base.cols, deg_to_rad(60.0));
  for (const int shift : {-7, 0, 3, 12}) {
    const cv::Mat rolled = roll_columns(base, shift);
    // Started half a column off: the fit comes back to the roll.
    const TravelFit fit = fit_turn_and_travel(base, rolled, mask, -shift + 0.4);
    EXPECT_NEAR(fit.shift_px, -shift, 0.05) << shift;
    EXPECT_NEAR(fit.parallax_sin_px, 0.0, 0.05) << shift;
    EXPECT_NEAR(fit.parallax_cos_px, 0.0, 0.05) << shift;
    EXPECT_TRUE(fit.improved);
  }
}

}  // namespace
}  // namespace omninav::compass
