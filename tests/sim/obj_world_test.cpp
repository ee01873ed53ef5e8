#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/world.hpp"
#include "support/png_header.hpp"
#include "support/shared_data.hpp"

namespace omninav::sim {
namespace {

class TempFolder {
 public:
  TempFolder()
      : path_(std::filesystem::temp_directory_path() /
              ("omninav_obj_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A 2 m cube around the origin, seen from inside: the +x wall textured (left half blue, right
// half green in the texture), the other faces one diffuse colour.
void write_textured_cube(const std::filesystem::path& folder) {
  cv::Mat texture(64, 64, CV_8UC3, cv::Scalar(255, 0, 0));
  texture.colRange(32, 64).setTo(cv::Scalar(0, 255, 0));
  cv::imwrite((folder / "wall.png").string(), texture);
  std::ofstream(folder / "cube.mtl") << "newmtl painted\nKd 1 1 1\nmap_Kd wall.png\n"
                                        "newmtl plain\nKd 0.8 0.2 0.2\n";
  std::ofstream obj(folder / "cube.obj");
  obj << "mtllib cube.mtl\n"
      << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      // The +x wall, as a quad from y = -1 (u = 0) to y = +1 (u = 1).
      << "usemtl painted\nf 2/1 3/2 7/3 6/4\n"
      << "usemtl plain\nf 1 2 6 5\nf 3 4 8 7\nf 4 1 5 8\nf 1 4 3 2\nf 5 6 7 8\n";
}

TEST(ObjWorld, LoadsGeometryMaterialsAndTextures) {
  TempFolder folder;
  write_textured_cube(folder.path());
  const World world = load_obj_world(folder.path() / "cube.obj");
  EXPECT_EQ(world.vertices.size(), 8u);
  EXPECT_EQ(world.triangles.size(), 12u);  // six quads, triangulated
  ASSERT_EQ(world.textures.size(), 1u);
  EXPECT_NEAR(world.floor.min_x_m, -1.0, 1e-6);
  EXPECT_NEAR(world.floor.max_y_m, 1.0, 1e-6);
}

TEST(ObjWorld, TextureAppearsWhereItsCoordinatesPutIt) {
  TempFolder folder;
  write_textured_cube(folder.path());
  const World world = load_obj_world(folder.path() / "cube.obj");
  RenderParams params;
  params.geometry.width_px = 360;
  params.geometry.height_px = 30;
  const cv::Mat panorama = Renderer(world, params).render({0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  // Facing +x: u grows with y, so the texture's left half (blue, u < 0.5, y < 0) is on the
  // robot's right (azimuth −20°), its right half (green, y > 0) on the left (azimuth +20°).
  const cv::Vec3b right =
      panorama.at<cv::Vec3b>(15, static_cast<int>(column_of_azimuth(deg_to_rad(-20), 360)));
  const cv::Vec3b left =
      panorama.at<cv::Vec3b>(15, static_cast<int>(column_of_azimuth(deg_to_rad(20), 360)));
  EXPECT_GT(right[0], 100);
  EXPECT_LT(right[1], 30);
  EXPECT_GT(left[1], 100);
  EXPECT_LT(left[0], 30);
  // Behind, the plain material: red dominates (Kd 0.8 0.2 0.2).
  const cv::Vec3b behind = panorama.at<cv::Vec3b>(15, 270);
  EXPECT_GT(behind[2], 2 * behind[1]);
}

TEST(ObjWorld, BadFilesAreClearErrors) {
  TempFolder folder;
  EXPECT_THROW(load_obj_world(folder.path() / "missing.obj"), InputError);
  write_textured_cube(folder.path());
  std::filesystem::remove(folder.path() / "wall.png");
  try {
    load_obj_world(folder.path() / "cube.obj");
    FAIL();
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("wall.png"), std::string::npos) << error.what();
  }
  std::ofstream(folder.path() / "empty.obj") << "# nothing\n";
  EXPECT_THROW(load_obj_world(folder.path() / "empty.obj"), InputError);
}

TEST(ObjWorld, ATextureDeclaringTooManyPixelsIsRefusedBeforeDecoding) {
  // A texture is bounded as every input image is (core/image_size.hpp): a PNG header declaring
  // 20000 x 20000 (1.2 GB decoded) is refused from the header, naming the texture.
  TempFolder folder;
  write_textured_cube(folder.path());
  testing::write_header_only_png(folder.path() / "wall.png", 20000, 20000);
  try {
    load_obj_world(folder.path() / "cube.obj");
    ADD_FAILURE() << "loaded";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("wall.png: image is 20000x20000 px, more than omninav reads"),
              std::string::npos)
        << what;
  }
  // Within the limit the header passes, and the missing pixels are what is wrong.
  testing::write_header_only_png(folder.path() / "wall.png", 64, 64);
  try {
    load_obj_world(folder.path() / "cube.obj");
    ADD_FAILURE() << "loaded";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot read the texture of material 'painted'"),
              std::string::npos)
        << error.what();
  }
}

TEST(ObjWorld, VerticesThatAreNotFinitePositionsAreRefused) {
  TempFolder folder;
  for (const std::string bad : {"nan", "inf", "-inf", "1e30"}) {
    SCOPED_TRACE(bad);
    std::ofstream(folder.path() / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 " << bad << " 1\nf 1 2 3\n";
    try {
      load_obj_world(folder.path() / "bad.obj");
      ADD_FAILURE() << "loaded";
    } catch (const InputError& error) {
      // Text that is no number is refused as it is read (tinyobjloader would read it as 0); a
      // number beyond the bound, once placed in the world.
      const std::string why = bad == "1e30" ? "bad.obj: vertex 3 y: 1e+30 m is not a position"
                                            : "bad.obj:3: vertex coordinate '" + bad + "'";
      EXPECT_NE(std::string(error.what()).find(why), std::string::npos) << error.what();
    }
  }
}

TEST(ObjWorld, TextureCoordinatesThatAreNotFiniteOrFarBeyondTheTextureAreRefused) {
  // (1e30 once reached the renderer's float-to-int wrapping: undefined behaviour, found by the
  // obj fuzz target.)
  TempFolder folder;
  for (const std::string bad : {"nan", "inf", "1e30", "-2e6"}) {
    SCOPED_TRACE(bad);
    std::ofstream(folder.path() / "bad.obj")
        << "v 0 0 0\nv 1 0 0\nv 0 1 1\nvt 0 0\nvt " << bad << " 0\nvt 1 1\nf 1/1 2/2 3/3\n";
    try {
      load_obj_world(folder.path() / "bad.obj");
      ADD_FAILURE() << "loaded";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("bad.obj:5: texture coordinate '" + bad + "'"),
                std::string::npos)
          << error.what();
    }
  }
  // A texture repeated many times is fine.
  std::ofstream(folder.path() / "tiled.obj")
      << "v 0 0 0\nv 1 0 0\nv 0 1 1\nvt 0 0\nvt 1000 0\nvt 1 1\nf 1/1 2/2 3/3\n";
  EXPECT_NO_THROW(load_obj_world(folder.path() / "tiled.obj"));
}

TEST(ObjWorld, AFileThatIsNoRegularFileIsNamedForWhatItIs) {
  TempFolder folder;
  const std::filesystem::path fifo = folder.path() / "world.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const auto& [file, why] : std::vector<std::pair<std::filesystem::path, std::string>>{
           {"/dev/zero", "/dev/zero: is a device, not an OBJ file"},
           {fifo, "world.obj: is a FIFO, not an OBJ file"},
           {folder.path() / "missing.obj", "missing.obj: no such OBJ file"}}) {
    try {
      load_obj_world(file);
      ADD_FAILURE() << file;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(why), std::string::npos) << error.what();
    }
  }
}

TEST(ObjWorld, OfstadArenaLoadsAndRendersItsTexture) {
  OMNINAV_REQUIRE_SHARED_DATA("worlds/ofstad/ofstad.obj");
  const World world =
      load_obj_world(omninav::testing::shared_data_dir() / "worlds/ofstad/ofstad.obj");
  EXPECT_EQ(world.triangles.size(), 64u);
  ASSERT_EQ(world.textures.size(), 1u);
  RenderParams params;
  params.geometry.elevation_min_rad = deg_to_rad(-20);
  params.geometry.elevation_max_rad = deg_to_rad(20);
  // The arena is 0.123 m in radius and 0.256 m tall: look from its centre at mid-height.
  const cv::Mat panorama = Renderer(world, params).render({0.0, 0.0, 0.128, 0.0, 0.0, 0.0});
  cv::Mat grey;
  cv::cvtColor(panorama, grey, cv::COLOR_BGR2GRAY);
  double darkest = 0, brightest = 0;
  cv::minMaxLoc(grey, &darkest, &brightest);
  // The texture is black-and-white bars: both must show.
  EXPECT_LT(darkest, 40);
  EXPECT_GT(brightest, 120);
}

}  // namespace
}  // namespace omninav::sim
