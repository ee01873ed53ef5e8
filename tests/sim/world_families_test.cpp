// The world families (room, house, field, office) and their specs: strict parsing, determinism,
// informative panoramas, and obstacles where a robot must not drive.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <set>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/field.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::sim {
namespace {

cv::Mat render(const World& world, const CameraPose& pose, int width = 180, int height = 45) {
  RenderParams params;
  params.geometry.width_px = width;
  params.geometry.height_px = height;
  params.rays_per_pixel = 1;
  return Renderer(world, params).render(pose);
}

double mean_abs_difference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat difference;
  cv::absdiff(a, b, difference);
  return cv::mean(cv::mean(difference))[0];
}

World load(const std::string& spec) {
  return load_world(spec, WorldsConfig{});
}

// Worlds and their renderers built once for the whole file: a field takes a quarter second
// to generate and another to index.
struct Cached {
  World world;
  std::unique_ptr<Renderer> renderer;
};
const Cached& cached(const std::string& spec) {
  static std::map<std::string, Cached> cache;
  auto found = cache.find(spec);
  if (found == cache.end()) {
    found = cache.emplace(spec, Cached{load(spec), nullptr}).first;
    RenderParams params;
    params.geometry.width_px = 180;
    params.geometry.height_px = 45;
    params.rays_per_pixel = 1;
    found->second.renderer = std::make_unique<Renderer>(found->second.world, params);
  }
  return found->second;
}
cv::Mat render(const std::string& spec, const CameraPose& pose) {
  return cached(spec).renderer->render(pose);
}

// The free point nearest to (x, y) on a 5 cm lattice, clear by `clearance_m`.
cv::Point2d nearest_free(const World& world, double x, double y, double clearance_m) {
  for (int ring = 0; ring < 60; ++ring) {
    for (int i = -ring; i <= ring; ++i) {
      for (int j = -ring; j <= ring; ++j) {
        if (std::max(std::abs(i), std::abs(j)) != ring) continue;
        const double px = x + 0.05 * i, py = y + 0.05 * j;
        if (world.is_free(px, py, clearance_m)) return {px, py};
      }
    }
  }
  ADD_FAILURE() << "no free point near (" << x << ", " << y << ")";
  return {x, y};
}

// ---- specs -------------------------------------------------------------------------------

void expect_usage_error(const std::string& spec, const std::string& fragment) {
  try {
    load(spec);
    ADD_FAILURE() << spec << " was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos)
        << spec << ": " << error.what();
    EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos) << "one line";
  }
}

TEST(WorldSpec, BadSpecsAreOneLineErrorsNamingTheKeyAndRange) {
  expect_usage_error("forest:seed=1", "unknown family 'forest'");
  expect_usage_error("forest", "unknown family 'forest'");
  expect_usage_error("room:sides=3", "unknown key 'sides' for room");
  expect_usage_error("house:boxes=3", "unknown key 'boxes' for house");
  expect_usage_error("room:seed=1,seed=2", "key 'seed' is given twice");
  expect_usage_error("room:size_x_m=20", "size_x_m = 20 is out of range (valid: [3, 12])");
  expect_usage_error("room:size_x_m=2.9", "valid: [3, 12]");
  expect_usage_error("room:boxes=21", "boxes = 21 is out of range (valid: [0, 20])");
  expect_usage_error("room:boxes=2.5", "boxes = 2.5 is not a whole number");
  expect_usage_error("field:size_m=nan", "size_m = 'nan' is not a finite number");
  expect_usage_error("field:size_m=inf", "is not a finite number");
  expect_usage_error("office:rows=", "rows = '' is not a whole number");
  expect_usage_error("room:walls=wallpaper", "walls = 'wallpaper' is not one of plain, textured");
  expect_usage_error("field:horizon=sea", "horizon = 'sea' is not one of trees, hills, none");
  expect_usage_error("room:seed", "expected key=value");
  expect_usage_error(":seed=1", "no world family");
  expect_usage_error("house:room_min_m=6,room_max_m=4", "room_min_m");
}

