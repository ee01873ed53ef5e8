#include "omninav/navigation/navigator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/virtual_robot.hpp"

namespace omninav::navigation {
namespace {

// What a stand-in localiser says: `place` recognised with full similarity, the robot's heading
// relative to it, and when given the robot's position on the lattice.
memory::Localisation recognised(std::size_t place, double relative_heading_rad,
                                const std::optional<Eigen::Vector2d>& lattice_position = {}) {
  memory::Localisation localisation;
  memory::PlaceMatch match;
  match.place = place;
  match.similarity = 1000.0;
  match.relative_heading_rad = relative_heading_rad;
  localisation.best.push_back(match);
  if (lattice_position) {
    memory::PositionEstimate estimate;
    estimate.frame = memory::PositionFrame::kLattice;
    estimate.interpolated_position = *lattice_position;
    localisation.position = estimate;
  }
  return localisation;
}

// A virtual robot of libs/sim behind the navigator's interface, moving freely (with motion
// noise) and stopped by the room's walls and furniture. It shows nothing: the oracle
// localisers below read its true pose instead.
class VirtualRobotWorld : public NavigationWorld {
 public:
  explicit VirtualRobotWorld(sim::VirtualRobot& robot) : robot_(robot) {}
  cv::Mat view(int) override { return {}; }
  double move(double turn_rad, double distance_m) override {
    return robot_.move(turn_rad, distance_m);
  }
  CameraPose truth() const override { return robot_.pose(); }

 private:
  sim::VirtualRobot& robot_;
};

NavigationResult navigate(sim::VirtualRobot& robot, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const PanoramaLocaliser& localise,
                          const NavigatorParams& params) {
  VirtualRobotWorld world(robot);
  return navigate(world, places, plan, localise, params);
}

// The navigation loop with a perfect localiser (the nearest place by true position, the
// heading by true heading): it isolates planning and control from recognition, whose own
// tests live with the memory.
class OracleNavigation : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::RoomParams room;
    room.texture_px_per_m = 20;
    world_ = sim::make_room(room);
    for (double y = 0.4; y < 4.7; y += 0.3) {
      for (double x = 0.4; x < 5.7; x += 0.3) {
        if (world_.is_free(x, y, 0.2))
          places_.push_back({Eigen::Vector2d(x, y), 0.3 * places_.size()});
      }
    }
  }

  PanoramaLocaliser oracle(const sim::VirtualRobot& robot) const {
    return [this, &robot](const cv::Mat&) {
      std::size_t nearest = 0;
      double best = 1e9;
      const Eigen::Vector2d at(robot.pose().x_m, robot.pose().y_m);
      for (std::size_t i = 0; i < places_.size(); ++i) {
        const double distance = (places_[i].position_m - at).norm();
        if (distance < best) {
          best = distance;
          nearest = i;
        }
      }
      return recognised(nearest,
                        signed_difference(robot.pose().heading_rad, places_[nearest].heading_rad));
    };
  }

  sim::World world_;
  std::vector<PlaceNode> places_;
};

TEST_F(OracleNavigation, ReachesTheGoalAlongAShortPath) {
  const RoutePlan plan = plan_to_goal(places_, lattice_neighbours(places_, 0.45),
                                      static_cast<int>(places_.size()) - 1);
  const Eigen::Vector2d goal = places_.back().position_m;
  sim::RobotParams robot_params;
  sim::VirtualRobot robot(
      world_, {places_.front().position_m.x(), places_.front().position_m.y(), 1.0, 2.0, 0.0, 0.0},
      robot_params);
  const NavigationResult result = navigate(robot, places_, plan, oracle(robot), NavigatorParams{});
  ASSERT_TRUE(result.reached) << result.steps.size() << " steps";
  EXPECT_LT((Eigen::Vector2d(robot.pose().x_m, robot.pose().y_m) - goal).norm(), 0.3);
  // The route bends round furniture: within 1.5 × the planned route's length.
  EXPECT_LT(result.path_length_m, 1.5 * plan.cost_m[0] + 0.3);
  EXPECT_EQ(result.jumps, 0);
}

TEST_F(OracleNavigation, FollowsThePlanWhateverTheRobotsStartingHeading) {
  const RoutePlan plan = plan_to_goal(places_, lattice_neighbours(places_, 0.45), 0);
  for (double heading_deg : {-170.0, -60.0, 45.0, 135.0}) {
    sim::VirtualRobot robot(world_,
                            {places_.back().position_m.x(), places_.back().position_m.y(), 1.0,
                             deg_to_rad(heading_deg), 0.0, 0.0},
                            sim::RobotParams{});
    EXPECT_TRUE(navigate(robot, places_, plan, oracle(robot), NavigatorParams{}).reached)
        << "starting heading " << heading_deg;
  }
}

