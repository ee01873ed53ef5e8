#include "fast_math.hpp"

#include "simd_dispatch.hpp"

// This file is compiled with -fno-math-errno and -fno-trapping-math (CMakeLists.txt): without
// them the loop below does not vectorise (std::sqrt's errno; the selects of fast_atan2).

namespace omninav::signature::detail {
namespace {

OMNINAV_KERNEL_CLONES
void polar_loop(const float* __restrict re, const float* __restrict im, std::size_t n, float scale,
                float* __restrict magnitude, float* __restrict phase_rad) {
  for (std::size_t i = 0; i < n; ++i) {
    const float a = re[i] * scale, b = im[i] * scale;
    magnitude[i] = std::sqrt(a * a + b * b);
    phase_rad[i] = fast_atan2(b, a);
  }
}

}  // namespace

void to_polar(const float* re, const float* im, std::size_t n, float scale, float* magnitude,
              float* phase_rad) {
  polar_loop(re, im, n, scale, magnitude, phase_rad);
}

OMNINAV_KERNEL_CLONES
void sin_cos(const double* __restrict x, std::size_t n, double* __restrict sin_x,
             double* __restrict cos_x) {
  // v + kRound − kRound is v rounded to an integer (to nearest, ties to even) for |v| < 2^51.
  constexpr double kRound = 6755399441055744.0;  // 1.5·2^52
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  // π/2 = kPio2_1 + kPio2_2 + kPio2_3; the first two have 33 significant bits, so that q times
  // either is exact for |q| < 2^20 (fdlibm's reduction).
  constexpr double kPio2_1 = 1.57079632673412561417e+00;
  constexpr double kPio2_2 = 6.07710050630396597660e-11;
  constexpr double kPio2_3 = 2.02226624879595063154e-21;
  // fdlibm's minimax polynomials for sin and cos on [−π/4, π/4] (k_sin.c, k_cos.c).
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  for (std::size_t i = 0; i < n; ++i) {
    const double q = (x[i] * kTwoOverPi + kRound) - kRound;  // x ≈ q·π/2 + r, |r| ≤ π/4
    const double r = ((x[i] - q * kPio2_1) - q * kPio2_2) - q * kPio2_3;
    const double z = r * r;
    const double sin_r = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    const double half_z = 0.5 * z;
    const double w = 1.0 - half_z;  // cos r = w plus what rounding w lost plus the rest
    const double cos_r = w + (((1.0 - w) - half_z) +
                              z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))));
    // The quadrant, q mod 4 in −2..2.
    const double quadrant = q - 4.0 * ((q * 0.25 + kRound) - kRound);
    const bool negate = quadrant == 2.0 || quadrant == -2.0;
    const double s = quadrant == 1.0 ? cos_r : quadrant == -1.0 ? -cos_r : sin_r;
    const double c = quadrant == 1.0 ? -sin_r : quadrant == -1.0 ? sin_r : cos_r;
    sin_x[i] = negate ? -s : s;
    cos_x[i] = negate ? -c : c;
  }
}

}  // namespace omninav::signature::detail
