#include "omninav/sim/field.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "room_textures.hpp"
#include "world_builder.hpp"

namespace omninav::sim {
namespace {

constexpr double kMargin_m = 6.0;  // grass, bushes and trees also grow this far round the floor
// The near ground's texture is at most this many pixels on a side (a big field gets a coarser
// one: at 40 px/m a 100 m field would need 20 million pixels and a gigabyte while made).
constexpr double kMaxGroundTexture_px = 2048.0;
const cv::Vec3f kHorizonSky{235.f, 215.f, 195.f};  // BGR: pale near the horizon
const cv::Vec3f kZenithSky{205.f, 150.f, 95.f};    // deeper blue overhead

// Bare soil with patches of moss and dry grass, pebbles and fine grain: `size_m` square.
cv::Mat ground_texture(double size_m, double px_per_m, cv::RNG& rng) {
  const int side = std::max(8, static_cast<int>(std::lround(size_m * px_per_m)));
  cv::Mat soil(side, side, CV_8UC3, cv::Scalar(70, 100, 125));
  // Moss and straw patches, blended in by smooth masks of a metre or two.
  for (const cv::Scalar& patch : {cv::Scalar(55, 115, 85), cv::Scalar(90, 150, 170)}) {
    const int cells = std::max(2, static_cast<int>(size_m / rng.uniform(1.0, 2.5)));
    cv::Mat coarse(cells, cells, CV_32F);
    rng.fill(coarse, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::Mat mask;
    cv::resize(coarse, mask, soil.size(), 0, 0, cv::INTER_CUBIC);
    cv::threshold(mask, mask, 0.55, 1.0, cv::THRESH_TOZERO);
    mask = cv::min(mask * 2.0, 1.0);
    cv::Mat mask3, soil_f;
    cv::merge(std::vector<cv::Mat>{mask, mask, mask}, mask3);
    soil.convertTo(soil_f, CV_32FC3);
    cv::Mat patch_f(soil.size(), CV_32FC3, patch);
    soil_f = soil_f.mul(cv::Scalar::all(1.0) - mask3) + patch_f.mul(mask3);
    soil_f.convertTo(soil, CV_8UC3);
  }
  const int pebbles = static_cast<int>(size_m * size_m * 3.0);
  for (int i = 0; i < pebbles; ++i) {
    const int radius = std::max(1, static_cast<int>(px_per_m * rng.uniform(0.01, 0.05)));
    const int grey = rng.uniform(110, 200);
    cv::circle(soil, {rng.uniform(0, side), rng.uniform(0, side)}, radius,
               cv::Scalar(grey, grey + 5, grey + 10), cv::FILLED, cv::LINE_AA);
  }
  textures::add_smooth_noise(soil, 1.0 / px_per_m, px_per_m, 10.0, rng);  // grain
  textures::add_smooth_noise(soil, 0.7, px_per_m, 12.0, rng);
  return soil;
}

// Greens and straw browns of grass blades, 48 of them, as materials; returns the first index.
int add_grass_palette(World& world, cv::RNG& rng, int count) {
  const int first = static_cast<int>(world.materials.size());
  for (int i = 0; i < count; ++i) {
    cv::Vec3f colour;
    if (i < count / 2) {  // greens
      colour = {static_cast<float>(rng.uniform(25, 70)), static_cast<float>(rng.uniform(95, 170)),
                static_cast<float>(rng.uniform(40, 110))};
    } else if (i < 3 * count / 4) {  // straw
      colour = {static_cast<float>(rng.uniform(50, 95)), static_cast<float>(rng.uniform(120, 175)),
                static_cast<float>(rng.uniform(140, 200))};
    } else {  // dead brown
      colour = {static_cast<float>(rng.uniform(25, 55)), static_cast<float>(rng.uniform(55, 95)),
                static_cast<float>(rng.uniform(80, 125))};
    }
    build::add_colour(world, "grass " + std::to_string(i), colour);
  }
  return first;
}

// A tussock: 8-18 thin blades from a small clump, leaning outwards, as single triangles.
void add_tussock(World& world, double x, double y, double height_m, int palette, int palette_size,
                 cv::RNG& rng) {
  const bool green = rng.uniform(0.0, 1.0) < 0.7;
  const int family_low = green ? 0 : palette_size / 2;
  const int family_high = green ? palette_size / 2 : palette_size;
  const int blades = rng.uniform(8, 19);
  const double clump_m = rng.uniform(0.015, 0.06);
  for (int blade = 0; blade < blades; ++blade) {
    const double azimuth = rng.uniform(0.0, kTwoPi);
    const double offset = clump_m * std::sqrt(rng.uniform(0.0, 1.0));
    const double bx = x + offset * std::cos(azimuth), by = y + offset * std::sin(azimuth);
    const double half_width = rng.uniform(0.004, 0.01);
    const double blade_height = height_m * rng.uniform(0.55, 1.0);
    const double lean = blade_height * rng.uniform(0.05, 0.6);
    const double across = azimuth + kPi / 2 + rng.uniform(-0.6, 0.6);
    const int first = static_cast<int>(world.vertices.size());
    world.vertices.emplace_back(static_cast<float>(bx + half_width * std::cos(across)),
                                static_cast<float>(by + half_width * std::sin(across)), 0.f);
    world.vertices.emplace_back(static_cast<float>(bx - half_width * std::cos(across)),
                                static_cast<float>(by - half_width * std::sin(across)), 0.f);
    world.vertices.emplace_back(static_cast<float>(bx + lean * std::cos(azimuth)),
                                static_cast<float>(by + lean * std::sin(azimuth)),
                                static_cast<float>(blade_height));
    world.triangles.push_back(
        {{first, first + 1, first + 2}, {}, palette + rng.uniform(family_low, family_high)});
  }
}

// A lumpy ellipsoid of flat-shaded facets (a bush, or a tree's crown) centred at `centre`
// with radii `radius_xy` and `radius_z`; its facets take one of `materials` at random.
void add_blob(World& world, cv::Vec3d centre, double radius_xy, double radius_z,
              const std::vector<int>& materials, cv::RNG& rng) {
  constexpr int kRings = 6, kSegments = 10;
  std::vector<std::vector<int>> index(kRings + 1, std::vector<int>(kSegments));
  for (int ring = 0; ring <= kRings; ++ring) {
    const double polar = kPi * ring / kRings;
    for (int segment = 0; segment < kSegments; ++segment) {
      const double azimuth = kTwoPi * (segment + 0.5 * (ring % 2)) / kSegments;
      const double lump = (ring == 0 || ring == kRings) ? 1.0 : rng.uniform(0.75, 1.2);
      index[ring][segment] = static_cast<int>(world.vertices.size());
      world.vertices.emplace_back(
          static_cast<float>(centre[0] + lump * radius_xy * std::sin(polar) * std::cos(azimuth)),
          static_cast<float>(centre[1] + lump * radius_xy * std::sin(polar) * std::sin(azimuth)),
          static_cast<float>(centre[2] + lump * radius_z * std::cos(polar)));
    }
  }
  const auto material = [&] {
    return materials[rng.uniform(0, static_cast<int>(materials.size()))];
  };
  for (int ring = 0; ring < kRings; ++ring) {
    for (int segment = 0; segment < kSegments; ++segment) {
      const int next = (segment + 1) % kSegments;
      const int a = index[ring][segment], b = index[ring][next];
      const int c = index[ring + 1][next], d = index[ring + 1][segment];
      world.triangles.push_back({{a, b, c}, {}, material()});
      world.triangles.push_back({{a, c, d}, {}, material()});
    }
  }
}

// An octagonal trunk from the ground to `height_m`.
void add_trunk(World& world, double x, double y, double radius_m, double height_m,
               const std::vector<int>& materials, cv::RNG& rng) {
  constexpr int kSides = 8;
  for (int side = 0; side < kSides; ++side) {
    const double a0 = kTwoPi * side / kSides, a1 = kTwoPi * (side + 1) / kSides;
    const auto at = [&](double a, double z) {
      return cv::Vec3f(static_cast<float>(x + radius_m * std::cos(a)),
                       static_cast<float>(y + radius_m * std::sin(a)), static_cast<float>(z));
    };
    build::add_quad(world, {at(a0, 0.0), at(a1, 0.0), at(a1, height_m), at(a0, height_m)}, {},
                    materials[rng.uniform(0, static_cast<int>(materials.size()))]);
  }
}

// A smooth random profile round the horizon: a sum of sinusoids of decreasing amplitude.
std::vector<double> horizon_profile(int samples, cv::RNG& rng) {
  std::vector<double> profile(samples, 0.0);
  for (int harmonic = 1; harmonic <= 8; ++harmonic) {
    const double phase = rng.uniform(0.0, kTwoPi);
    const double amplitude = rng.uniform(0.5, 1.0) / harmonic;
    for (int i = 0; i < samples; ++i) {
      profile[i] += amplitude * std::sin(harmonic * kTwoPi * i / samples + phase);
    }
  }
  return profile;
}

// A ring of upright quads round `centre` at `radius_m`, heights `height_m[i]` at sample i.
void add_ring(World& world, cv::Vec2d centre, double radius_m, const std::vector<double>& height_m,
              const std::vector<int>& materials, cv::RNG& rng) {
  const int samples = static_cast<int>(height_m.size());
  for (int i = 0; i < samples; ++i) {
    const int j = (i + 1) % samples;
    const auto at = [&](int k, double z) {
      const double a = kTwoPi * k / samples;
      return cv::Vec3f(static_cast<float>(centre[0] + radius_m * std::cos(a)),
                       static_cast<float>(centre[1] + radius_m * std::sin(a)),
                       static_cast<float>(z));
    };
    build::add_quad(world, {at(i, -1.0), at(j, -1.0), at(j, height_m[j]), at(i, height_m[i])}, {},
                    materials[rng.uniform(0, static_cast<int>(materials.size()))]);
  }
}

// Flat colours around `base`, each channel scaled by up to ±`spread`, mixed `haze` of the way
// towards the horizon sky (distant things are paler).
std::vector<int> add_shades(World& world, const std::string& name, cv::Vec3f base, double spread,
                            double haze, int count, cv::RNG& rng) {
  std::vector<int> materials;
  for (int i = 0; i < count; ++i) {
    cv::Vec3f colour = base * static_cast<float>(rng.uniform(1.0 - spread, 1.0 + spread));
    colour = colour * static_cast<float>(1.0 - haze) + kHorizonSky * static_cast<float>(haze);
    materials.push_back(build::add_colour(world, name + " " + std::to_string(i), colour));
  }
  return materials;
}

}  // namespace

std::string to_string(Horizon horizon) {
  switch (horizon) {
    case Horizon::kTrees:
      return "trees";
    case Horizon::kHills:
      return "hills";
    case Horizon::kNone:
      return "none";
  }
  return "?";
}

Horizon horizon_from_string(std::string_view text) {
  for (const Horizon horizon : {Horizon::kTrees, Horizon::kHills, Horizon::kNone}) {
    if (to_string(horizon) == text) return horizon;
  }
  throw UsageError("horizon '" + std::string(text) + "': expected trees, hills or none");
}

namespace {

// The extent of a field: its floor, the margin round it that holds the same scenery, and the
// distances of the tree line and the hills.
struct FieldExtent {
  double size = 0.0;
  cv::Vec2d centre;
  double near_low = 0.0, near_high = 0.0;
  double tree_line_m = 0.0, hills_m = 0.0;
  double margin_share = 0.0;  // the area of floor and margin over the floor's
};

std::array<cv::Vec3f, 4> flat_quad(double x0, double y0, double x1, double y1, double z) {
  return {cv::Vec3f(static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(z)),
          cv::Vec3f(static_cast<float>(x1), static_cast<float>(y0), static_cast<float>(z)),
          cv::Vec3f(static_cast<float>(x1), static_cast<float>(y1), static_cast<float>(z)),
          cv::Vec3f(static_cast<float>(x0), static_cast<float>(y1), static_cast<float>(z))};
}

// The ground: a unique texture over the floor and its margin, one smooth low-resolution texture
// out to the hills (a little lower, so that the near ground is always hit first). Far away the
// ground is seen at grazing angles, where a tiled texture's repeats would show as a chequer.
void add_ground(World& world, const FieldExtent& extent, const FieldParams& params, cv::RNG& rng) {
  const std::array<cv::Vec2f, 4> whole{cv::Vec2f(0.f, 0.f), cv::Vec2f(1.f, 0.f),
                                       cv::Vec2f(1.f, 1.f), cv::Vec2f(0.f, 1.f)};
  const double near_m = extent.near_high - extent.near_low;
  build::add_quad(
      world, flat_quad(extent.near_low, extent.near_low, extent.near_high, extent.near_high, 0.0),
      whole,
      build::add_material(
          world, "ground",
          ground_texture(near_m, std::min(params.texture_px_per_m, kMaxGroundTexture_px / near_m),
                         rng)));
  const double far = extent.hills_m * 1.05;
  cv::Mat far_ground(512, 512, CV_8UC3, cv::Scalar(75, 120, 135));
  textures::add_smooth_noise(far_ground, 10.0, 512.0 / (2.0 * far), 14.0, rng);
  const cv::Vec2d& c = extent.centre;
  build::add_quad(world, flat_quad(c[0] - far, c[1] - far, c[0] + far, c[1] + far, -0.01), whole,
                  build::add_material(world, "far ground", std::move(far_ground)));
}

// Places round things on the floor and its margin, each at least 0.8 m from the others.
class Spots {
 public:
  Spots(const FieldExtent& extent, cv::RNG& rng) : extent_(extent), rng_(rng) {}