TEST_F(OracleNavigation, GivesUpWhenTheBudgetIsSpent) {
  const RoutePlan plan = plan_to_goal(places_, lattice_neighbours(places_, 0.45), 0);
  sim::VirtualRobot robot(
      world_, {places_.back().position_m.x(), places_.back().position_m.y(), 1.0, 0.0, 0.0, 0.0},
      sim::RobotParams{});
  NavigatorParams params;
  params.max_steps = 3;
  const NavigationResult result = navigate(robot, places_, plan, oracle(robot), params);
  EXPECT_FALSE(result.reached);
  EXPECT_EQ(result.steps.size(), 3u);
}

// A box on the floor of a PointWorld.
struct Box {
  double min_x, max_x, min_y, max_y;
};

// A wall stub (x 0.4..0.6 m, y below 0.6 m).
constexpr Box kStub{0.4, 0.6, -1e9, 0.6};

// A world of its own behind the navigator's interface: a point robot on a plane, among boxes
// that the lattice knows nothing of.
class PointWorld : public NavigationWorld {
 public:
  explicit PointWorld(std::vector<Box> boxes = {}) : boxes_(std::move(boxes)) {}
  cv::Mat view(int) override { return {}; }
  double move(double turn_rad, double distance_m) override {
    pose_.heading_rad = wrap_angle(pose_.heading_rad + turn_rad);
    double driven = 0.0;
    for (; driven + 0.01 <= distance_m + 1e-9; driven += 0.01) {
      const double x = pose_.x_m + 0.01 * std::cos(pose_.heading_rad);
      const double y = pose_.y_m + 0.01 * std::sin(pose_.heading_rad);
      const auto inside = [x, y](const Box& b) {
        return x > b.min_x && x < b.max_x && y > b.min_y && y < b.max_y;
      };
      if (std::any_of(boxes_.begin(), boxes_.end(), inside)) break;
      pose_.x_m = x;
      pose_.y_m = y;
    }
    return driven;
  }
  CameraPose truth() const override { return pose_; }

 private:
  const std::vector<Box> boxes_;
  CameraPose pose_{0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
};

// The place whose true position (`truth`, not the lattice) is nearest to the robot, all places
// facing +x; with `position`, the robot's true position as the localiser's estimate (the
// lattice must then be the truth). `world` must outlive the localiser.
PanoramaLocaliser point_oracle(const PointWorld& world, std::vector<Eigen::Vector2d> truth,
                               bool position = false) {
  return [&world, truth, position](const cv::Mat&) {
    std::size_t nearest = 0;
    double best = 1e9;
    const Eigen::Vector2d at(world.truth().x_m, world.truth().y_m);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      if ((truth[i] - at).norm() < best) {
        best = (truth[i] - at).norm();
        nearest = i;
      }
    }
    return recognised(nearest, world.truth().heading_rad,
                      position ? std::optional<Eigen::Vector2d>(at) : std::nullopt);
  };
}

TEST(Navigator, ReplansWithoutALinkThatFurnitureBlocks) {
  // 3 × 3 places 1 m apart, all facing +x; the goal is place 2 at (2, 0), straight east of the
  // start behind the wall stub.
  std::vector<PlaceNode> places;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 3; ++x) places.push_back({Eigen::Vector2d(x, y), 0.0});
  }
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 2);
  ASSERT_EQ(plan.next[0], 1);
  PointWorld world({kStub});
  std::vector<Eigen::Vector2d> truth;
  for (const PlaceNode& place : places) truth.push_back(place.position_m);
  const PanoramaLocaliser oracle = point_oracle(world, truth);
  const NavigationResult result = navigate(world, places, plan, oracle, NavigatorParams{});
  ASSERT_TRUE(result.reached);
  EXPECT_GE(result.replans, 1);
  // Stopped where the goal place is the nearest: within half a cell's diagonal of it.
  EXPECT_LT(std::hypot(world.truth().x_m - 2.0, world.truth().y_m), std::hypot(0.5, 0.5));
  // Round the stub: longer than the straight 2 m, shorter than going up a whole row and back.
  EXPECT_GT(result.path_length_m, 2.0);
  EXPECT_LT(result.path_length_m, 4.0);
}