TEST(WorldSpec, ObjPathsAreRecognisedAndMissingOnesAreInputErrors) {
  EXPECT_TRUE(is_obj_path("worlds/ant.OBJ"));
  EXPECT_TRUE(is_obj_path("some/dir/scene"));
  EXPECT_FALSE(is_obj_path("room:seed=2"));
  EXPECT_FALSE(is_obj_path("house"));
  EXPECT_FALSE(is_obj_path("field:size_m=1/2"));  // a family's spec, however odd its values
  EXPECT_THROW(load("no_such_world.obj"), InputError);
}

TEST(WorldSpec, KeysOverrideTheConfiguredDefaults) {
  WorldsConfig config;
  config.room.size_x_m = 7.0;
  const World plain = load_world("room", config);
  EXPECT_DOUBLE_EQ(plain.floor.max_x_m, 7.0);
  EXPECT_EQ(plain.name, "room");
  const World room = load_world("room:size_y_m=9,boxes=0,seed=4", config);
  EXPECT_DOUBLE_EQ(room.floor.max_x_m, 7.0);
  EXPECT_DOUBLE_EQ(room.floor.max_y_m, 9.0);
  EXPECT_TRUE(room.obstacles.empty());
  EXPECT_EQ(room.name, "room:size_y_m=9,boxes=0,seed=4");
  // `room` alone is make_room with the configured parameters, unchanged.
  const World direct = make_room(config.room);
  ASSERT_EQ(plain.textures.size(), direct.textures.size());
  for (std::size_t i = 0; i < plain.textures.size(); ++i) {
    EXPECT_EQ(cv::norm(plain.textures[i], direct.textures[i], cv::NORM_INF), 0.0);
  }
}

TEST(WorldSpec, FieldHorizonIsOneOfThreeNames) {
  for (const Horizon horizon : {Horizon::kTrees, Horizon::kHills, Horizon::kNone}) {
    EXPECT_EQ(horizon_from_string(to_string(horizon)), horizon);
  }
  EXPECT_EQ(to_string(Horizon::kHills), "hills");
  EXPECT_THROW(horizon_from_string("mountains"), UsageError);
  EXPECT_THROW(horizon_from_string("Trees"), UsageError);
}

TEST(WorldSpec, PlainWallsHaveNoPictures) {
  // A plain wall is one paint with faint stains: far less varied than a decorated one.
  const World plain = load("room:walls=plain,boxes=0");
  const World textured = load("room:walls=textured,boxes=0");
  cv::Scalar mean, plain_sd, textured_sd;
  cv::meanStdDev(plain.textures[0], mean, plain_sd);
  cv::meanStdDev(textured.textures[0], mean, textured_sd);
  EXPECT_LT(plain_sd[1], 0.5 * textured_sd[1]);
}

// ---- every family ------------------------------------------------------------------------

struct FamilyCase {
  std::string spec;
  double z_m;
};

class Family : public ::testing::TestWithParam<FamilyCase> {};

