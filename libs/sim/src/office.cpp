#include "omninav/sim/office.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "room_textures.hpp"
#include "world_builder.hpp"

namespace omninav::sim {
namespace {

constexpr double kEndAisle_m = 1.5;   // from the end walls to the first and last desk slot
constexpr double kSideAisle_m = 0.9;  // from the side walls to the first and last row
constexpr double kDeskWidth_m = 1.4, kDeskDepth_m = 0.7, kDeskHeight_m = 0.74;
constexpr double kChairSide_m = 0.5, kChairGap_m = 0.25;
constexpr double kColumnSide_m = 0.35;

int px(double metres, double px_per_m) {
  return std::max(1, static_cast<int>(std::lround(metres * px_per_m)));
}

// A wall of plain paint with windows centred at `window_centres_m` (none for an inner wall).
cv::Mat office_wall(double width_m, double height_m, double px_per_m, const cv::Scalar& paint,
                    const std::vector<double>& window_centres_m, cv::RNG& rng) {
  cv::Mat image = textures::painted_wall(width_m, height_m, px_per_m, paint, false, rng);
  for (const double centre : window_centres_m) {
    const cv::Rect window(px(centre - 0.6, px_per_m), image.rows - px(2.2, px_per_m),
                          px(1.2, px_per_m), px(1.3, px_per_m));
    cv::rectangle(image, window, cv::Scalar(235, 220, 205), cv::FILLED);
    cv::rectangle(image, window, cv::Scalar(90, 90, 95), std::max(2, px(0.05, px_per_m)));
    cv::line(image, {window.x + window.width / 2, window.y},
             {window.x + window.width / 2, window.y + window.height}, cv::Scalar(90, 90, 95),
             std::max(1, px(0.03, px_per_m)));
  }
  return image;
}

// Grey carpet tiles of 0.5 m, each a little lighter or darker.
cv::Mat carpet_tiles(double width_m, double depth_m, double px_per_m, cv::RNG& rng) {
  const cv::Scalar grey = textures::random_colour(rng, 70, 150);
  cv::Mat image(px(depth_m, px_per_m), px(width_m, px_per_m), CV_8UC3, grey);
  const int tile = px(0.5, px_per_m);
  for (int y = 0; y < image.rows; y += tile) {
    for (int x = 0; x < image.cols; x += tile) {
      const double tone = ((x / tile + y / tile) % 2 == 0) ? 1.0 : 0.9;
      cv::rectangle(image, cv::Rect(x, y, tile, tile), grey * tone, cv::FILLED);
    }
  }
  textures::add_smooth_noise(image, 0.1, px_per_m, 4.0, rng);
  return image;
}

// A white ceiling with a light panel above every desk slot.
cv::Mat ceiling_lights(double width_m, double depth_m, double px_per_m,
                       const std::vector<cv::Point2d>& lights_m, cv::RNG& rng) {
  cv::Mat image(px(depth_m, px_per_m), px(width_m, px_per_m), CV_8UC3, cv::Scalar(230, 232, 232));
  textures::add_smooth_noise(image, 1.0, px_per_m, 3.0, rng);
  for (const cv::Point2d& light : lights_m) {
    cv::rectangle(image,
                  cv::Rect(px(light.x - 0.6, px_per_m), px(light.y - 0.3, px_per_m),
                           px(1.2, px_per_m), px(0.6, px_per_m)),
                  cv::Scalar(255, 255, 255), cv::FILLED);
  }
  return image;
}

struct DeskMaterials {
  int top, panel, screen, chair;
};

// A desk centred at (x, y) facing south: top, side and modesty panels, a screen, and a chair
// south of it. Returns the footprints of the desk and of the chair.
std::array<FloorBox, 2> add_desk(World& world, double x, double y, const DeskMaterials& m) {
  const double hw = kDeskWidth_m / 2, hd = kDeskDepth_m / 2;
  const FloorBox desk{x - hw, y - hd, x + hw, y + hd};
  const float top = static_cast<float>(kDeskHeight_m);
  build::add_box(world, desk, top, m.top, top - 0.04f);
  build::add_box(world, {x - hw, y - hd, x - hw + 0.03, y + hd}, top - 0.04f, m.panel);
  build::add_box(world, {x + hw - 0.03, y - hd, x + hw, y + hd}, top - 0.04f, m.panel);
  build::add_box(world, {x - hw, y + hd - 0.03, x + hw, y + hd}, top - 0.04f, m.panel, 0.15f);
  build::add_box(world, {x - 0.3, y + 0.1, x + 0.3, y + 0.14}, top + 0.45f, m.screen, top + 0.1f);
  build::add_box(world, {x - 0.04, y + 0.14, x + 0.04, y + 0.18}, top + 0.1f, m.screen, top);
  const double cy = y - hd - kChairGap_m - kChairSide_m / 2;
  const double hc = kChairSide_m / 2;
  const FloorBox chair{x - hc, cy - hc, x + hc, cy + hc};
  build::add_box(world, {x - 0.04, cy - 0.04, x + 0.04, cy + 0.04}, 0.42f, m.panel);
  build::add_box(world, chair, 0.5f, m.chair, 0.42f);
  build::add_box(world, {x - hc, cy - hc, x + hc, cy - hc + 0.06}, 0.95f, m.chair, 0.5f);
  return {desk, chair};
}

// Where the desks stand: x of a column, y of a row, and the floor's size.
struct OfficeGrid {
  const OfficeParams& params;
  double size_x = 0.0, size_y = 0.0;