// Where the lattice is distorted, a place's direction can lead into a neighbour whose direction
// leads back. Truth: A (0,0), B (1,0), C (0,1), D (1,1), E (1,2), goal G (0,2), 1 m apart. On the
// lattice C lies east of A, so A's direction (towards C, the shortest route) takes the robot
// into B, whose route runs back through A: without loop detection the robot swings between A
// and B (due east, due west) until its budget is spent.
TEST(Navigator, LeavesALoopBetweenPlacesByPlanningWithoutTheLink) {
  enum { A, B, C, D, E, G };
  const std::vector<Eigen::Vector2d> truth{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<PlaceNode> places{{{0, 0}, 0.0}, {{1, 0}, 0.0}, {{0.9, 0}, 0.0},
                                      {{2, 1}, 0.0}, {{2, 2}, 0.0}, {{0, 2}, 0.0}};
  const std::vector<Edge> edges{{A, B}, {A, C}, {C, G}, {B, D}, {D, E}, {E, G}};
  const RoutePlan plan = plan_to_goal(places, edges, G);
  ASSERT_EQ(plan.next[A], C);
  ASSERT_EQ(plan.next[B], A);

  NavigatorParams params;
  params.loop_entries = 0;
  params.stall_spacings = 0.0;  // the loop check alone (a stall would drop the link too)
  PointWorld looping;
  const NavigationResult lost =
      navigate(looping, places, plan, point_oracle(looping, truth), params);
  EXPECT_FALSE(lost.reached);

  params.loop_entries = 3;
  PointWorld world;
  const NavigationResult result = navigate(world, places, plan, point_oracle(world, truth), params);
  ASSERT_TRUE(result.reached) << result.steps.size() << " steps";
  EXPECT_GE(result.loops, 1);
  // Swinging, then by B, D and E: about 1 + 1 + 1.5 + 1 m, well within 40 steps of 0.15 m.
  EXPECT_LT(result.steps.size(), 40u);
}

// 3 × 3 places 1 m apart, all facing +x, with the route planned to place 2 at (2, 0); the goal
// pose lies on its far side from the start at the origin. The goal image is seen as from its
// true pose: distance and bearing exact, so that the control is what is tested.
struct GoalBesideItsPlace {
  std::vector<PlaceNode> places;
  std::vector<Eigen::Vector2d> truth;
  RoutePlan plan;
  Eigen::Vector2d goal{2.4, 0.3};

  GoalBesideItsPlace() {
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 3; ++x) places.push_back({Eigen::Vector2d(x, y), 0.0});
    }
    for (const PlaceNode& place : places) truth.push_back(place.position_m);
    plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 2);
  }
  NavigationResult run(PointWorld& world, const NavigatorParams& params) const {
    const GoalHoming exact = [&world, goal = goal](const cv::Mat&) {
      const CameraPose at = world.truth();
      const Eigen::Vector2d to = goal - Eigen::Vector2d(at.x_m, at.y_m);
      return GoalCue{to.norm(), signed_difference(std::atan2(to.y(), to.x()), at.heading_rad),
                     to.norm() > 0.01};
    };
    return navigate(world, places, plan, point_oracle(world, truth), params, exact);
  }
  double miss_m(const PointWorld& world) const {
    return std::hypot(world.truth().x_m - goal.x(), world.truth().y_m - goal.y());
  }
};

// The robot stops on recognising the goal's place (§3.5), which may be a whole cell from the
// goal pose; homing on the goal image takes it there.
TEST(Navigator, HomesOnTheGoalImageAfterRecognisingItsPlace) {
  const GoalBesideItsPlace scene;
  NavigatorParams params;
  params.home_on_goal_image = false;
  PointWorld stopping;
  const NavigationResult stopped = scene.run(stopping, params);
  ASSERT_TRUE(stopped.reached);
  EXPECT_GT(scene.miss_m(stopping), 0.6);  // entered place 2's cell at x ≈ 1.5 m

  params.home_on_goal_image = true;
  PointWorld world;
  const NavigationResult result = scene.run(world, params);
  ASSERT_TRUE(result.reached);
  EXPECT_LE(scene.miss_m(world), params.homing_stop_m + 1e-9);
  EXPECT_GT(result.homing_steps, 0);
  EXPECT_LE(result.homing_steps, params.homing_max_steps);
  // Homing goes straight at the goal: no longer than the way from where the robot stopped.
  EXPECT_LT(result.path_length_m, stopped.path_length_m + scene.miss_m(stopping) + 1e-6);
}

