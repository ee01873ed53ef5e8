#include "omninav/measures/contact_sheet.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "measures/scratch_dir.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/measures/png.hpp"

namespace omninav::measures {
namespace {

using testing::ScratchDir;

cv::Vec3b at(const cv::Mat& image, int x, int y) {
  return image.at<cv::Vec3b>(y, x);
}

TEST(ContactSheet, LayoutAndEachImageInItsCell) {
  const cv::Mat grey(45, 360, CV_8UC1, cv::Scalar(50));           // factor 2 → 720×90
  const cv::Mat red(45, 360, CV_8UC3, cv::Scalar(0, 0, 255));     // factor 2 → 720×90
  const cv::Mat green(100, 200, CV_8UC3, cv::Scalar(0, 255, 0));  // factor 4 → 800×400
  const ContactSheetParams params;  // 720 px, margin 10, caption band 30
  const cv::Mat sheet = contact_sheet({grey, red, green}, {"grey", "red", "green"}, 2, params);

  // cell_w = 800, image_h = 400, cell_h = 430; 2 columns, 2 rows:
  // width 10 + 2·(800 + 10) = 1630, height 10 + 2·(430 + 10) = 890.
  ASSERT_EQ(sheet.type(), CV_8UC3);
  ASSERT_EQ(sheet.cols, 1630);
  ASSERT_EQ(sheet.rows, 890);

  // Image 0: column 0, row 0, x = 10 + (800 − 720)/2 = 50, y = 10, 720×90.
  EXPECT_EQ(at(sheet, 50, 10), cv::Vec3b(50, 50, 50));
  EXPECT_EQ(at(sheet, 50 + 719, 10 + 89), cv::Vec3b(50, 50, 50));
  EXPECT_EQ(at(sheet, 49, 50), cv::Vec3b(200, 200, 200));    // just left of it: background
  EXPECT_EQ(at(sheet, 100, 100), cv::Vec3b(200, 200, 200));  // just below it, above the caption
  // Image 1: column 1, x = 10 + 810 + 40 = 860.
  EXPECT_EQ(at(sheet, 860, 10), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(at(sheet, 860 + 719, 99), cv::Vec3b(0, 0, 255));
  // Image 2: column 0, row 1, x = 10, y = 10 + 440 = 450, 800×400.
  EXPECT_EQ(at(sheet, 10, 450), cv::Vec3b(0, 255, 0));
  EXPECT_EQ(at(sheet, 809, 849), cv::Vec3b(0, 255, 0));
  // The fourth cell is empty.
  EXPECT_EQ(at(sheet, 1200, 650), cv::Vec3b(200, 200, 200));

  // Each caption puts dark text in the band under its cell's image band (y 410..440).
  auto dark_pixels_in = [&](const cv::Rect& band) {
    int count = 0;
    for (int y = band.y; y < band.br().y; ++y) {
      for (int x = band.x; x < band.br().x; ++x) count += at(sheet, x, y)[0] < 100;
    }
    return count;
  };
  EXPECT_GT(dark_pixels_in(cv::Rect(10, 410, 800, 30)), 20);
  EXPECT_GT(dark_pixels_in(cv::Rect(820, 410, 800, 30)), 20);
  EXPECT_GT(dark_pixels_in(cv::Rect(10, 850, 800, 30)), 20);
  EXPECT_EQ(dark_pixels_in(cv::Rect(820, 850, 800, 30)), 0);
}

TEST(ContactSheet, NearestEnlargementKeepsEveryPixel) {
  // Column stripes of a 360×45 panorama, factor 2: source pixel (x, y) fills the 2×2 block
  // at (10 + 2x, 10 + 2y) (a single cell is as wide as its image, so no centring offset).
  cv::Mat panorama(45, 360, CV_8UC3);
  for (int y = 0; y < 45; ++y) {
    for (int x = 0; x < 360; ++x) panorama.at<cv::Vec3b>(y, x) = cv::Vec3b(x % 256, 5 * y, 77);
  }
  const cv::Mat sheet = contact_sheet({panorama}, {}, 3);
  ASSERT_EQ(sheet.size(), cv::Size(10 + 720 + 10, 10 + 90 + 30 + 10));
  for (int y = 0; y < 45; y += 4) {
    for (int x = 0; x < 360; x += 7) {
      const cv::Vec3b source = panorama.at<cv::Vec3b>(y, x);
      EXPECT_EQ(at(sheet, 10 + 2 * x, 10 + 2 * y), source);
      EXPECT_EQ(at(sheet, 11 + 2 * x, 11 + 2 * y), source);
    }
  }
}

TEST(ContactSheet, WideImagesKeepTheirSize) {
  const cv::Mat wide(10, 1000, CV_8UC3, cv::Scalar(1, 2, 3));
  const cv::Mat sheet = contact_sheet({wide},
                                      {"a caption far too long to fit under the image "
                                       "so it is shrunk and then cut short"},
                                      1, {.min_width_px = 720, .margin_px = 0});
  EXPECT_EQ(sheet.size(), cv::Size(1000, 10 + 30));
}

TEST(ContactSheet, RejectsBadArguments) {
  const cv::Mat image(45, 360, CV_8UC3, cv::Scalar::all(0));
  EXPECT_THROW(contact_sheet({}, {}, 2), UsageError);
  EXPECT_THROW(contact_sheet({image, image}, {"one"}, 2), UsageError);
  EXPECT_THROW(contact_sheet({image}, {}, 0), UsageError);
  EXPECT_THROW(contact_sheet({image, cv::Mat()}, {}, 2), UsageError);
  EXPECT_THROW(contact_sheet({cv::Mat(45, 360, CV_32FC1, cv::Scalar(0))}, {}, 2), UsageError);
  EXPECT_THROW(contact_sheet({cv::Mat(45, 360, CV_8UC2, cv::Scalar(0))}, {}, 2), UsageError);
}

TEST(SavePng, RoundTripsAndNamesTheFileOnFailure) {
  ScratchDir dir("save_png");
  cv::Mat image(45, 360, CV_8UC3);
  cv::randu(image, 0, 255);
  // PNG whatever the extension: the bytes are PNG, imread sniffs the content.
  for (const char* name : {"a.png", "b.dat"}) {
    save_png(image, dir / name);
    const cv::Mat read = cv::imread((dir / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(read.size(), image.size()) << name;
    EXPECT_EQ(cv::norm(read, image, cv::NORM_INF), 0.0) << name;
  }
  const std::filesystem::path bad = dir / "no_such_folder" / "x.png";
  try {
    save_png(image, bad);
    FAIL() << "no error for " << bad;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(save_png(cv::Mat(), dir / "empty.png"), UsageError);
  EXPECT_THROW(save_png(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0)), dir / "float.png"), UsageError);
}

}  // namespace
}  // namespace omninav::measures
