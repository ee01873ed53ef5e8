#include "low_frequency_dft.hpp"

#include <cmath>
#include <cstddef>
#include <cstring>

#include "omninav/core/angles.hpp"
#include "simd_dispatch.hpp"

namespace omninav::signature::detail {
namespace {

typedef float Lanes __attribute__((vector_size(32)));  // 8 floats
constexpr int kLanes = 8;

// R lines' folded rows (fold()) times the table, G 8-lane groups per parity. The folded values
// are read from memory one at a time and broadcast (a load, not a shuffle, on x86), each table
// vector is loaded once and used R times, and the 4·G·R sums are independent chains. Loads
// bound it: 4 broadcasts per line and 4·G table vectors per x; R = 3 lines (12 sums and 4
// table vectors in AVX2's 16 registers) ran 15% faster than 2 and 30% faster than 1.
template <int G, int R>
__attribute__((always_inline)) inline void kernel(const float* folded, int width, int m,
                                                  const float* table, float* re, float* im) {
  const int q = width / 4;
  Lanes sum[R][G][4] = {};  // per line and group: Re even k, Re odd k, Im even k, Im odd k
  for (int x = 1; x < q; ++x) {
    const float* t = table + static_cast<std::size_t>(x) * G * 4 * kLanes;
    for (int g = 0; g < G; ++g) {
      // The table is only float-aligned: copied, not dereferenced as 32-byte vectors.
      Lanes cos_even, cos_odd, sin_even, sin_odd;
      std::memcpy(&cos_even, t + (g * 4 + 0) * kLanes, sizeof(Lanes));
      std::memcpy(&cos_odd, t + (g * 4 + 1) * kLanes, sizeof(Lanes));
      std::memcpy(&sin_even, t + (g * 4 + 2) * kLanes, sizeof(Lanes));
      std::memcpy(&sin_odd, t + (g * 4 + 3) * kLanes, sizeof(Lanes));
      for (int r = 0; r < R; ++r) {
        const float* line = folded + static_cast<std::size_t>(r) * width;
        sum[r][g][0] += line[x] * cos_even;
        sum[r][g][1] += line[q + x] * cos_odd;
        sum[r][g][2] += line[2 * q + x] * sin_even;
        sum[r][g][3] += line[3 * q + x] * sin_odd;
      }
    }
  }
  static constexpr float kCosQuarter[4] = {1.f, 0.f, -1.f, 0.f};  // cos(πk/2)
  static constexpr float kSinQuarter[4] = {0.f, 1.f, 0.f, -1.f};  // sin(πk/2)
  for (int r = 0; r < R; ++r) {
    const float* line = folded + static_cast<std::size_t>(r) * width;
    // f(0) ± f(W/2), e(W/4), o(W/4): the x = 0 slots.
    const float sum_even = line[0], sum_odd = line[q], e_q = line[2 * q], o_q = line[3 * q];
    float* re_line = re + static_cast<std::size_t>(r) * m;
    float* im_line = im + static_cast<std::size_t>(r) * m;
    for (int g = 0; g < G; ++g) {
      for (int j = 0; j < kLanes; ++j) {
        const int even = 2 * (g * kLanes + j), odd = even + 1;
        if (even < m) {
          re_line[even] = sum_even + sum[r][g][0][j] + e_q * kCosQuarter[even % 4];
          im_line[even] = -(sum[r][g][2][j] + o_q * kSinQuarter[even % 4]);
        }
        if (odd < m) {
          re_line[odd] = sum_odd + sum[r][g][1][j] + e_q * kCosQuarter[odd % 4];
          im_line[odd] = -(sum[r][g][3][j] + o_q * kSinQuarter[odd % 4]);
        }
      }
    }
  }
}

OMNINAV_KERNEL_CLONES
void kernel_one_group_three_lines(const float* folded, int width, int m, const float* table,
                                  float* re, float* im) {
  kernel<1, 3>(folded, width, m, table, re, im);
}

OMNINAV_KERNEL_CLONES
void kernel_one_group_two_lines(const float* folded, int width, int m, const float* table,
                                float* re, float* im) {
  kernel<1, 2>(folded, width, m, table, re, im);
}

OMNINAV_KERNEL_CLONES
void kernel_one_group_one_line(const float* folded, int width, int m, const float* table, float* re,
                               float* im) {
  kernel<1, 1>(folded, width, m, table, re, im);
}

OMNINAV_KERNEL_CLONES
void kernel_two_groups_one_line(const float* folded, int width, int m, const float* table,
                                float* re, float* im) {
  kernel<2, 1>(folded, width, m, table, re, im);
}

OMNINAV_KERNEL_CLONES
void fold_row(const float* __restrict f, int width, float* __restrict folded) {
  const int h = width / 2, q = width / 4;
  float* __restrict ee = folded;
  float* __restrict eo = folded + q;
  float* __restrict oe = folded + 2 * q;
  float* __restrict oo = folded + 3 * q;
  for (int x = 1; x < q; ++x) {
    // e(x) = f(x) + f(W−x), e(W/2−x) = f(W/2−x) + f(W/2+x); likewise o with differences.
    const float e_x = f[x] + f[width - x], e_m = f[h - x] + f[h + x];
    const float o_x = f[x] - f[width - x], o_m = f[h - x] - f[h + x];
    ee[x] = e_x + e_m;
    eo[x] = e_x - e_m;
    oe[x] = o_x - o_m;
    oo[x] = o_x + o_m;
  }
  ee[0] = f[0] + f[h];
  eo[0] = f[0] - f[h];
  oe[0] = f[q] + f[width - q];
  oo[0] = f[q] - f[width - q];
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

void LowFrequencyDft::fold(const float* f, float* folded) const {
  fold_row(f, width_, folded);
}

void LowFrequencyDft::transform_folded(const float* folded, int lines, float* re, float* im) const {
  const float* table = table_.data();
  const int m = components_;
  if (groups_ == 1 && lines == 3) {
    kernel_one_group_three_lines(folded, width_, m, table, re, im);
  } else if (groups_ == 1 && lines == 2) {
    kernel_one_group_two_lines(folded, width_, m, table, re, im);
  } else {
    for (int line = 0; line < lines; ++line) {
      const float* f = folded + static_cast<std::size_t>(line) * width_;
      float* re_line = re + static_cast<std::size_t>(line) * m;
      float* im_line = im + static_cast<std::size_t>(line) * m;
      if (groups_ == 1) {
        kernel_one_group_one_line(f, width_, m, table, re_line, im_line);
      } else {
        kernel_two_groups_one_line(f, width_, m, table, re_line, im_line);
      }
    }
  }
}

}  // namespace omninav::signature::detail