// The goal lies beyond the corner of a box (x 1.9..2.0 m, y below 0.15 m) that stands across
// the straight line from where the robot recognises the goal's place: homing sidesteps round
// the corner as the navigator does on its way, instead of stopping at the box. The robot meets
// the box's face 2 cm below the corner: only the third sidestep, 90° left, leads up past it.
TEST(Navigator, HomingSidestepsRoundACornerBeforeTheGoal) {
  const GoalBesideItsPlace scene;
  const std::vector<Box> corner{{1.9, 2.0, -1e9, 0.15}};
  NavigatorParams params;
  params.sidestep_deg = 45.0;
  params.homing_max_steps = 20;
  PointWorld world(corner);
  const NavigationResult result = scene.run(world, params);
  ASSERT_TRUE(result.reached);
  EXPECT_GE(result.sidesteps, 1);
  EXPECT_LE(scene.miss_m(world), params.homing_stop_m + 1e-9);

  params.sidesteps = 0;
  PointWorld stopping(corner);
  ASSERT_TRUE(scene.run(stopping, params).reached);
  EXPECT_GT(scene.miss_m(stopping), 0.4);  // stopped at the box
  EXPECT_LT(stopping.truth().x_m, 1.9);
}

// A dead end the lattice knows nothing of: the robot stands in a pocket open only to the west
// (boxes 0.05 m above, below and east of it) and its only link, east to the goal, is blocked.
// With no route left it escapes: 60° either side of the plan are blocked too, so the turns
// widen until one leads out.
TEST(Navigator, EscapesADeadEndByWideningItsTurns) {
  const std::vector<PlaceNode> places{{{0, 0}, 0.0}, {{1, 0}, 0.0}};
  const RoutePlan plan = plan_to_goal(places, {{0, 1}}, 1);
  PointWorld world({{-1.0, 0.5, 0.05, 0.5}, {-1.0, 0.5, -0.5, -0.05}, {0.05, 0.5, -0.5, 0.5}});
  NavigatorParams params;
  params.max_steps = 40;
  const NavigationResult result =
      navigate(world, places, plan, point_oracle(world, {{0, 0}, {1, 0}}), params);
  double westmost_m = 0.0;
  for (const NavigationStep& step : result.steps) westmost_m = std::min(westmost_m, step.truth.x_m);
  EXPECT_LT(westmost_m, -0.3);
}

// A robot beside its places runs along furniture and grazes it (here its directions are 4°
// off towards a table edge, as a distorted lattice makes them). Truth: two rows of places 1 m
// apart, y = 0 and y = 1, x = 0..4; the table's edge runs 0.1 m below the lower row from
// x = 0.5 to 3.5 m; the lattice is the truth turned by −4°. The goal is place 4 at (4, 0).
TEST(Navigator, SlidesPastFurnitureItGrazesInsteadOfDroppingLinks) {
  std::vector<Eigen::Vector2d> truth;
  std::vector<PlaceNode> places;
  const Eigen::Rotation2Dd distortion(deg_to_rad(-4.0));
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 5; ++x) {
      truth.emplace_back(x, y);
      places.push_back({distortion * truth.back(), 0.0});
    }
  }
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 4);
  const std::vector<Box> table{{0.5, 3.5, -1.0, -0.1}};

  NavigatorParams params;
  params.look_ahead_links = 0;  // the places' own directions, 4° off
  PointWorld sliding(table);
  const NavigationResult slid =
      navigate(sliding, places, plan, point_oracle(sliding, truth), params);
  ASSERT_TRUE(slid.reached) << slid.steps.size() << " steps";
  EXPECT_GE(slid.sidesteps, 1);  // it did graze the table...
  EXPECT_EQ(slid.replans, 0);    // ... and turned a little away each time
  // Hardly longer than straight along x to where it stopped (the goal's place recognised).
  EXPECT_LT(slid.path_length_m, 1.05 * sliding.truth().x_m);

  // Without sidesteps (the loop before them) each graze drops a link of the plan.
  params.sidesteps = 0;
  PointWorld dropping(table);
  const NavigationResult dropped =
      navigate(dropping, places, plan, point_oracle(dropping, truth), params);
  ASSERT_TRUE(dropped.reached) << dropped.steps.size() << " steps";
  EXPECT_GE(dropped.replans, 1);
}

