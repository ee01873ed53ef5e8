#pragma once
// Building blocks of the generated worlds (room, house, field, office): materials, textured
// quads, walls and boxes appended to a World.

#include <array>
#include <opencv2/core.hpp>
#include <string>

#include "omninav/sim/world.hpp"

namespace omninav::sim::build {

// A textured material (white, so the texture shows as it is); returns its index.
int add_material(World& world, std::string name, cv::Mat texture);
// A flat-coloured material; returns its index.
int add_colour(World& world, std::string name, const cv::Vec3f& colour_bgr);

// A planar quad a-b-c-d (in order around its edge) as two triangles, with the texture
// coordinates of its corners.
void add_quad(World& world, const std::array<cv::Vec3f, 4>& corners,
              const std::array<cv::Vec2f, 4>& uv, int material);

// A vertical wall from `from` to `to`, floor to `height`, its texture spanning it once.
void add_wall(World& world, cv::Vec2f from, cv::Vec2f to, float height, int material);

// An upright box on the floor, from z = `bottom` to z = `top`: four sides and a top, its 1 m
// texture tiled in metres along each face.
void add_box(World& world, const FloorBox& box, float top, int material, float bottom = 0.f);

// True when the boxes come closer than gap_m.
bool overlaps(const FloorBox& a, const FloorBox& b, double gap_m);

}  // namespace omninav::sim::build
