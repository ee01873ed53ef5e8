// Real panoramas: shared/data/real/ftl-arena/route/ (130 consecutive frames of a PixPro camera
// carried through an arena, 180×50, no poses; shared/data/README.md). Skipped when absent.
#include <gtest/gtest.h>

#include <iostream>

#include "omninav/core/angles.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/phase_heading.hpp"
#include "support/shared_data.hpp"

namespace omninav::signature {
namespace {

std::vector<Signature> route_signatures(ColourMode mode) {
  const std::filesystem::path folder = omninav::testing::shared_data_dir() / "real/ftl-arena/route";
  SignatureExtractor extractor({15, mode});
  std::vector<Signature> out;
  for (int i = 0; i < 130; ++i) {
    const std::filesystem::path file = folder / ("snapshot_" + std::to_string(i) + ".png");
    out.push_back(extractor.compute(io::read_image(file), file.string()));
  }
  return out;
}

TEST(RealImages, DissimilarityGrowsWithTheFrameGapOverShortGaps) {
  OMNINAV_REQUIRE_SHARED_DATA("real/ftl-arena/route");
  for (ColourMode mode : {ColourMode::kLuminance, ColourMode::kPerChannel}) {
    const std::vector<Signature> route = route_signatures(mode);
    // Mean Dis over every pair of frames `gap` apart (Fig. 7's linear part, on real images).
    std::vector<double> mean_by_gap;
    for (int gap = 1; gap <= 6; ++gap) {
      double sum = 0.0;
      int count = 0;
      for (std::size_t i = 0; i + gap < route.size(); ++i) {
        sum += dissimilarity(route[i], route[i + gap]);
        ++count;
      }
      mean_by_gap.push_back(sum / count);
    }
    std::cout << to_string(mode) << ": mean Dis by frame gap 1..6:";
    for (double d : mean_by_gap) std::cout << ' ' << d;
    std::cout << "\n";
    for (std::size_t g = 1; g < mean_by_gap.size(); ++g) {
      EXPECT_GT(mean_by_gap[g], mean_by_gap[g - 1]) << to_string(mode) << ", gap " << g + 1;
    }
  }
}

TEST(RealImages, PhaseHeadingRecoversRollsOfRealFrames) {
  OMNINAV_REQUIRE_SHARED_DATA("real/ftl-arena/route");
  const std::filesystem::path folder = omninav::testing::shared_data_dir() / "real/ftl-arena/route";
  SignatureExtractor extractor({15, ColourMode::kLuminance});
  for (int frame : {0, 64, 129}) {
    const cv::Mat image = io::read_image(folder / ("snapshot_" + std::to_string(frame) + ".png"));
    const Signature reference = extractor.compute(image);
    for (double shift : {1.0, -17.0, 45.0, 89.0, -90.0, 30.5, -61.25}) {
      const Signature rolled = extractor.compute(roll_columns_fractional(image, shift));
      const double turn = relative_heading(reference, rolled).turn_rad;
      const double error_columns =
          std::fabs(signed_difference(turn, rotation_of_shift_px(shift, image.cols))) * image.cols /
          kTwoPi;
      EXPECT_LT(error_columns, 0.5) << "frame " << frame << ", roll " << shift;
    }
  }
}

}  // namespace
}  // namespace omninav::signature