// The route zig-zags: places 1 m apart along x, every other one 0.45 m up, linked in a chain.
// Following each place's direction the robot zig-zags with it; looking ahead it drives the
// straight line to the goal (8, 0).
TEST(Navigator, LookAheadDrivesStraightWhereTheRouteZigZags) {
  std::vector<Eigen::Vector2d> truth;
  std::vector<PlaceNode> places;
  std::vector<Edge> chain;
  for (int x = 0; x < 9; ++x) {
    truth.emplace_back(x, x % 2 == 1 ? 0.45 : 0.0);
    places.push_back({truth.back(), 0.0});
    if (x > 0) chain.emplace_back(x - 1, x);
  }
  const RoutePlan plan = plan_to_goal(places, chain, 8);
  const auto run = [&](int links, double& widest_m) {
    NavigatorParams params;
    params.look_ahead_links = links;
    PointWorld world;
    const NavigationResult result =
        navigate(world, places, plan, point_oracle(world, truth, true), params);
    EXPECT_TRUE(result.reached) << links << " links";
    widest_m = 0.0;
    for (const NavigationStep& step : result.steps) widest_m = std::max(widest_m, step.truth.y_m);
    // Stopped where the goal place is the nearest: past x = 7.5 m.
    EXPECT_GT(world.truth().x_m, 7.4) << links << " links";
    return result.path_length_m / world.truth().x_m;
  };
  double widest_place_by_place_m = 0.0, widest_looking_ahead_m = 0.0;
  const double place_by_place = run(0, widest_place_by_place_m);
  const double looking_ahead = run(6, widest_looking_ahead_m);
  EXPECT_GT(place_by_place, 1.05);
  EXPECT_GT(widest_place_by_place_m, 0.3);
  EXPECT_LT(looking_ahead, 1.02);
  EXPECT_LT(widest_looking_ahead_m, 0.1);
}

// A localiser that knows how far the robot stands from the nearest place: the match's
// dissimilarity per value is that distance in metres, so that a match limit of d says "within
// d metres of a place". All places face +x; the robot's heading relative to `misled`'s image
// reads `misled_rad` too far left (a place whose stored heading is wrong: its direction leads
// elsewhere). `world` must outlive the localiser.
PanoramaLocaliser distance_oracle(const PointWorld& world, std::vector<Eigen::Vector2d> truth,
                                  int misled = -1, double misled_rad = 0.0) {
  return [&world, truth, misled, misled_rad](const cv::Mat&) {
    std::size_t nearest = 0;
    const Eigen::Vector2d at = world.truth().floor_position();
    for (std::size_t i = 1; i < truth.size(); ++i) {
      if ((truth[i] - at).norm() < (truth[nearest] - at).norm()) nearest = i;
    }
    const double error_rad = static_cast<int>(nearest) == misled ? misled_rad : 0.0;
    memory::Localisation localisation = recognised(nearest, world.truth().heading_rad + error_rad);
    localisation.best.front().dissimilarity_per_value = (truth[nearest] - at).norm();
    return localisation;
  };
}

// The farthest the robot stood from the row y = 0 over the run, and where it stopped.
double farthest_from_row_m(const NavigationResult& result, const PointWorld& world) {
  double farthest = std::abs(world.truth().y_m);
  for (const NavigationStep& step : result.steps) {
    farthest = std::max(farthest, std::abs(step.truth.y_m));
  }
  return farthest;
}

// Five places in a row, 1 m apart along x, the goal at the east end; place 2's heading reads
// 90° off, so its direction sends the robot south, off the map, and it keeps recognising place
// 2 (the nearest) as it goes. Views farther than 0.7 m from every place are not recognised.
TEST(Navigator, LostOffTheMapGoesBackAndStopsInsteadOfDrivingAway) {
  std::vector<PlaceNode> places;
  std::vector<Eigen::Vector2d> truth;
  for (int x = 0; x < 5; ++x) {
    places.push_back({Eigen::Vector2d(x, 0), 0.0});
    truth.emplace_back(x, 0);
  }
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 4);
  NavigatorParams params;
  params.max_steps = 200;
  const auto run = [&](const NavigatorParams& with, PointWorld& world) {
    return navigate(world, places, plan, distance_oracle(world, truth, 2, kPi / 2), with, {}, 0.7);
  };
  PointWorld world;
  const NavigationResult result = run(params, world);
  EXPECT_FALSE(result.reached);
  // Lost, back, on again (the same way: no route is left round place 2's link), lost again:
  // once more than the two recoveries allowed, then back to its start and stopped, long
  // before the budget.
  EXPECT_EQ(result.lost_events, 3);
  EXPECT_EQ(result.recoveries, 2);
  EXPECT_TRUE(result.gave_up);
  EXPECT_LT(static_cast<int>(result.steps.size()), params.max_steps / 2);
  const int lost_steps =
      static_cast<int>(std::count_if(result.steps.begin(), result.steps.end(),
                                     [](const NavigationStep& step) { return step.lost; }));
  EXPECT_EQ(lost_steps, 3);
  // Stopped back at its start (the dead reckoning of a point robot without noise: exact but
  // for the last return step's quarter step).
  EXPECT_LT(world.truth().floor_position().norm(), 0.25 * params.step_m + 0.01);
  // Never farther than the views that found it lost past the 0.7 m: the first not recognised
  // and three more, each farther from the map (steps of 0.15 m).
  EXPECT_LT(farthest_from_row_m(result, world), 0.7 + (params.lost_views + 1) * params.step_m);

  // The navigator of §3.5 without the checks drives on south until its budget is spent.
  NavigatorParams unaware = params;
  unaware.lost_views = 0;
  unaware.stay_within_map_extent = false;
  PointWorld away;
  const NavigationResult driven_away = run(unaware, away);
  EXPECT_EQ(driven_away.lost_events, 0);
  EXPECT_GT(std::abs(away.truth().y_m), 10.0);

  // Where every view matches (a field seen from 10 cm: off the map as well as on it), the
  // map's extent still bounds the way: the row is 4 m across, and a robot farther than that
  // from its start by its dead reckoning is lost, goes back to where it last recognised a
  // place within that reach, and after the recoveries goes back to its start and stops.
  NavigatorParams fenced = params;
  fenced.lost_views = 0;
  PointWorld fenced_world;
  const NavigationResult bounded = navigate(
      fenced_world, places, plan, distance_oracle(fenced_world, truth, 2, kPi / 2), fenced, {});
  EXPECT_FALSE(bounded.reached);
  EXPECT_TRUE(bounded.gave_up);
  EXPECT_EQ(bounded.lost_events, 3);
  double farthest_from_start = 0.0;
  for (const NavigationStep& step : bounded.steps) {
    farthest_from_start = std::max(farthest_from_start, step.truth.floor_position().norm());
  }
  EXPECT_LT(farthest_from_start, 4.0 + fenced.step_m + 0.01);
  EXPECT_LT(fenced_world.truth().floor_position().norm(), 0.25 * fenced.step_m + 0.01);

  // Kept within the lattice's bounding box grown by one spacing (1 m here) instead, by the
  // dead reckoning carried onto the lattice from the first place recognised, the robot never
  // goes more than a step past 1 m from the row.
  NavigatorParams boxed = fenced;
  boxed.stay_within_lattice_box = true;
  PointWorld boxed_world;
  const NavigationResult in_box = navigate(
      boxed_world, places, plan, distance_oracle(boxed_world, truth, 2, kPi / 2), boxed, {});
  EXPECT_TRUE(in_box.gave_up);
  EXPECT_LT(farthest_from_row_m(in_box, boxed_world), 1.0 + boxed.step_m + 0.01);
}

