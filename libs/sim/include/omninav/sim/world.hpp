#pragma once
// A world the renderer can draw: textured triangles in metres, z up (docs/design.md, Worlds).
// Both the built-in room (room.hpp) and Wavefront OBJ files (load_obj_world) become one.

#include <array>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace omninav::sim {

struct Material {
  std::string name;
  cv::Vec3f colour_bgr{200.f, 200.f, 200.f};  // 0..255; multiplies the texture when there is one
  int texture = -1;                           // index into World::textures, or -1
};

struct Triangle {
  std::array<int, 3> vertex{};    // indices into World::vertices
  std::array<cv::Vec2f, 3> uv{};  // texture coordinates of the corners (repeat wrap)
  int material = 0;               // index into World::materials
};

// An axis-aligned floor rectangle the robot cannot enter (furniture), or the free area.
struct FloorBox {
  double min_x_m = 0.0, min_y_m = 0.0, max_x_m = 0.0, max_y_m = 0.0;
  bool contains(double x_m, double y_m) const {
    return x_m >= min_x_m && x_m <= max_x_m && y_m >= min_y_m && y_m <= max_y_m;
  }
};

// A named part of the floor (a room or corridor of a house), so that evaluation can tell
// whether a place was recognised in the right room.
struct Region {
  std::string name;
  FloorBox area;
};

struct World {
  std::string name;
  std::vector<cv::Vec3f> vertices;  // metres, z up
  std::vector<Triangle> triangles;
  std::vector<Material> materials;
  std::vector<cv::Mat> textures;               // 8-bit BGR
  cv::Vec3f background_bgr{40.f, 40.f, 40.f};  // what a ray that hits nothing sees
  // When set, a ray that hits nothing above the horizon sees a sky blending from
  // background_bgr at the horizon to this colour at the zenith (outdoor worlds).
  std::optional<cv::Vec3f> sky_zenith_bgr;

  // Where a robot may stand: inside `floor`, outside every obstacle (for trajectories and the
  // navigator). For OBJ worlds the floor is the bounding box and there are no obstacles.
  FloorBox floor;
  std::vector<FloorBox> obstacles;

  // Named floor rectangles (a house's rooms and corridor; empty for other worlds). They do
  // not overlap; a point in a doorway or a wall may be in none.
  std::vector<Region> regions;

  bool is_free(double x_m, double y_m, double clearance_m = 0.0) const;
  // True when every point of the segment from (x0, y0) to (x1, y1) is free: inside the floor
  // and clear of every obstacle by clearance_m (a thin wall between the ends is a collision).
  bool segment_is_free(double x0_m, double y0_m, double x1_m, double y1_m,
                       double clearance_m = 0.0) const;
  // The region containing (x, y), or nullptr when none does.
  const Region* region_at(double x_m, double y_m) const;
};

// How to read an OBJ file: its axis convention and unit.
struct ObjWorldParams {
  bool y_up = false;        // true for files whose up axis is +y (then y→z, z→−y)
  double scale_to_m = 1.0;  // multiply coordinates by this to get metres
};

// Loads a Wavefront OBJ with its MTL diffuse colours (Kd) and textures (map_Kd, relative to
// the MTL file). Throws InputError naming the file on a missing file, a parse error, or a
// texture that cannot be read.
World load_obj_world(const std::filesystem::path& obj_file, const ObjWorldParams& params = {});

}  // namespace omninav::sim
