#include "free_space.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"

namespace omninav::sim {

void move_to_free_point(const World& world, double clearance_m, double& x, double& y) {
  const double centre_x = x, centre_y = y;
  for (int ring = 1; ring < 400 && !world.is_free(x, y, clearance_m); ++ring) {
    for (int k = 0; k < 8 * ring && !world.is_free(x, y, clearance_m); ++k) {
      const double angle = kTwoPi * k / (8 * ring);
      x = centre_x + 0.05 * ring * std::cos(angle);
      y = centre_y + 0.05 * ring * std::sin(angle);
    }
  }
}

double lookahead_m(double speed_m_s, double fps) {
  return std::max(0.5 * speed_m_s, 2.0 * speed_m_s / fps);
}

std::optional<double> turn_to_clear(const World& world, double x, double y, double lookahead_m,
                                    double keep_m, double direction) {
  const auto clear = [&](double turn) {
    const double towards = wrap_angle(direction + turn);
    return world.segment_is_free(x, y, x + lookahead_m * std::cos(towards),
                                 y + lookahead_m * std::sin(towards), keep_m);
  };
  if (clear(0.0)) return 0.0;
  for (int k = 1; k <= 18; ++k) {
    for (const double side : {1.0, -1.0}) {
      const double turn = side * k * deg_to_rad(10.0);
      if (clear(turn)) return turn;
    }
  }
  return std::nullopt;
}

Wobble::Wobble(double amplitude_rad, double period_s, cv::RNG& rng)
    : mean_amplitude_rad_(amplitude_rad),
      mean_period_s_(period_s),
      phase_(rng.uniform(0.0, kTwoPi)),
      amplitude_(amplitude_rad),
      rate_(kTwoPi / period_s) {}

void Wobble::advance(double fps, cv::RNG& rng) {
  const double previous = phase_;
  phase_ += rate_ / fps;
  if (std::floor(phase_ / kTwoPi) != std::floor(previous / kTwoPi)) {
    amplitude_ = mean_amplitude_rad_ * rng.uniform(0.7, 1.3);
    rate_ = kTwoPi / (mean_period_s_ * rng.uniform(0.7, 1.3));
  }
}

}  // namespace omninav::sim