// Two places 1 m apart, the goal the second; the robot recognises nothing (every view 100 per
// value from its best place, the limit 1). It never reaches the goal, and gives up after
// finding itself lost once more than the recoveries allow.
NavigationResult navigate_never_recognising(NavigationWorld& world, const NavigatorParams& params) {
  const std::vector<PlaceNode> places{{Eigen::Vector2d(0, 0), 0.0}, {Eigen::Vector2d(1, 0), 0.0}};
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 1);
  const PanoramaLocaliser far_away = [&world](const cv::Mat&) {
    memory::Localisation localisation = recognised(0, world.truth().heading_rad);
    localisation.best.front().dissimilarity_per_value = 100.0;
    return localisation;
  };
  NavigationResult result = navigate(world, places, plan, far_away, params, {}, 1.0);
  EXPECT_FALSE(result.reached);
  EXPECT_TRUE(result.gave_up);
  EXPECT_EQ(result.lost_events, params.recoveries + 1);
  return result;
}

// A robot that recognises nothing (started off the map): lost after lost_views views, back to
// its start by dead reckoning, out again turned 90° one way, then the other, and after the
// recoveries back at its start, stopped.
TEST(Navigator, NeverRecognisingAPlaceItStopsWhereItStarted) {
  PointWorld world;
  const NavigatorParams params;
  const NavigationResult result = navigate_never_recognising(world, params);
  EXPECT_EQ(result.recoveries, 0);
  EXPECT_LT(std::hypot(world.truth().x_m, world.truth().y_m), 0.05);
  double farthest = 0.0;
  for (const NavigationStep& step : result.steps) {
    farthest = std::max(farthest, std::hypot(step.truth.x_m, step.truth.y_m));
  }
  // Lost at the fourth view (the first not recognised, three more no nearer to the map).
  EXPECT_LT(farthest, params.lost_views * params.step_m + 0.05);
  EXPECT_LT(static_cast<int>(result.steps.size()), 40);
}

// A robot that recognises nothing drives out, finds itself lost and turns back, but there the
// floor holds it (past 0.2 m from its start every move is blocked: a dead end its dead
// reckoning does not know of). Its returns, blocked every way round, end; after the recoveries
// it gives up where it stands, long before its budget, instead of turning on the spot until the
// budget runs out.
TEST(Navigator, AReturnBlockedEveryWayEndsInsteadOfSpendingTheBudget) {
  class Stuck : public NavigationWorld {
   public:
    cv::Mat view(int step) override { return inner.view(step); }
    double move(double turn_rad, double distance_m) override {
      if (inner.truth().floor_position().norm() > 0.2) {
        inner.move(turn_rad, 0.0);
        return 0.0;
      }
      return inner.move(turn_rad, distance_m);
    }
    CameraPose truth() const override { return inner.truth(); }
    PointWorld inner;
  } world;
  const NavigatorParams params;
  const NavigationResult result = navigate_never_recognising(world, params);
  EXPECT_LT(static_cast<int>(result.steps.size()), params.max_steps / 2);
}