  // A free centre for a thing of `radius_m`, none after 200 tries; its box is last().
  std::optional<cv::Vec2d> place(double radius_m) {
    for (int attempt = 0; attempt < 200; ++attempt) {
      const cv::Vec2d at(rng_.uniform(extent_.near_low + 1.0, extent_.near_high - 1.0),
                         rng_.uniform(extent_.near_low + 1.0, extent_.near_high - 1.0));
      const FloorBox box{at[0] - radius_m, at[1] - radius_m, at[0] + radius_m, at[1] + radius_m};
      bool free = true;
      for (const FloorBox& other : taken_) free = free && !build::overlaps(box, other, 0.8);
      if (!free) continue;
      taken_.push_back(box);
      return at;
    }
    return std::nullopt;
  }
  const FloorBox& last() const { return taken_.back(); }

 private:
  const FieldExtent& extent_;
  cv::RNG& rng_;
  std::vector<FloorBox> taken_;
};

// Trees, rocks and bushes, apart from each other; trunks, rocks and bushes are obstacles.
void add_trees_rocks_and_bushes(World& world, const FieldExtent& extent, const FieldParams& params,
                                cv::RNG& rng) {
  const std::vector<int> bark = add_shades(world, "bark", {60.f, 75.f, 90.f}, 0.25, 0.0, 6, rng);
  const std::vector<int> leaves =
      add_shades(world, "leaves", {40.f, 105.f, 60.f}, 0.35, 0.0, 10, rng);
  const std::vector<int> shrub = add_shades(world, "bush", {45.f, 95.f, 70.f}, 0.35, 0.0, 10, rng);
  Spots spots(extent, rng);
  const int trees = static_cast<int>(std::lround(params.trees * extent.margin_share));
  for (int i = 0; i < trees; ++i) {
    const double trunk_m = rng.uniform(0.08, 0.2);
    const double crown_xy = rng.uniform(1.0, 2.2), crown_z = rng.uniform(0.9, 1.8);
    const double trunk_height = 1.9 + 0.7 * crown_z + rng.uniform(0.0, 1.5);
    const std::optional<cv::Vec2d> at = spots.place(trunk_m);
    if (!at) break;
    add_trunk(world, (*at)[0], (*at)[1], trunk_m, trunk_height + 0.3 * crown_z, bark, rng);
    add_blob(world, {(*at)[0], (*at)[1], trunk_height + 0.3 * crown_z}, crown_xy, crown_z, leaves,
             rng);
    world.obstacles.push_back(spots.last());
  }
  const std::vector<int> stone = add_shades(world, "rock", {120.f, 125.f, 130.f}, 0.3, 0.0, 6, rng);
  const int rocks = static_cast<int>(std::lround(params.rocks * extent.margin_share));
  for (int i = 0; i < rocks; ++i) {  // low, flattened
    const double radius = rng.uniform(0.1, 0.45), height = rng.uniform(0.08, 0.4);
    const std::optional<cv::Vec2d> at = spots.place(radius);
    if (!at) break;
    add_blob(world, {(*at)[0], (*at)[1], 0.2 * height}, radius, 0.8 * height, stone, rng);
    world.obstacles.push_back(spots.last());
  }
  const int bushes = static_cast<int>(std::lround(params.bushes * extent.margin_share));
  for (int i = 0; i < bushes; ++i) {
    const double radius = rng.uniform(0.15, 0.45), height = rng.uniform(0.3, 1.2);
    const std::optional<cv::Vec2d> at = spots.place(radius);
    if (!at) break;
    add_blob(world, {(*at)[0], (*at)[1], height / 2.0}, radius, height / 2.0, shrub, rng);
    world.obstacles.push_back(spots.last());
  }
}

// Grass tussocks at the same density over the floor and its margin, more short ones than tall
// ones; not obstacles.
void add_grass(World& world, const FieldExtent& extent, const FieldParams& params, cv::RNG& rng) {
  constexpr int kPalette = 48;
  const int palette = add_grass_palette(world, rng, kPalette);
  const int tussocks = static_cast<int>(std::lround(params.tussocks * extent.margin_share));
  for (int i = 0; i < tussocks; ++i) {
    const double x = rng.uniform(extent.near_low, extent.near_high);
    const double y = rng.uniform(extent.near_low, extent.near_high);
    const double height = params.grass_min_m + (params.grass_max_m - params.grass_min_m) *
                                                   std::pow(rng.uniform(0.0, 1.0), 1.5);
    add_tussock(world, x, y, height, palette, kPalette, rng);
  }
}

// The horizon: hills, and a tree line in front of them, both hazy with distance.
void add_horizon(World& world, const FieldExtent& extent, Horizon horizon, cv::RNG& rng) {
  constexpr int kHorizonSamples = 720;
  if (horizon != Horizon::kNone) {
    std::vector<double> hills = horizon_profile(kHorizonSamples, rng);
    for (double& h : hills) h = extent.hills_m * (0.09 + 0.04 * h);
    add_ring(world, extent.centre, extent.hills_m, hills,
             add_shades(world, "hills", {95.f, 120.f, 105.f}, 0.05, 0.45, 4, rng), rng);
  }
  if (horizon == Horizon::kTrees) {
    std::vector<double> line = horizon_profile(kHorizonSamples, rng);
    for (double& h : line) h = extent.tree_line_m * (0.07 + 0.03 * h) * rng.uniform(0.8, 1.2);
    add_ring(world, extent.centre, extent.tree_line_m, line,
             add_shades(world, "tree line", {45.f, 85.f, 55.f}, 0.2, 0.2, 8, rng), rng);
  }
}

}  // namespace

World make_field(const FieldParams& params) {
  if (params.grass_min_m > params.grass_max_m) {
    throw UsageError("field: grass_min_m must not exceed grass_max_m");
  }
  World world;
  world.name = "field";
  world.background_bgr = kHorizonSky;
  world.sky_zenith_bgr = kZenithSky;
  cv::RNG rng(static_cast<std::uint64_t>(params.seed) * 7919 + 31);
  FieldExtent extent;
  extent.size = params.size_m;
  extent.centre = cv::Vec2d(extent.size / 2.0, extent.size / 2.0);
  extent.near_low = -kMargin_m;
  extent.near_high = extent.size + kMargin_m;
  extent.tree_line_m = std::max(80.0, 4.0 * extent.size);
  extent.hills_m = 4.0 * extent.tree_line_m;
  extent.margin_share = (extent.near_high - extent.near_low) *
                        (extent.near_high - extent.near_low) / (extent.size * extent.size);
  world.floor = {0.0, 0.0, extent.size, extent.size};
  add_ground(world, extent, params, rng);
  add_trees_rocks_and_bushes(world, extent, params, rng);
  add_grass(world, extent, params, rng);
  add_horizon(world, extent, params.horizon, rng);
  return world;
}

}  // namespace omninav::sim