  double desk_x(int column) const { return kEndAisle_m + params.desk_pitch_m * (column + 0.5); }
  double row_y(int row) const { return kSideAisle_m + params.row_pitch_m * (row + 0.5); }
};

// Walls in one paint, windows along the north wall at the desks' pitch; carpet tiles; a ceiling
// with a light over every desk.
void add_office_room(World& world, const OfficeGrid& grid, cv::RNG& rng) {
  const OfficeParams& params = grid.params;
  const double ppm = params.texture_px_per_m;
  const float lx = static_cast<float>(grid.size_x), ly = static_cast<float>(grid.size_y);
  const float height = static_cast<float>(params.height_m);
  const cv::Scalar paint(rng.uniform(200, 235), rng.uniform(205, 235), rng.uniform(205, 235));
  std::vector<double> windows;
  for (int column = 0; column < params.desks_per_row; ++column) {
    windows.push_back(grid.size_x - grid.desk_x(column));  // the north wall runs east to west
  }
  const std::array<cv::Vec2f, 5> corners{cv::Vec2f(0.f, 0.f), cv::Vec2f(lx, 0.f), cv::Vec2f(lx, ly),
                                         cv::Vec2f(0.f, ly), cv::Vec2f(0.f, 0.f)};
  for (int side = 0; side < 4; ++side) {
    const double length_m = cv::norm(corners[side + 1] - corners[side]);
    const int material =
        build::add_material(world, "wall " + std::to_string(side),
                            office_wall(length_m, params.height_m, ppm, paint,
                                        side == 2 ? windows : std::vector<double>{}, rng));
    build::add_wall(world, corners[side], corners[side + 1], height, material);
  }
  const std::array<cv::Vec2f, 4> whole{cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f),
                                       cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)};
  build::add_quad(
      world,
      {cv::Vec3f(0.f, 0.f, 0.f), cv::Vec3f(lx, 0.f, 0.f), cv::Vec3f(lx, ly, 0.f),
       cv::Vec3f(0.f, ly, 0.f)},
      whole, build::add_material(world, "floor", carpet_tiles(grid.size_x, grid.size_y, ppm, rng)));
  // Texture rows run from the top (v = 1, y = size_y) down.
  std::vector<cv::Point2d> lights;
  for (int row = 0; row < params.rows; ++row) {
    for (int column = 0; column < params.desks_per_row; ++column) {
      lights.emplace_back(grid.desk_x(column), grid.size_y - grid.row_y(row));
    }
  }
  build::add_quad(world,
                  {cv::Vec3f(0.f, 0.f, height), cv::Vec3f(lx, 0.f, height),
                   cv::Vec3f(lx, ly, height), cv::Vec3f(0.f, ly, height)},
                  whole,
                  build::add_material(world, "ceiling",
                                      ceiling_lights(grid.size_x, grid.size_y, ppm, lights, rng)));
}

