#include "omninav/io/panorama_input.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "io_test_support.hpp"
#include "omninav/io/image_file.hpp"

namespace omninav::io {
namespace {

using testing::make_image;
using testing::TempDir;

// A raw camera whose annulus fills a 64 × 64 image, unwrapped to 36 × 8 panoramas.
omni::UnwrapParams small_camera() {
  omni::UnwrapParams params;
  params.units = omni::LengthUnits::kPixels;
  params.centre_x = 32.0;
  params.centre_y = 32.0;
  params.inner_radius = 8.0;
  params.outer_radius = 30.0;
  params.width_px = 36;
  params.height_px = 8;
  return params;
}

TEST(ImageFileName, KnowsTheImageExtensionsInAnyCase) {
  for (const char* name :
       {"a.png", "b.JPG", "c.jpeg", "d.Bmp", "e.tif", "f.TIFF", "g.ppm", "dir/h.pgm"}) {
    EXPECT_TRUE(is_image_file_name(name)) << name;
  }
  for (const char* name : {"a.csv", "b.mp4", "png", "c.png.txt", "folder/"}) {
    EXPECT_FALSE(is_image_file_name(name)) << name;
  }
}

TEST(PanoramaInput, ASingleImageIsOneFrameWithAnAbsoluteSource) {
  TempDir dir;
  cv::imwrite((dir / "one.png").string(), make_image(5));
  int asked = 0;
  PanoramaInput input(dir / "one.png", [&asked] { return ++asked, small_camera(); }, {});
  EXPECT_EQ(input.size(), 1u);
  EXPECT_FALSE(input.is_grid());
  const std::optional<Frame> frame = input.next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(testing::index_of(frame->image), 5);
  EXPECT_EQ(frame->source, std::filesystem::absolute(dir / "one.png").lexically_normal().string());
  EXPECT_FALSE(input.next());
  EXPECT_EQ(asked, 0) << "nothing to unwrap: camera.yaml is never read";
}

TEST(PanoramaInput, UnwrapsEveryFrameWhenAskedWithTheParametersReadOnce) {
  TempDir dir;
  for (int i = 0; i < 3; ++i) {
    cv::imwrite((dir / ("raw_" + std::to_string(i) + ".png")).string(),
                make_image(i, cv::Size(64, 64)));
  }
  int asked = 0;
  PanoramaInput input(dir.path(), [&asked] { return ++asked, small_camera(); },
                      {.force_unwrap = true, .absolute_sources = false});
  EXPECT_TRUE(input.unwraps());
  EXPECT_NE(input.describe().find("(unwrapped with camera.yaml)"), std::string::npos);
  int frames = 0;
  while (const std::optional<Frame> frame = input.next()) {
    EXPECT_EQ(frame->image.size(), cv::Size(36, 8)) << frame->source;
    EXPECT_EQ(frame->source, (dir / ("raw_" + std::to_string(frames) + ".png")).string());
    ++frames;
  }
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(asked, 1);
}

}  // namespace
}  // namespace omninav::io
