#include "omninav/signature/signature.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "rendered_room.hpp"

namespace omninav::signature {
namespace {

using testing::render;

// Single-precision FFT of rows of ≤ 720 values ≤ 255, scaled by 1/W: rounding errors stay
// below 1e-4 grey levels; 1e-3 leaves room and is still 1e-5 of the mean component.
constexpr float kFloatTolerance = 1e-3f;

float max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
  float worst = 0.f;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  return worst;
}

TEST(Signature, LayoutAndFirstComponentIsTheRowMean) {
  const cv::Mat panorama = render(2.0, 2.0, 10.0);
  SignatureParams params;
  params.components = 15;
  params.normalise_brightness = false;
  const Signature s = compute_signature(panorama, params);
  EXPECT_EQ(s.rows, 45);
  EXPECT_EQ(s.channels, 1);
  EXPECT_EQ(s.components, 15);
  EXPECT_EQ(s.width_px, 360);
  ASSERT_EQ(s.magnitude.size(), 45u * 15u);
  ASSERT_EQ(s.phase_rad.size(), s.magnitude.size());
  cv::Mat grey;
  cv::cvtColor(panorama, grey, cv::COLOR_BGR2GRAY);
  for (int y : {0, 22, 44}) {
    const double mean = cv::mean(grey.row(y))[0];
    EXPECT_NEAR(s.magnitude[s.at(y, 0)], mean, 1e-3) << "row " << y;
  }
  for (float phase : s.phase_rad) {
    EXPECT_GT(phase, -3.1415927f);
    EXPECT_LE(phase, 3.1415927f);
  }
}

TEST(Signature, ColourPerChannelKeepsBlueGreenRedRowsApart) {
  cv::Mat panorama(4, 64, CV_8UC3, cv::Scalar(10, 20, 30));
  SignatureParams params;
  params.components = 3;
  params.colour = ColourMode::kPerChannel;
  params.normalise_brightness = false;
  const Signature s = compute_signature(panorama, params);
  EXPECT_EQ(s.channels, 3);
  EXPECT_EQ(s.lines(), 12);
  EXPECT_NEAR(s.magnitude[s.at(0, 0)], 10.0, 1e-4);  // blue rows first
  EXPECT_NEAR(s.magnitude[s.at(4, 0)], 20.0, 1e-4);  // then green
  EXPECT_NEAR(s.magnitude[s.at(8, 0)], 30.0, 1e-4);  // then red
  EXPECT_NEAR(s.magnitude[s.at(8, 1)], 0.0, 1e-4);   // a flat row has no other component
}

TEST(Signature, MatchesADirectDiscreteFourierTransform) {
  cv::Mat panorama(3, 40, CV_8UC1);
  cv::randu(panorama, 0, 256);
  SignatureParams params;
  params.components = 6;
  params.normalise_brightness = false;
  const Signature s = compute_signature(panorama, params);
  for (int y = 0; y < 3; ++y) {
    for (int k = 0; k < 6; ++k) {
      std::complex<double> sum = 0.0;
      for (int x = 0; x < 40; ++x) {
        sum += double(panorama.at<std::uint8_t>(y, x)) * std::polar(1.0, -kTwoPi * k * x / 40);
      }
      sum /= 40.0;
      EXPECT_NEAR(s.magnitude[s.at(y, k)], std::abs(sum), 1e-4);
      if (std::abs(sum) > 1e-3) {
        EXPECT_NEAR(std::remainder(s.phase_rad[s.at(y, k)] - std::arg(sum), kTwoPi), 0.0, 2e-5);
      }
    }
  }
}

TEST(Signature, TruncatedEqualsFewerComponents) {
  const cv::Mat panorama = render(3.0, 2.5, -40.0);
  const Signature full = compute_signature(panorama, {15, ColourMode::kPerChannel});
  const Signature five = compute_signature(panorama, {5, ColourMode::kPerChannel});
  const Signature cut = full.truncated(5);
  EXPECT_EQ(cut.magnitude, five.magnitude);
  EXPECT_EQ(cut.phase_rad, five.phase_rad);
  EXPECT_THROW(full.truncated(16), UsageError);
}

TEST(Signature, SameInputGivesBitIdenticalSignatures) {
  const cv::Mat panorama = render(1.3, 3.2, 77.0);
  SignatureExtractor a({15, ColourMode::kLuminance});
  const Signature first = a.compute(panorama);
  const Signature second = compute_signature(panorama, {15, ColourMode::kLuminance});
  EXPECT_EQ(first.magnitude, second.magnitude);
  EXPECT_EQ(first.phase_rad, second.phase_rad);
}

TEST(Signature, RollingLeavesTheMagnitudesUnchanged) {
  for (const auto& [width, height] : {std::pair{360, 45}, std::pair{720, 80}}) {
    const cv::Mat panorama = render(2.4, 1.9, 25.0, width, height);
    for (ColourMode mode : {ColourMode::kLuminance, ColourMode::kPerChannel}) {
      SignatureExtractor extractor({15, mode});
      const Signature reference = extractor.compute(panorama);
      for (int shift : {1, 7, 90, 123, width - 1}) {
        const Signature rolled = extractor.compute(roll_columns(panorama, shift));
        EXPECT_LE(max_abs_difference(reference.magnitude, rolled.magnitude), kFloatTolerance)
            << width << "x" << height << " " << to_string(mode) << ", roll " << shift;
      }
    }
  }
}

TEST(Signature, BadInputIsRefusedWithAClearError) {
  EXPECT_THROW(compute_signature(cv::Mat(), {}), InputError);
  EXPECT_THROW(compute_signature(cv::Mat(10, 40, CV_32F, 0.f), {}), InputError);
  try {
    compute_signature(cv::Mat(10, 20, CV_8UC3, cv::Scalar::all(0)), {15, ColourMode::kLuminance});
    FAIL() << "a 20-column panorama has only 11 components";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("11 Fourier components"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(SignatureExtractor({0, ColourMode::kLuminance}), UsageError);
}

TEST(Signature, AGreyPanoramaInColourModeGivesThreeEqualChannels) {
  cv::Mat grey(5, 50, CV_8UC1);
  cv::randu(grey, 0, 256);
  const Signature s = compute_signature(grey, {4, ColourMode::kPerChannel, false});
  for (int y = 0; y < 5; ++y) {
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(s.magnitude[s.at(y, k)], s.magnitude[s.at(y + 5, k)]);
      EXPECT_EQ(s.magnitude[s.at(y, k)], s.magnitude[s.at(y + 10, k)]);
    }
  }
}

TEST(Signature, NormalisedBrightnessCancelsAnExposureChange) {
  const cv::Mat panorama = render(2.2, 2.6, 15.0);
  cv::Mat darker;
  panorama.convertTo(darker, -1, 0.7);  // an exposure 0.7 times as long, rounded to 8 bits
  const cv::Mat elsewhere = render(2.5, 2.6, 15.0);
  for (ColourMode mode : {ColourMode::kLuminance, ColourMode::kPerChannel}) {
    SignatureExtractor raw({15, mode, false}), normalised({15, mode, true});
    const auto dis = [](SignatureExtractor& e, const cv::Mat& a, const cv::Mat& b) {
      return dissimilarity(e.compute(a), e.compute(b));
    };
    // Raw magnitudes see the exposure change as more change than 30 cm of travel...
    EXPECT_GT(dis(raw, panorama, darker), dis(raw, panorama, elsewhere)) << to_string(mode);
    // ...normalised ones see only the rounding, far less than the travel.
    EXPECT_LT(dis(normalised, panorama, darker), 0.1 * dis(normalised, panorama, elsewhere))
        << to_string(mode);
    // Each channel's mean component is 128 after normalisation.
    const Signature s = normalised.compute(panorama);
    for (int c = 0; c < s.channels; ++c) {
      double mean = 0.0;
      for (int y = 0; y < s.rows; ++y) mean += s.magnitude[s.at(c * s.rows + y, 0)] / s.rows;
      EXPECT_NEAR(mean, 128.0, 1e-3);
    }
  }
}

TEST(ColourMode, NamesRoundTrip) {
  EXPECT_EQ(colour_mode_from_string(to_string(ColourMode::kLuminance)), ColourMode::kLuminance);
  EXPECT_EQ(colour_mode_from_string(to_string(ColourMode::kPerChannel)), ColourMode::kPerChannel);
  EXPECT_THROW(colour_mode_from_string("rgb"), UsageError);
}

// A value set in code, as Python's writable fields set it, is refused by the extractor as the
// YAML loader refuses it in memory.yaml, naming the key (SignatureParams::check).
TEST(Signature, ComponentsOutOfRangeAreRefusedByTheExtractor) {
  SignatureParams params;
  params.components = 0;
  try {
    SignatureExtractor extractor(params);
    ADD_FAILURE() << "0 components were accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("signature.components"), std::string::npos);
  }
  params.components = 5000;
  EXPECT_THROW(SignatureExtractor{params}, UsageError);
  params.components = 4096;
  EXPECT_NO_THROW(SignatureExtractor{params});
}

}  // namespace
}  // namespace omninav::signature