// The office's furniture scheme, the same for every desk, depends on the seed: a desk top of
// light or dark wood, white or grey laminate; grey panels; a dark chair.
DeskMaterials desk_materials(World& world, cv::RNG& rng) {
  const std::array<cv::Vec3f, 4> tops{
      {{150.f, 185.f, 210.f}, {60.f, 90.f, 125.f}, {225.f, 225.f, 220.f}, {150.f, 155.f, 160.f}}};
  const float panel_grey = static_cast<float>(rng.uniform(90, 200));
  const int top = build::add_colour(
      world, "desk top", tops[rng.uniform(0, 4)] * static_cast<float>(rng.uniform(0.9, 1.1)));
  const int panel =
      build::add_colour(world, "desk panel", {panel_grey, panel_grey, panel_grey * 0.95f});
  const int screen = build::add_colour(world, "screen", {35.f, 30.f, 30.f});
  const cv::Scalar chair = textures::random_colour(rng, 25, 110);
  return {top, panel, screen,
          build::add_colour(world, "chair",
                            cv::Vec3f(static_cast<float>(chair[0]), static_cast<float>(chair[1]),
                                      static_cast<float>(chair[2])))};
}

// A plant, a box of files, a lamp... on the desk at (x, y), with probability params.clutter.
void maybe_add_clutter(World& world, double desk_x, double desk_y, const OfficeParams& params,
                       cv::RNG& rng) {
  if (rng.uniform(0.0, 1.0) >= params.clutter) return;
  const double side = rng.uniform(0.1, 0.35);
  const double x = desk_x + rng.uniform(-0.6, 0.6 - side);
  const double y = desk_y + rng.uniform(-0.3, 0.3 - side);
  const cv::Scalar colour = textures::random_colour(rng, 20, 240);
  build::add_box(world, {x, y, x + side, y + side},
                 static_cast<float>(kDeskHeight_m + rng.uniform(0.1, 0.5)),
                 build::add_colour(world, "clutter",
                                   {static_cast<float>(colour[0]), static_cast<float>(colour[1]),
                                    static_cast<float>(colour[2])}),
                 static_cast<float>(kDeskHeight_m));
}

// Identical desks in rows, columns between every column_every-th pair of desks.
void add_desk_rows(World& world, const OfficeGrid& grid, cv::RNG& rng) {
  const OfficeParams& params = grid.params;
  const DeskMaterials desk = desk_materials(world, rng);
  const int column_material = build::add_colour(world, "column", {200.f, 200.f, 195.f});
  for (int row = 0; row < params.rows; ++row) {
    for (int column = 0; column < params.desks_per_row; ++column) {
      for (const FloorBox& box : add_desk(world, grid.desk_x(column), grid.row_y(row), desk)) {
        world.obstacles.push_back(box);
      }
      maybe_add_clutter(world, grid.desk_x(column), grid.row_y(row), params, rng);
    }
    for (int gap = params.column_every; gap < params.desks_per_row; gap += params.column_every) {
      const double x = kEndAisle_m + params.desk_pitch_m * gap, y = grid.row_y(row);
      const double h = kColumnSide_m / 2;
      const FloorBox column{x - h, y - h, x + h, y + h};
      build::add_box(world, column, static_cast<float>(params.height_m), column_material);
      world.obstacles.push_back(column);
    }
  }
}

}  // namespace

World make_office(const OfficeParams& params) {
  World world;
  world.name = "office";
  cv::RNG rng(static_cast<std::uint64_t>(params.seed) * 7919 + 43);
  const OfficeGrid grid{params, 2 * kEndAisle_m + params.desks_per_row * params.desk_pitch_m,
                        2 * kSideAisle_m + params.rows * params.row_pitch_m};
  world.floor = {0.0, 0.0, grid.size_x, grid.size_y};
  add_office_room(world, grid, rng);
  add_desk_rows(world, grid, rng);
  return world;
}

}  // namespace omninav::sim
