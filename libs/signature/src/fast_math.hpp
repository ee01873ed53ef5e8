#pragma once
// A branch-light atan2 that the compiler vectorises: computing 675 phases with the C library's
// atan2f would cost more than the FFT itself (bench: signature_bench).

#include <cmath>
#include <numbers>

namespace omninav::signature::detail {

// atan2(y, x) in (−π, π], absolute error below 1e-5 rad (the degree-11 odd minimax polynomial
// of atan on [−1, 1], coefficients from mazzo.li/posts/vectorized-atan2.html). 1e-5 rad is
// 6e-4°, far below the half column (0.5° at 360 columns) that headings are tested to.
// atan2(0, 0) = 0.
inline float fast_atan2(float y, float x) {
  constexpr float a1 = 0.99997726f, a3 = -0.33262347f, a5 = 0.19354346f, a7 = -0.11643287f,
                  a9 = 0.05265332f, a11 = -0.01172120f;
  constexpr float pi = std::numbers::pi_v<float>;
  const float ax = std::fabs(x), ay = std::fabs(y);
  const bool swap = ay > ax;
  const float num = swap ? ax : ay;
  const float den = swap ? ay : ax;
  const float t = den > 0.f ? num / den : 0.f;  // in [0, 1]
  const float t2 = t * t;
  float r = t * (a1 + t2 * (a3 + t2 * (a5 + t2 * (a7 + t2 * (a9 + t2 * a11)))));
  if (swap) r = pi / 2 - r;
  if (x < 0.f) r = pi - r;
  if (y < 0.f) r = -r;
  // y = −0 with x < 0 would give −π; keep (−π, π].
  if (r <= -pi) r = pi;
  return r;
}

}  // namespace omninav::signature::detail
