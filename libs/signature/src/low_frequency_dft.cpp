#include "low_frequency_dft.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"

// GCC and Clang compile the kernel twice on x86-64, for AVX2 and for the baseline, and pick one
// at load time (an ifunc): no -march flag, no intrinsics. The 8-lane vector type is the same in
// both, so every sum is made in the same order, and neither target has FMA to fuse a·b + c
// with, so both give the same floats.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define OMNINAV_KERNEL_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define OMNINAV_KERNEL_CLONES
#endif

namespace omninav::signature::detail {
namespace {

typedef float Lanes __attribute__((vector_size(32)));  // 8 floats
// The same, readable at any float's alignment (GCC lets vectors alias their element type).
typedef float UnalignedLanes __attribute__((vector_size(32), aligned(4)));
constexpr int kLanes = 8;

template <int G>
__attribute__((always_inline)) inline void kernel(const float* f, int width, int m,
                                                  const float* table, float* re, float* im) {
  const int h = width / 2, q = width / 4;
  Lanes ree[G] = {}, reo[G] = {}, ime[G] = {}, imo[G] = {};  // Re/Im, even/odd k
  for (int x = 1; x < q; ++x) {
    // e(x) = f(x) + f(W−x), e(W/2−x) = f(W/2−x) + f(W/2+x); likewise o with differences.
    const float e_x = f[x] + f[width - x], e_m = f[h - x] + f[h + x];
    const float o_x = f[x] - f[width - x], o_m = f[h - x] - f[h + x];
    const float ee = e_x + e_m, eo = e_x - e_m, oe = o_x - o_m, oo = o_x + o_m;
    const float* t = table + static_cast<std::size_t>(x) * G * 4 * kLanes;
    for (int g = 0; g < G; ++g, t += 4 * kLanes) {
      const auto* lanes = reinterpret_cast<const UnalignedLanes*>(t);
      ree[g] += ee * lanes[0];
      reo[g] += eo * lanes[1];
      ime[g] += oe * lanes[2];
      imo[g] += oo * lanes[3];
    }
  }
  const float e_q = f[q] + f[width - q], o_q = f[q] - f[width - q];
  static constexpr float kCosQuarter[4] = {1.f, 0.f, -1.f, 0.f};  // cos(πk/2)
  static constexpr float kSinQuarter[4] = {0.f, 1.f, 0.f, -1.f};  // sin(πk/2)
  for (int g = 0; g < G; ++g) {
    for (int j = 0; j < kLanes; ++j) {
      const int even = 2 * (g * kLanes + j), odd = even + 1;
      if (even < m) {
        re[even] = f[0] + f[h] + ree[g][j] + e_q * kCosQuarter[even % 4];
        im[even] = -(ime[g][j] + o_q * kSinQuarter[even % 4]);
      }
      if (odd < m) {
        re[odd] = f[0] - f[h] + reo[g][j] + e_q * kCosQuarter[odd % 4];
        im[odd] = -(imo[g][j] + o_q * kSinQuarter[odd % 4]);
      }
    }
  }
}

OMNINAV_KERNEL_CLONES
void kernel_one_group(const float* f, int width, int m, const float* table, float* re, float* im) {
  kernel<1>(f, width, m, table, re, im);
}

OMNINAV_KERNEL_CLONES
void kernel_two_groups(const float* f, int width, int m, const float* table, float* re, float* im) {
  kernel<2>(f, width, m, table, re, im);
}

}  // namespace

bool LowFrequencyDft::applicable(int width, int components) {
  return width >= 8 && width % 4 == 0 && components >= 1 && components <= 32 &&
         components <= width / 2 + 1;
}

LowFrequencyDft::LowFrequencyDft(int width, int components)
    : width_(width), components_(components), groups_(components <= 16 ? 1 : 2) {
  const int q = width / 4;
  table_.assign(static_cast<std::size_t>(q) * groups_ * 4 * kLanes, 0.f);
  for (int x = 0; x < q; ++x) {
    for (int g = 0; g < groups_; ++g) {
      float* t = table_.data() + (static_cast<std::size_t>(x) * groups_ + g) * 4 * kLanes;
      for (int j = 0; j < kLanes; ++j) {
        const int even = 2 * (g * kLanes + j), odd = even + 1;
        // Angles reduced exactly (k·x mod W) before the double-precision trigonometry.
        const double a_even = kTwoPi * ((static_cast<long>(even) * x) % width) / width;
        const double a_odd = kTwoPi * ((static_cast<long>(odd) * x) % width) / width;
        t[j] = static_cast<float>(std::cos(a_even));
        t[kLanes + j] = static_cast<float>(std::cos(a_odd));
        t[2 * kLanes + j] = static_cast<float>(std::sin(a_even));
        t[3 * kLanes + j] = static_cast<float>(std::sin(a_odd));
      }
    }
  }
}

void LowFrequencyDft::transform(const float* f, float* re, float* im) const {
  if (groups_ == 1) {
    kernel_one_group(f, width_, components_, table_.data(), re, im);
  } else {
    kernel_two_groups(f, width_, components_, table_.data(), re, im);
  }
}

}  // namespace omninav::signature::detail