TEST_P(Family, RendersDeterministicallyAndInformatively) {
  const World first = load(GetParam().spec);
  const cv::Point2d at = nearest_free(first, (first.floor.min_x_m + first.floor.max_x_m) / 2 + 0.3,
                                      (first.floor.min_y_m + first.floor.max_y_m) / 2 + 0.2, 0.3);
  const CameraPose pose{at.x, at.y, GetParam().z_m, 0.4, 0.0, 0.0};
  const cv::Mat a = render(first, pose), b = render(GetParam().spec, pose);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << "same spec, same pixels";
  // Not degenerate: brightness varies across the columns and down the rows.
  cv::Mat grey, columns, rows;
  cv::cvtColor(a, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  cv::reduce(grey, columns, 0, cv::REDUCE_AVG);
  cv::reduce(grey, rows, 1, cv::REDUCE_AVG);
  cv::Scalar mean, across, down, all;
  cv::meanStdDev(columns, mean, across);
  cv::meanStdDev(rows, mean, down);
  cv::meanStdDev(grey, mean, all);
  EXPECT_GT(all[0], 12.0) << GetParam().spec;
  EXPECT_GT(across[0], 3.0) << GetParam().spec;
  EXPECT_GT(down[0], 3.0) << GetParam().spec;
  // A different seed is a different world.
  const World other = load(
      GetParam().spec + (GetParam().spec.find(':') == std::string::npos ? ":seed=99" : ",seed=99"));
  const cv::Point2d there = nearest_free(other, at.x, at.y, 0.3);
  EXPECT_GT(mean_abs_difference(a, render(other, {there.x, there.y, pose.z_m, 0.4, 0.0, 0.0})),
            3.0);
}

INSTANTIATE_TEST_SUITE_P(Worlds, Family,
                         ::testing::Values(FamilyCase{"room", 1.0},
                                           FamilyCase{"room:size_x_m=11,boxes=20,walls=plain", 1.0},
                                           FamilyCase{"house", 1.0}, FamilyCase{"office", 1.2},
                                           FamilyCase{"field", 0.02}, FamilyCase{"field", 0.1},
                                           FamilyCase{"field", 1.5}),
                         [](const auto& info) { return "case" + std::to_string(info.index); });

// ---- house -------------------------------------------------------------------------------

TEST(House, RegionsNameEveryRoomAndTheCorridorWithoutOverlap) {
  const World house = load("house:rooms=6");
  ASSERT_EQ(house.regions.size(), 7u);
  std::set<std::string> names;
  for (const Region& region : house.regions) names.insert(region.name);
  EXPECT_TRUE(names.contains("corridor"));
  EXPECT_TRUE(names.contains("room 1"));
  EXPECT_TRUE(names.contains("room 6"));
  int free = 0, in_a_region = 0;
  for (double x = house.floor.min_x_m + 0.01; x < house.floor.max_x_m; x += 0.07) {
    for (double y = house.floor.min_y_m + 0.01; y < house.floor.max_y_m; y += 0.07) {
      int containing = 0;
      for (const Region& region : house.regions) containing += region.area.contains(x, y) ? 1 : 0;
      EXPECT_LE(containing, 1);
      if (!house.is_free(x, y)) continue;
      ++free;
      in_a_region += house.region_at(x, y) != nullptr ? 1 : 0;
    }
  }
  // Only doorways (inside the walls' thickness) are free but in no region.
  EXPECT_GT(in_a_region, 0.98 * free);
  for (const Region& region : house.regions) {
    const double x = (region.area.min_x_m + region.area.max_x_m) / 2;
    const double y = (region.area.min_y_m + region.area.max_y_m) / 2;
    ASSERT_NE(house.region_at(x, y), nullptr);
    EXPECT_EQ(house.region_at(x, y)->name, region.name);
  }
}

TEST(House, EveryRoomIsReachableThroughDoorsWideEnoughForTheRobot) {
  const World house = load("house:rooms=8,seed=3");
  constexpr double kRadius = 0.2, kCell = 0.05;
  const int nx = static_cast<int>((house.floor.max_x_m - house.floor.min_x_m) / kCell);
  const int ny = static_cast<int>((house.floor.max_y_m - house.floor.min_y_m) / kCell);
  const auto centre = [&](int i, int j) {
    return cv::Point2d(house.floor.min_x_m + (i + 0.5) * kCell,
                       house.floor.min_y_m + (j + 0.5) * kCell);
  };
  // Flood the free cells from the corridor's centre.
  const Region& corridor = house.regions.back();
  ASSERT_EQ(corridor.name, "corridor");
  const cv::Point2d start =
      nearest_free(house, (corridor.area.min_x_m + corridor.area.max_x_m) / 2,
                   (corridor.area.min_y_m + corridor.area.max_y_m) / 2, kRadius);
  std::vector<char> seen(static_cast<std::size_t>(nx * ny), 0);
  std::deque<std::pair<int, int>> queue{
      {static_cast<int>((start.x - house.floor.min_x_m) / kCell),
       static_cast<int>((start.y - house.floor.min_y_m) / kCell)}};
  std::set<std::string> reached;
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    if (i < 0 || j < 0 || i >= nx || j >= ny || seen[j * nx + i]) continue;
    const cv::Point2d p = centre(i, j);
    if (!house.is_free(p.x, p.y, kRadius)) continue;
    seen[j * nx + i] = 1;
    if (const Region* region = house.region_at(p.x, p.y)) reached.insert(region->name);
    for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      queue.emplace_back(i + di, j + dj);
    }
  }
  EXPECT_EQ(reached.size(), house.regions.size());
}

