#pragma once
// A branch-free atan2 that the compiler vectorises, and the magnitudes and phases of a block of
// complex values with it, and a vectorised sine and cosine. The atan2: computing 675 phases with
// the C library's atan2f would cost more than the transform itself (signature_bench), and branches
// on the signs of random phases are mispredicted half the time.

#include <cmath>
#include <cstddef>
#include <numbers>

namespace omninav::signature::detail {

// atan2(y, x) in (−π, π], absolute error below 1e-5 rad (the degree-11 odd minimax polynomial
// of atan on [−1, 1], coefficients from mazzo.li/posts/vectorized-atan2.html). 1e-5 rad is
// 6e-4°, far below the half column (0.5° at 360 columns) that headings are tested to.
// atan2(0, 0) = 0. Written with selects only, so that a loop of it vectorises.
inline float fast_atan2(float y, float x) {
  constexpr float a1 = 0.99997726f, a3 = -0.33262347f, a5 = 0.19354346f, a7 = -0.11643287f,
                  a9 = 0.05265332f, a11 = -0.01172120f;
  constexpr float pi = std::numbers::pi_v<float>;
  const float ax = std::fabs(x), ay = std::fabs(y);
  const bool swap = ay > ax;
  const float num = swap ? ax : ay;
  const float den = swap ? ay : ax;
  const float t = num / (den > 0.f ? den : 1.f);  // in [0, 1]; den = 0 only when num = 0
  const float t2 = t * t;
  float r = t * (a1 + t2 * (a3 + t2 * (a5 + t2 * (a7 + t2 * (a9 + t2 * a11)))));
  r = swap ? pi / 2 - r : r;
  r = x < 0.f ? pi - r : r;
  r = y < 0.f ? -r : r;
  // y = −0 with x < 0 would give −π; keep (−π, π].
  return r <= -pi ? pi : r;
}

// magnitude[i] = |z_i|·scale and phase_rad[i] = fast_atan2 of z_i = re[i] + i·im[i], for n
// values (vectorised; the same floats on every instruction set, simd_dispatch.hpp).
void to_polar(const float* re, const float* im, std::size_t n, float scale, float* magnitude,
              float* phase_rad);

// sin_x[i] = sin x[i] and cos_x[i] = cos x[i] within 2.2e-16 of the C library's for
// |x| ≤ 10⁵ (measured 1.1e-16, motion_test.cpp); the warp fit's and the phase heading's angles stay
// within a few π. Vectorised, the same doubles on every instruction set: the C library's sincos,
// one call per value, took a fifth of estimate_motion()'s time. Written here (fdlibm's reduction
// and polynomials) because glibc's vector variants (libmvec) are only called under -ffast-math,
// which this project does not use: it would let the compiler reorder the sums that tests compare
// bit for bit.
void sin_cos(const double* x, std::size_t n, double* sin_x, double* cos_x);

}  // namespace omninav::signature::detail
