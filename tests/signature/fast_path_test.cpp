// The fast signature path (lines converted one at a time, the direct low-frequency transform,
// the polynomial atan2) against the reference path (cv::cvtColor, FFTW, the C library's atan2):
// the oracle of STYLE.md's "an oracle checks the fast ones".
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "../../libs/signature/src/panorama_lines.hpp"
#include "omninav/signature/signature.hpp"
#include "rendered_room.hpp"

namespace omninav::signature {
namespace {

using testing::render;

// Both paths sum ≤ 720 floats ≤ 255 in single precision and divide by W: their rounding errors
// stay below 1e-4 grey levels (measured: the largest |ΔF| over every case below is 6.1e-5,
// the polynomial atan2's share included). 1e-3 leaves room and is still far below what
// matters: neighbouring places 30 cm apart differ by ~1.85 grey levels per value
// (docs/memory.md, Fig. 7).
constexpr double kCoefficientTolerance = 1e-3;
// fast_atan2's error bound (fast_math.hpp): 1e-5 rad, which moves a coefficient by ≤ 1e-5·|F|.
constexpr double kAtan2Error = 1e-5;

struct Case {
  std::string name;
  cv::Mat panorama;
};

std::vector<Case> panoramas() {
  std::vector<Case> cases;
  cases.push_back({"rendered 360x45", render(2.1, 3.3, 40.0)});
  cases.push_back({"rendered 720x80", render(3.4, 2.2, -120.0, 720, 80)});
  cv::RNG random(7);
  for (const auto& [width, height] : {std::pair{64, 7}, std::pair{100, 9}, std::pair{98, 4}}) {
    // Noise: every component large and every phase used; widths 64 and 100 take the direct
    // transform, 98 (not divisible by 4) FFTW on both paths.
    cv::Mat noise(height, width, CV_8UC3);
    random.fill(noise, cv::RNG::UNIFORM, 0, 256);
    cases.push_back({"noise " + std::to_string(width) + "x" + std::to_string(height), noise});
    cv::Mat grey;
    cv::cvtColor(noise, grey, cv::COLOR_BGR2GRAY);
    cases.push_back({"grey noise " + std::to_string(width) + "x" + std::to_string(height), grey});
  }
  return cases;
}

void expect_same_signature(const Signature& fast, const Signature& reference,
                           const std::string& what) {
  ASSERT_TRUE(fast.same_layout(reference)) << what;
  ASSERT_EQ(fast.components, reference.components) << what;
  ASSERT_EQ(fast.size(), reference.size()) << what;
  for (int line = 0; line < fast.lines(); ++line) {
    for (int k = 0; k < fast.components; ++k) {
      const std::complex<double> a = fast.coefficient(line, k);
      const std::complex<double> b = reference.coefficient(line, k);
      const double difference = std::abs(a - b);
      ASSERT_LE(difference, kCoefficientTolerance + kAtan2Error * std::abs(b))
          << what << ", line " << line << ", k = " << k << ": " << a << " against " << b;
      // (−π, π] in float: π rounds up to 3.14159274f, the value a phase of ±π is stored as.
      EXPECT_GT(fast.phase_rad[fast.at(line, k)], -std::numbers::pi_v<float>) << what;
      EXPECT_LE(fast.phase_rad[fast.at(line, k)], std::numbers::pi_v<float>) << what;
    }
  }
}

TEST(SignatureFastPath, MatchesTheReferencePath) {
  for (const Case& c : panoramas()) {
    for (ColourMode mode : {ColourMode::kLuminance, ColourMode::kPerChannel}) {
      // m = 15 (the default, one 8-lane group), 16 and 17 (the group edges), 1, 2 and 32
      // (the smallest and the largest the direct transform serves), 33 (FFTW on both paths).
      for (int m : {1, 2, 15, 16, 17, 32, 33}) {
        if (m > c.panorama.cols / 2 + 1) continue;
        for (bool normalise : {false, true}) {
          const SignatureParams params{m, mode, normalise};
          SignatureExtractor fast(params, SignaturePath::kFast);
          SignatureExtractor reference(params, SignaturePath::kReference);
          const std::string what = c.name + ", " + to_string(mode) + ", m = " + std::to_string(m) +
                                   (normalise ? ", normalised" : "");
          expect_same_signature(fast.compute(c.panorama), reference.compute(c.panorama), what);
        }
      }
    }
  }
}

TEST(SignatureFastPath, IsTheSameWhateverTheExtractorComputedBefore) {
  // The workspace is reused between calls and resized when the size changes; a line's result
  // does not depend on the lines transformed with it.
  const cv::Mat small = render(1.5, 1.5, 0.0);
  const cv::Mat large = render(1.5, 1.5, 0.0, 720, 80);
  SignatureExtractor reused({15, ColourMode::kLuminance});
  const Signature first = reused.compute(small);
  reused.compute(large);
  const Signature again = reused.compute(small);
  EXPECT_EQ(first.magnitude, again.magnitude);
  EXPECT_EQ(first.phase_rad, again.phase_rad);
  // The odd last row of 45 is transformed alone, the others in pairs: the same floats as a
  // panorama of that row only.
  const Signature last_row = SignatureExtractor({15, ColourMode::kLuminance, false})
                                 .compute(small.rowRange(44, 45).clone());
  const Signature whole = SignatureExtractor({15, ColourMode::kLuminance, false}).compute(small);
  const Signature first_row =
      SignatureExtractor({15, ColourMode::kLuminance, false}).compute(small.rowRange(0, 1).clone());
  for (int k = 0; k < 15; ++k) {
    EXPECT_EQ(last_row.magnitude[last_row.at(0, k)], whole.magnitude[whole.at(44, k)]) << k;
    EXPECT_EQ(last_row.phase_rad[last_row.at(0, k)], whole.phase_rad[whole.at(44, k)]) << k;
    EXPECT_EQ(first_row.magnitude[first_row.at(0, k)], whole.magnitude[whole.at(0, k)]) << k;
    EXPECT_EQ(first_row.phase_rad[first_row.at(0, k)], whole.phase_rad[whole.at(0, k)]) << k;
  }
}

TEST(SignatureFastPath, LuminanceIsOpenCvsOnEveryColour) {
  // All 2^24 colours, 4096 per row: the fused conversion gives cv::cvtColor's integers exactly,
  // so signatures (and the maps made with them before it existed) do not change.
  cv::Mat colours(4096, 4096, CV_8UC3);
  for (int i = 0; i < (1 << 24); ++i) {
    std::uint8_t* pixel = colours.data + 3 * static_cast<std::size_t>(i);
    pixel[0] = static_cast<std::uint8_t>(i & 255);
    pixel[1] = static_cast<std::uint8_t>((i >> 8) & 255);
    pixel[2] = static_cast<std::uint8_t>(i >> 16);
  }
  cv::Mat grey;
  cv::cvtColor(colours, grey, cv::COLOR_BGR2GRAY);
  std::vector<float> line(4096);
  int mismatches = 0;
  for (int y = 0; y < colours.rows; ++y) {
    detail::load_line(colours, ColourMode::kLuminance, y, line.data());
    const std::uint8_t* expected = grey.ptr<std::uint8_t>(y);
    for (int x = 0; x < colours.cols; ++x) mismatches += line[x] != expected[x];
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(SignatureFastPath, FullSpectrumStartsWithTheSignaturesMagnitudes) {
  const cv::Mat panorama = render(2.7, 1.4, 200.0);
  for (ColourMode mode : {ColourMode::kLuminance, ColourMode::kPerChannel}) {
    SignatureExtractor extractor({15, mode, false});
    const Signature s = extractor.compute(panorama);
    const cv::Mat spectrum = extractor.full_spectrum(panorama);
    ASSERT_EQ(spectrum.rows, s.lines());
    ASSERT_EQ(spectrum.cols, 181);
    for (int line = 0; line < s.lines(); ++line) {
      for (int k = 0; k < 15; ++k) {
        EXPECT_NEAR(spectrum.at<float>(line, k), s.magnitude[s.at(line, k)], kCoefficientTolerance)
            << to_string(mode) << ", line " << line << ", k = " << k;
      }
    }
  }
}

}  // namespace
}  // namespace omninav::signature
