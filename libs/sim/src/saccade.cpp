#include "saccade.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::sim {

void SaccadeParams::check() const {
  check_range("stretch_s", stretch_s, 0.01, 1e4);
  check_range_deg("saccade_min_deg", saccade_min_rad, 0.0, 180.0);
  check_range_deg("saccade_max_deg", saccade_max_rad, rad_to_deg(saccade_min_rad), 180.0);
  // Slower than 1 °/s is no saccade; faster than 10⁵ °/s turns half a circle between frames.
  check_range_deg("saccade_rate_deg_s", saccade_rate_rad_s, 1.0, 1e5);
  check_range("stop_share", stop_share, 0.0, 1.0);
  check_range("stop_s", stop_s, 0.0, 1e4);
  check_range_deg("spot_turn_rate_deg_s", spot_turn_rate_rad_s, 1.0, 1e5);
}

namespace {

[[noreturn]] void throw_too_many(std::size_t max_poses) {
  throw UsageError("more than " + std::to_string(max_poses) + " poses");
}

// The walker, frame by frame: every frame interval is a step straight ahead (the heading
// wobbling about it), a standstill, or a turn on the spot, never a turn and a step at once.
class SaccadeWalker {
 public:
  SaccadeWalker(const World& world, const FreeRouteSettings& route, const SaccadeParams& params,
                double fps, std::size_t max_poses)
      : world_(world),
        route_(route),
        params_(params),
        fps_(fps),
        max_poses_(max_poses),
        rng_(static_cast<std::uint64_t>(route.seed) * 2654435761ULL + 13),
        wobble_(route.wobble_rad, route.wobble_period_s, rng_),
        x_(route.x),
        y_(route.y),
        travel_(route.heading_rad),
        lookahead_m_(lookahead_m(route.speed_m_s, fps)),
        last_pose_(route.duration_s > 0.0 ? std::floor(route.duration_s * fps + 1e-9) : -1.0) {}

  std::vector<TimedPose> walk() {
    heading_ = travel_ + wobble_.offset_rad();
    add_pose();
    while (!done()) {
      stretch();
      if (done()) break;
      if (rng_.uniform(0.0, 1.0) < params_.stop_share) {
        const double stop_s = params_.stop_s * rng_.uniform(0.5, 1.5);
        for (int frame = 0; frame < std::lround(stop_s * fps_) && !done(); ++frame) add_pose();
        turn(rng_.uniform(-kPi, kPi), params_.spot_turn_rate_rad_s);
      } else {
        const double sign = rng_.uniform(0, 2) == 0 ? -1.0 : 1.0;
        turn(sign * rng_.uniform(params_.saccade_min_rad, params_.saccade_max_rad),
             params_.saccade_rate_rad_s);
      }
    }
    return std::move(poses_);
  }

 private:
  // A straight stretch: ends after its drawn time, or early where the way ahead is not clear.
  void stretch() {
    const double seconds = params_.stretch_s * -std::log(1.0 - rng_.uniform(0.0, 1.0));
    const long frames = std::max(1L, std::lround(seconds * fps_));
    const double step = route_.speed_m_s / fps_;
    for (long frame = 0; frame < frames && !done(); ++frame) {
      if (turn_to_clear_from(travel_) != 0.0) return;
      x_ += step * std::cos(travel_);
      y_ += step * std::sin(travel_);
      travelled_m_ += step;
      wobble_.advance(fps_, rng_);
      heading_ = travel_ + wobble_.offset_rad();
      add_pose();
    }
  }

  // Turns on the spot by `angle` (rad) and on, as far as needed, until the way ahead is clear,
  // at `rate` (rad/s) at most: in whole frames, each the same share of the turn.
  void turn(double angle, double rate_rad_s) {
    const double wanted = wrap_angle(travel_ + angle);
    const double further = turn_to_clear_from(wanted);
    const double total = angle + further;
    travel_ = wrap_angle(wanted + further);
    const double from = heading_;
    const long frames = std::lround(std::ceil(std::abs(total) / (rate_rad_s / fps_) - 1e-9));
    for (long frame = 1; frame <= frames && !done(); ++frame) {
      heading_ = from + total * frame / frames;
      add_pose();
    }
  }

  // The smallest turn from `direction` after which the way ahead is clear (free_space.hpp).
  double turn_to_clear_from(double direction) const {
    // A walker closer than clearance_m to something, at its start, keeps out of it only.
    const double keep = world_.is_free(x_, y_, route_.clearance_m) ? route_.clearance_m : 0.0;
    const std::optional<double> turn = turn_to_clear(world_, x_, y_, lookahead_m_, keep, direction);
    if (!turn) {
      throw UsageError("boxed in at x " + fixed(x_, 2) + ", y " + fixed(y_, 2) +
                       " m: no direction is clear by clearance_m " + general(keep) + " m");
    }
    return *turn;
  }

  bool done() const {
    if (last_pose_ >= 0.0) return static_cast<double>(poses_.size()) > last_pose_;
    return travelled_m_ >= route_.length_m - 1e-9;
  }

  void add_pose() {
    if (poses_.size() >= max_poses_) throw_too_many(max_poses_);
    const double time_s = static_cast<double>(poses_.size()) / fps_;
    poses_.push_back({time_s, {x_, y_, 0.0, wrap_angle(heading_), 0.0, 0.0}, {}, {}});
  }

  const World& world_;
  const FreeRouteSettings& route_;
  const SaccadeParams& params_;
  const double fps_;
  const std::size_t max_poses_;
  cv::RNG rng_;
  Wobble wobble_;
  double x_, y_, travel_, heading_ = 0.0;
  double travelled_m_ = 0.0;
  const double lookahead_m_;
  const double last_pose_;  // the last pose's index when the route is timed, else -1
  std::vector<TimedPose> poses_;
};

}  // namespace

std::vector<TimedPose> saccade_route(const World& world, const FreeRouteSettings& route,
                                     const SaccadeParams& params, double fps,
                                     std::size_t max_poses) {
  params.check();
  // Refused before walking when even a route of stretches alone would have too many poses.
  const double fewest_poses =
      route.duration_s > 0.0 ? route.duration_s * fps : route.length_m / (route.speed_m_s / fps);
  if (fewest_poses >= static_cast<double>(max_poses)) throw_too_many(max_poses);
  return SaccadeWalker(world, route, params, fps, max_poses).walk();
}

}  // namespace omninav::sim