TEST(House, RoomsLookDifferentFromEachOther) {
  const World& house = cached("house").world;
  std::vector<cv::Mat> centres, nudged;
  for (const Region& region : house.regions) {
    if (region.name == "corridor") continue;
    const cv::Point2d at = nearest_free(house, (region.area.min_x_m + region.area.max_x_m) / 2,
                                        (region.area.min_y_m + region.area.max_y_m) / 2, 0.25);
    centres.push_back(render("house", {at.x, at.y, 1.0, 0.0, 0.0, 0.0}));
    nudged.push_back(render("house", {at.x + 0.1, at.y, 1.0, 0.0, 0.0, 0.0}));
  }
  ASSERT_GE(centres.size(), 3u);
  double largest_nudge = 0.0, smallest_between = 1e9;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    largest_nudge = std::max(largest_nudge, mean_abs_difference(centres[i], nudged[i]));
    for (std::size_t j = i + 1; j < centres.size(); ++j) {
      smallest_between = std::min(smallest_between, mean_abs_difference(centres[i], centres[j]));
    }
  }
  EXPECT_GT(smallest_between, 3.0 * largest_nudge)
      << "between rooms " << smallest_between << ", 10 cm apart " << largest_nudge;
}

TEST(House, TheRobotStopsAtWallsAndPassesThroughDoorways) {
  const World house = load("house:rooms=2,furniture=0,seed=5");
  // rooms=2: room 1 south of the corridor, room 2 north; the corridor wall above room 1 is
  // an obstacle except at its doorway.
  const Region* room = &house.regions[0];
  ASSERT_EQ(room->name, "room 1");
  const FloorBox* wall = nullptr;  // the widest piece of the wall north of room 1
  for (const FloorBox& box : house.obstacles) {
    if (std::abs(box.min_y_m - room->area.max_y_m) < 1e-6 &&
        (!wall || box.max_x_m - box.min_x_m > wall->max_x_m - wall->min_x_m)) {
      wall = &box;
    }
  }
  ASSERT_NE(wall, nullptr);
  RobotParams params;
  params.turn_noise_deg = 0.0;
  params.distance_noise = 0.0;
  params.radius_m = 0.15;
  const double wall_x = (wall->min_x_m + wall->max_x_m) / 2;
  VirtualRobot blocked(house, {wall_x, room->area.max_y_m - 1.0, 1.0, kPi / 2, 0.0, 0.0}, params);
  blocked.move(0.0, 3.0);
  EXPECT_LT(blocked.pose().y_m, room->area.max_y_m - 0.14);
  EXPECT_EQ(house.region_at(blocked.pose().x_m, blocked.pose().y_m)->name, "room 1");
  // Through the doorway: the gap in that wall.
  double door_x = -1.0;
  for (double x = room->area.min_x_m; x < room->area.max_x_m; x += 0.01) {
    if (house.is_free(x, room->area.max_y_m + 0.06, 0.3)) {
      door_x = x + 0.15;  // a little inside the gap: its left edge is at least 0.3 m away
      break;
    }
  }
  ASSERT_GT(door_x, 0.0) << "a doorway at least 0.6 m wide";
  VirtualRobot through(house, {door_x, room->area.max_y_m - 1.0, 1.0, kPi / 2, 0.0, 0.0}, params);
  through.move(0.0, 1.8);
  const Region* now = house.region_at(through.pose().x_m, through.pose().y_m);
  ASSERT_NE(now, nullptr);
  EXPECT_EQ(now->name, "corridor");
}

TEST(House, DoorwaysHaveAFloor) {
  // Looking down across a doorway from just beside it: the floor continues under the door
  // (a threshold), no hole onto the background.
  const World& house = cached("house").world;
  const Region& room = house.regions[0];
  int doorways = 0;
  for (double x = room.area.min_x_m; x < room.area.max_x_m; x += 0.05) {
    const double y = room.area.max_y_m + 0.06;  // inside the corridor wall's thickness
    if (!house.is_free(x, y, 0.3)) continue;
    ++doorways;
    const cv::Mat view = render("house", {x, room.area.max_y_m - 0.1, 0.1, kPi / 2, 0.0, 0.0});
    cv::Mat hole;
    cv::inRange(view.rowRange(35, 45), cv::Scalar(39, 39, 39), cv::Scalar(41, 41, 41), hole);
    EXPECT_EQ(cv::countNonZero(hole), 0) << "at x " << x;
  }
  EXPECT_GT(doorways, 0);
}