// Measured links (motions, §3.4) along rows of places 0.5 m apart, all facing +x: each link's
// direction is the true one, but for the link from `bad` to `bad + 1`, whose measured
// direction points back at both ends (a look-alike's fit): at `bad` the plan says west, at
// `bad + 1` east. The truth is the lattice: a plan over it is right.
struct BackPointingLink {
  std::vector<PlaceNode> places;
  std::vector<Eigen::Vector2d> truth;
  std::vector<MeasuredLink> links;

  // `rows` rows of 8 places, y = 0, 0.5, ...; rungs between rows at every place.
  BackPointingLink(int rows, int bad) {
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < 8; ++x) {
        places.push_back({Eigen::Vector2d(0.5 * x, 0.5 * y), 0.0});
        truth.push_back(places.back().position_m);
        const int here = y * 8 + x;
        if (x > 0) {
          const bool back = here - 1 == bad;
          links.push_back({{here - 1, here}, 0.5, back ? M_PI : 0.0, back ? 0.0 : M_PI});
        }
        if (y > 0) links.push_back({{here - 8, here}, 0.5, M_PI / 2, -M_PI / 2});
      }
    }
  }
};

// Over the back-pointing link the robot swings between its two ends (loop detection off, to
// isolate the stall) until the budget is spent; stalled, it drops the link and switches to the
// plan over the lattice, or (stall_other_links off) plans round the link over the motions.
TEST(Navigator, AStalledRobotDropsTheLinkItKeepsMissingAndSwitchesToTheOtherLinks) {
  const BackPointingLink line(1, 4);
  const RoutePlan plan = plan_to_goal(line.places, line.links, 7);
  const RoutePlan lattice = plan_to_goal(line.places, lattice_neighbours(line.places, 0.6), 7);
  ASSERT_EQ(plan.next[4], 5);
  NavigatorParams params;
  params.loop_entries = 0;
  params.stall_spacings = 0.0;
  PointWorld swinging;
  const NavigationResult old =
      navigate(swinging, line.places, plan, lattice, point_oracle(swinging, line.truth), params, {},
               std::numeric_limits<double>::infinity(), {});
  EXPECT_FALSE(old.reached);
  EXPECT_LT(swinging.truth().x_m, 2.5);  // never past the link's far end
  EXPECT_EQ(old.stalls, 0);

  params.stall_spacings = 4.0;  // × the lattice spacing, 0.5 m: 2 m, 14 steps of 0.15 m
  PointWorld world;
  const NavigationResult result =
      navigate(world, line.places, plan, lattice, point_oracle(world, line.truth), params, {},
               std::numeric_limits<double>::infinity(), {});
  ASSERT_TRUE(result.reached) << result.steps.size() << " steps";
  EXPECT_EQ(result.stalls, 1);
  EXPECT_EQ(result.link_switches, 1);
  EXPECT_NEAR(world.truth().x_m, 3.5, 0.25);
  // 3.5 m to the goal, the swing before the stall (at most 2 m past the nearest place) and
  // back: well within 70 steps of 0.15 m.
  EXPECT_LT(result.steps.size(), 70u);
  const auto stalled = std::count_if(result.steps.begin(), result.steps.end(),
                                     [](const NavigationStep& step) { return step.stalled; });
  EXPECT_EQ(stalled, 1);

  // Two rows: without the switch, the plan without the link goes round it by the second row.
  const BackPointingLink rows(2, 4);
  const RoutePlan two_rows = plan_to_goal(rows.places, rows.links, 7);
  ASSERT_EQ(two_rows.next[4], 5);
  params.stall_other_links = false;
  PointWorld around;
  const NavigationResult dropped =
      navigate(around, rows.places, two_rows, point_oracle(around, rows.truth), params);
  ASSERT_TRUE(dropped.reached) << dropped.steps.size() << " steps";
  EXPECT_GE(dropped.stalls, 1);
  EXPECT_EQ(dropped.link_switches, 0);
  EXPECT_NEAR(around.truth().x_m, 3.5, 0.25);
  params.stall_spacings = 0.0;
  PointWorld stuck;
  EXPECT_FALSE(
      navigate(stuck, rows.places, two_rows, point_oracle(stuck, rows.truth), params).reached);
}

