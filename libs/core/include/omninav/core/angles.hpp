#pragma once
// The one set of angle helpers used everywhere (docs/design.md, Conventions: Angles).
// Radians inside the libraries, degrees only at the edges; never compare raw angles across
// the ±180° seam, difference them with signed_difference().

#include <cmath>
#include <numbers>

namespace omninav {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

constexpr double deg_to_rad(double deg) {
  return deg * (kPi / 180.0);
}
constexpr double rad_to_deg(double rad) {
  return rad * (180.0 / kPi);
}

// Wraps to (-π, π]. Exact for inputs already in range, so that wrap(wrap(a)) == wrap(a).
inline double wrap_angle(double rad) {
  if (rad > -kPi && rad <= kPi) return rad;
  double wrapped = std::remainder(rad, kTwoPi);  // in [-π, π]
  if (wrapped <= -kPi) wrapped += kTwoPi;
  return wrapped;
}

// Wraps to (-180°, 180°].
inline double wrap_angle_deg(double deg) {
  if (deg > -180.0 && deg <= 180.0) return deg;
  double wrapped = std::remainder(deg, 360.0);
  if (wrapped <= -180.0) wrapped += 360.0;
  return wrapped;
}

// The signed angle that takes `from` to `to`, in (-π, π]: to ≈ from + signed_difference(to, from).
inline double signed_difference(double to, double from) {
  return wrap_angle(to - from);
}

inline double signed_difference_deg(double to, double from) {
  return wrap_angle_deg(to - from);
}

}  // namespace omninav