// ---- office ------------------------------------------------------------------------------

TEST(Office, PlacesOneDeskPitchApartLookAlike) {
  OfficeParams params;  // the defaults of docs/worlds.md
  const World& office = cached("office").world;
  // Mid-aisle between row 0's desks and row 1's chairs.
  const double aisle_y =
      (0.9 + params.row_pitch_m * 0.5 + 0.35 + 0.9 + params.row_pitch_m * 1.5 - 0.35 - 0.25 - 0.5) /
      2;
  double same = 0.0, half = 0.0;
  for (int desk = 1; desk <= 3; ++desk) {
    const double x = 1.5 + params.desk_pitch_m * (desk + 0.5);
    ASSERT_TRUE(office.is_free(x, aisle_y, 0.3));
    const cv::Mat here = render("office", {x, aisle_y, 1.2, 0.0, 0.0, 0.0});
    same += mean_abs_difference(
        here, render("office", {x + params.desk_pitch_m, aisle_y, 1.2, 0.0, 0.0, 0.0}));
    half += mean_abs_difference(
        here, render("office", {x + params.desk_pitch_m / 2, aisle_y, 1.2, 0.0, 0.0, 0.0}));
  }
  EXPECT_LT(same, 0.6 * half) << "one pitch " << same / 3 << ", half a pitch " << half / 3;
}

TEST(Office, TheRobotStopsAtDesksAndColumns) {
  OfficeParams params;
  const World& office = cached("office").world;
  RobotParams robot;
  robot.turn_noise_deg = 0.0;
  robot.distance_noise = 0.0;
  robot.radius_m = 0.1;
  const double row_y = 0.9 + params.row_pitch_m * 1.5;  // row 1's centre line
  const double desk_x = 1.5 + params.desk_pitch_m * 1.5;
  // North from the aisle towards desk 1 of row 1: its chair stops the robot.
  VirtualRobot to_desk(office, {desk_x, row_y - 1.5, 1.0, kPi / 2, 0.0, 0.0}, robot);
  to_desk.move(0.0, 2.0);
  EXPECT_LT(to_desk.pose().y_m, row_y - 0.35 - 0.25 - 0.5 - 0.09);
  // Along the row's line from the west wall: the first desk stops it.
  VirtualRobot along(office, {0.5, row_y, 1.0, 0.0, 0.0, 0.0}, robot);
  along.move(0.0, 4.0);
  EXPECT_LT(along.pose().x_m, 1.5 + params.desk_pitch_m * 0.5 - 0.7 - 0.09);
  // A column between desks 2 and 3 (column_every = 2): approach it from the aisle.
  const double column_x = 1.5 + params.desk_pitch_m * 2;
  VirtualRobot to_column(office, {column_x, row_y + 1.2, 1.0, -kPi / 2, 0.0, 0.0}, robot);
  to_column.move(0.0, 2.0);
  EXPECT_GT(to_column.pose().y_m, row_y + 0.175 + 0.1);
  EXPECT_LT(to_column.pose().y_m, row_y + 0.175 + 0.1 + 0.02);
}

// ---- field -------------------------------------------------------------------------------