// The same two rows with a folded lattice as the fallback (every place right of x = 1.25 m
// mirrored onto the left, as a spring lattice folds): the places the robot drove between lie
// on top of each other there, the lattice does not explain its motion, and the stalled robot
// stays on the motions, planning round the dropped link.
TEST(Navigator, AStalledRobotKeepsToTheMotionsWhenTheLatticeDoesNotExplainItsMotion) {
  const BackPointingLink rows(2, 4);
  std::vector<PlaceNode> folded = rows.places;
  for (PlaceNode& place : folded) {
    if (place.position_m.x() > 1.25) place.position_m.x() = 2.5 - place.position_m.x();
  }
  const RoutePlan plan = plan_to_goal(folded, rows.links, 7);
  const RoutePlan lattice = plan_to_goal(folded, lattice_neighbours(folded, 0.6), 7);
  NavigatorParams params;
  params.loop_entries = 0;
  params.stall_spacings = 4.0;
  PointWorld world;
  const NavigationResult result =
      navigate(world, folded, plan, lattice, point_oracle(world, rows.truth), params, {},
               std::numeric_limits<double>::infinity(), {});
  ASSERT_TRUE(result.reached) << result.steps.size() << " steps";
  EXPECT_GE(result.stalls, 1);
  EXPECT_EQ(result.link_switches, 0);
  EXPECT_NEAR(world.truth().x_m, 3.5, 0.25);
}

TEST(Navigator, AFallbackPlanToAnotherGoalIsAUsageError) {
  const BackPointingLink line(1, 4);
  PointWorld world;
  EXPECT_THROW(navigate(world, line.places, plan_to_goal(line.places, line.links, 7),
                        plan_to_goal(line.places, line.links, 6), point_oracle(world, line.truth),
                        NavigatorParams{}, {}, std::numeric_limits<double>::infinity(), {}),
               UsageError);
}

TEST(Navigator, ReadsItsParametersAndRejectsSidestepsPastHalfATurn) {
  NavigatorParams params;
  load_navigator_params(ConfigReader::from_string("navigator:\n  look_ahead_links: 3\n"
                                                  "  look_ahead_tolerance_spacings: 0.7\n"
                                                  "  sidesteps: 6\n  sidestep_deg: 60\n",
                                                  "navigation.yaml")
                            .section("navigator"),
                        params);
  EXPECT_EQ(params.look_ahead_links, 3);
  EXPECT_DOUBLE_EQ(params.look_ahead_tolerance_spacings, 0.7);
  EXPECT_EQ(params.sidesteps, 6);
  EXPECT_DOUBLE_EQ(params.sidestep_deg, 60.0);
  load_navigator_params(ConfigReader::from_string("navigator:\n  lost_views: 5\n  lost_jumps: 2\n"
                                                  "  lost_jump_window: 4\n  recoveries: 1\n"
                                                  "  return_max_steps: 9\n",
                                                  "navigation.yaml")
                            .section("navigator"),
                        params);
  EXPECT_EQ(params.lost_views, 5);
  EXPECT_EQ(params.lost_jumps, 2);
  EXPECT_EQ(params.lost_jump_window, 4);
  EXPECT_EQ(params.recoveries, 1);
  EXPECT_EQ(params.return_max_steps, 9);
  load_navigator_params(ConfigReader::from_string("navigator:\n  stall_spacings: 3\n"
                                                  "  stall_other_links: false\n",
                                                  "navigation.yaml")
                            .section("navigator"),
                        params);
  EXPECT_DOUBLE_EQ(params.stall_spacings, 3.0);
  EXPECT_FALSE(params.stall_other_links);
  const auto error_of = [](const std::string& yaml) -> std::string {
    NavigatorParams ignored;
    try {
      load_navigator_params(ConfigReader::from_string(yaml, "navigation.yaml").section("navigator"),
                            ignored);
    } catch (const ConfigError& error) {
      return error.what();
    }
    return "";
  };
  // Seven sidesteps of 60°: the last turns 240° from the plan.
  const std::string past = error_of("navigator:\n  sidesteps: 7\n  sidestep_deg: 60\n");
  EXPECT_NE(past.find("'navigator.sidesteps' (7)"), std::string::npos) << past;
  EXPECT_NE(past.find("turn the last sidestep 240 degrees"), std::string::npos) << past;
  EXPECT_NE(error_of("navigator:\n  look_ahead_links: -1\n").find("look_ahead_links"),
            std::string::npos);
  EXPECT_NE(error_of("navigator:\n  sidestep_deg: 0\n").find("sidestep_deg"), std::string::npos);
}

}  // namespace
}  // namespace omninav::navigation
