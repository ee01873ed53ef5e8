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

}  // namespace omninav::signature::detail
