#include "panorama_lines.hpp"

#include "simd_dispatch.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define OMNINAV_AVX2_LUMINANCE 1
#endif

namespace omninav::signature::detail {
namespace {

constexpr int kLuminanceShift = 15;
constexpr int kBlueWeight = 3735, kGreenWeight = 19235, kRedWeight = 9798;  // sum 2^15
static_assert(kBlueWeight + kGreenWeight + kRedWeight == 1 << kLuminanceShift);

constexpr int kHalf = 1 << (kLuminanceShift - 1);

// Pixels [from, width) one at a time: the portable version, and the AVX2 version's tail.
OMNINAV_KERNEL_CLONES
void luminance_pixels(const std::uint8_t* bgr, int from, int width, float* dst) {
  for (int x = from; x < width; ++x) {
    const int b = bgr[3 * x], g = bgr[3 * x + 1], r = bgr[3 * x + 2];
    dst[x] = static_cast<float>((b * kBlueWeight + g * kGreenWeight + r * kRedWeight + kHalf) >>
                                kLuminanceShift);
  }
}

#ifdef OMNINAV_AVX2_LUMINANCE
// The one place with intrinsics: what the compiler makes of the loop above spends most of its
// time taking the interleaved B, G, R bytes apart (2.3 times as long as this, which does 8
// pixels with two byte shuffles and two 16-bit dot products: B·wb + G·wg and R·wr + 1·half).
// Integer arithmetic, so the same values as the portable loop, exactly.

// Pixels x..x+7: x..x+3 from the 16 bytes at 3x, x+4..x+7 from `high` (their 12 bytes first).
__attribute__((target("avx2"), always_inline)) inline void luminance_eight(const std::uint8_t* bgr,
                                                                           int x, __m128i high,
                                                                           float* dst) {
  // Per 32-bit lane i of each 128-bit half: the bytes (B, 0, G, 0) and (R, 0, 0, 0) of pixel
  // i of that half; −1 gives a zero byte.
  const __m256i blue_green =
      _mm256_setr_epi8(0, -1, 1, -1, 3, -1, 4, -1, 6, -1, 7, -1, 9, -1, 10, -1, 0, -1, 1, -1, 3, -1,
                       4, -1, 6, -1, 7, -1, 9, -1, 10, -1);
  const __m256i red = _mm256_setr_epi8(2, -1, -1, -1, 5, -1, -1, -1, 8, -1, -1, -1, 11, -1, -1, -1,
                                       2, -1, -1, -1, 5, -1, -1, -1, 8, -1, -1, -1, 11, -1, -1, -1);
  const __m256i one_high = _mm256_set1_epi32(1 << 16);
  const __m256i blue_green_weights = _mm256_set1_epi32(kBlueWeight | (kGreenWeight << 16));
  const __m256i red_half_weights = _mm256_set1_epi32(kRedWeight | (kHalf << 16));
  const __m128i low = _mm_loadu_si128(reinterpret_cast<const __m128i*>(bgr + 3 * x));
  const __m256i pixels = _mm256_inserti128_si256(_mm256_castsi128_si256(low), high, 1);
  const __m256i bg = _mm256_madd_epi16(_mm256_shuffle_epi8(pixels, blue_green), blue_green_weights);
  const __m256i r1 = _mm256_or_si256(_mm256_shuffle_epi8(pixels, red), one_high);
  const __m256i sum = _mm256_add_epi32(bg, _mm256_madd_epi16(r1, red_half_weights));
  _mm256_storeu_ps(dst + x, _mm256_cvtepi32_ps(_mm256_srai_epi32(sum, kLuminanceShift)));
}

__attribute__((target("avx2"))) void luminance_avx2(const std::uint8_t* bgr, int width,
                                                    float* dst) {
  if (width < 8) {
    luminance_pixels(bgr, 0, width, dst);
    return;
  }
  // The second 16-byte load ends 4 bytes past pixel x+7: stop where it would leave the row...
  int x = 0;
  for (; 3 * x + 28 <= 3 * width; x += 8) {
    luminance_eight(bgr, x, _mm_loadu_si128(reinterpret_cast<const __m128i*>(bgr + 3 * x + 12)),
                    dst);
  }
  // ...and do the last 8 pixels (again, in part) with that load 4 bytes earlier, shifted.
  if (x < width) {
    x = width - 8;
    const __m128i ending = _mm_loadu_si128(reinterpret_cast<const __m128i*>(bgr + 3 * x + 8));
    luminance_eight(bgr, x, _mm_srli_si128(ending, 4), dst);
  }
}

bool has_avx2() {
  static const bool has = [] {
    __builtin_cpu_init();  // may run before the library's own initialisation
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
}
#endif

void luminance_row(const std::uint8_t* bgr, int width, float* dst) {
#ifdef OMNINAV_AVX2_LUMINANCE
  if (has_avx2()) {
    luminance_avx2(bgr, width, dst);
    return;
  }
#endif
  luminance_pixels(bgr, 0, width, dst);
}

OMNINAV_KERNEL_CLONES
void grey_row(const std::uint8_t* grey, int width, float* dst) {
  for (int x = 0; x < width; ++x) dst[x] = grey[x];
}

OMNINAV_KERNEL_CLONES
void channel_row(const std::uint8_t* bgr, int channel, int width, float* dst) {
  for (int x = 0; x < width; ++x) dst[x] = bgr[3 * x + channel];
}

}  // namespace

void load_line(const cv::Mat& panorama, ColourMode mode, int line, float* dst) {
  const int rows = panorama.rows;
  const int y = line % rows;
  const std::uint8_t* src = panorama.ptr<std::uint8_t>(y);
  if (panorama.channels() == 1) {
    grey_row(src, panorama.cols, dst);
  } else if (mode == ColourMode::kLuminance) {
    luminance_row(src, panorama.cols, dst);
  } else {
    channel_row(src, line / rows, panorama.cols, dst);  // lines: blue rows, green, red
  }
}

}  // namespace omninav::signature::detail