TEST(Field, TrunksAndBushesAreObstaclesButGrassIsNot) {
  const World& field = cached("field:seed=2").world;
  // Obstacles are the few trunks and bushes, not the thousands of tussocks.
  EXPECT_GT(field.triangles.size(), 50000u);
  EXPECT_GE(field.obstacles.size(), 10u);
  EXPECT_LT(field.obstacles.size(), 100u);
  RobotParams params;
  params.turn_noise_deg = 0.0;
  params.distance_noise = 0.0;
  params.radius_m = 0.1;
  int stopped = 0, tested = 0;
  for (const FloorBox& box : field.obstacles) {
    const double x = (box.min_x_m + box.max_x_m) / 2, y = (box.min_y_m + box.max_y_m) / 2;
    const double start_x = box.min_x_m - 1.5;
    if (!field.segment_is_free(start_x, y, box.min_x_m - 0.2, y, 0.1)) continue;
    if (!field.is_free(start_x, y, 0.1)) continue;
    ++tested;
    VirtualRobot robot(field, {start_x, y, 0.1, 0.0, 0.0, 0.0}, params);
    robot.move(0.0, 3.0);
    stopped += robot.pose().x_m < box.min_x_m - 0.09 && robot.pose().x_m < x ? 1 : 0;
  }
  EXPECT_GT(tested, 3);
  EXPECT_EQ(stopped, tested);
  // Across open grass the robot drives the whole way.
  int drove = 0;
  for (double y = 1.0; y < 19.0; y += 1.0) {
    if (!field.segment_is_free(1.0, y, 4.0, y, 0.1)) continue;
    VirtualRobot robot(field, {1.0, y, 0.1, 0.0, 0.0, 0.0}, params);
    EXPECT_NEAR(robot.move(0.0, 3.0), 3.0, 1e-6);
    ++drove;
  }
  EXPECT_GT(drove, 5);
}

TEST(Field, LowCameraSeesGrassAndHighCameraSeesTheHorizon) {
  const cv::Point2d at = nearest_free(cached("field").world, 10.0, 10.0, 0.3);
  // At 2 cm the tussocks hide most of the horizon; at 1.5 m the camera looks over them, and
  // the sky fills the rows above the horizon.
  cv::Mat low = render("field", {at.x, at.y, 0.02, 0.0, 0.0, 0.0});
  cv::Mat high = render("field", {at.x, at.y, 1.5, 0.0, 0.0, 0.0});
  EXPECT_GT(mean_abs_difference(low, high), 10.0);
  // Blue (sky) dominates the top row from 1.5 m.
  const cv::Scalar top = cv::mean(high.row(0));
  EXPECT_GT(top[0], top[2] + 20.0);
}

// ---- the virtual robot and thin walls ----------------------------------------------------

TEST(VirtualRobotWalls, AWallThinnerThanOneIncrementStillStopsIt) {
  World world = load("room:boxes=0");
  world.obstacles.push_back({3.003, 0.0, 3.006, 5.0});  // 3 mm, between two 1 cm increments
  RobotParams params;
  params.turn_noise_deg = 0.0;
  params.distance_noise = 0.0;
  params.radius_m = 0.0;
  VirtualRobot robot(world, {2.5, 2.5, 1.0, 0.0, 0.0, 0.0}, params);
  robot.move(0.0, 2.0);
  EXPECT_LT(robot.pose().x_m, 3.003);
  EXPECT_FALSE(world.segment_is_free(2.5, 2.5, 3.5, 2.5));
  EXPECT_TRUE(world.segment_is_free(2.5, 2.5, 2.9, 3.5));
}

}  // namespace
}  // namespace omninav::sim

namespace omninav::sim {
namespace {

TEST(RendererRobust, AxisAlignedRaysDoNotSlipThroughGeometry) {
  // From the field's centre (10, 10), the middle ray of column 270 points exactly along -x
  // (its y component is sin(pi) ~ 1e-16). Without Embree's robust mode that ray missed every
  // triangle, and the column showed a third of sky over trees and ground. A camera 0.5 mm
  // away must see nearly the same column.
  RenderParams params;
  params.geometry.width_px = 360;
  params.geometry.height_px = 45;
  params.rays_per_pixel = 3;
  const Renderer renderer(cached("field").world, params);
  const cv::Mat exact = renderer.render({10.0, 10.0, 1.5, 0.0, 0.0, 0.0});
  const cv::Mat nudged = renderer.render({10.0, 10.0005, 1.5, 0.0, 0.0, 0.0});
  for (const int column : {0, 90, 180, 270}) {
    EXPECT_LT(mean_abs_difference(exact.col(column), nudged.col(column)), 4.0) << column;
  }
}

}  // namespace
}  // namespace omninav::sim
