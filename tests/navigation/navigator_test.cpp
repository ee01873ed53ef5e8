#include "omninav/navigation/navigator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/navigation/robot_worlds.hpp"
#include "omninav/sim/room.hpp"

namespace omninav::navigation {
namespace {

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
    params_.geometry.width_px = 36;  // the oracle ignores the image
    params_.geometry.height_px = 4;
    params_.rays_per_pixel = 1;
  }

  Localiser oracle(const sim::VirtualRobot& robot) const {
    return [this, &robot](const cv::Mat&) {
      PlaceMatch match;
      double best = 1e9;
      const Eigen::Vector2d at(robot.pose().x_m, robot.pose().y_m);
      for (std::size_t i = 0; i < places_.size(); ++i) {
        const double distance = (places_[i].position_m - at).norm();
        if (distance < best) {
          best = distance;
          match.place = static_cast<int>(i);
        }
      }
      match.similarity = 1000.0;
      match.heading_in_place_rad =
          signed_difference(robot.pose().heading_rad, places_[match.place].heading_rad);
      return match;
    };
  }

  sim::World world_;
  std::vector<PlaceNode> places_;
  sim::RenderParams params_;
};

TEST_F(OracleNavigation, ReachesTheGoalAlongAShortPath) {
  const sim::Renderer renderer(world_, params_);
  const RoutePlan plan = plan_to_goal(places_, lattice_neighbours(places_, 0.45),
                                      static_cast<int>(places_.size()) - 1);
  const Eigen::Vector2d goal = places_.back().position_m;
  sim::RobotParams robot_params;
  sim::VirtualRobot robot(
      world_, {places_.front().position_m.x(), places_.front().position_m.y(), 1.0, 2.0, 0.0, 0.0},
      robot_params);
  const NavigationResult result =
      navigate(robot, renderer, places_, plan, oracle(robot), NavigatorParams{});
  ASSERT_TRUE(result.reached) << result.steps.size() << " steps";
  EXPECT_LT((Eigen::Vector2d(robot.pose().x_m, robot.pose().y_m) - goal).norm(), 0.3);
  // The route bends round furniture: within 1.5 × the planned route's length.
  EXPECT_LT(result.path_length_m, 1.5 * plan.cost_m[0] + 0.3);
  EXPECT_EQ(result.jumps, 0);
}

TEST_F(OracleNavigation, FollowsThePlanWhateverTheRobotsStartingHeading) {
  const sim::Renderer renderer(world_, params_);
  const RoutePlan plan = plan_to_goal(places_, lattice_neighbours(places_, 0.45), 0);
  for (double heading_deg : {-170.0, -60.0, 45.0, 135.0}) {
    sim::VirtualRobot robot(world_,
                            {places_.back().position_m.x(), places_.back().position_m.y(), 1.0,
                             deg_to_rad(heading_deg), 0.0, 0.0},
                            sim::RobotParams{});
    EXPECT_TRUE(navigate(robot, renderer, places_, plan, oracle(robot), NavigatorParams{}).reached)
        << "starting heading " << heading_deg;
  }
}

TEST_F(OracleNavigation, GivesUpWhenTheBudgetIsSpent) {
  const sim::Renderer renderer(world_, params_);
  const RoutePlan plan = plan_to_goal(places_, lattice_neighbours(places_, 0.45), 0);
  sim::VirtualRobot robot(
      world_, {places_.back().position_m.x(), places_.back().position_m.y(), 1.0, 0.0, 0.0, 0.0},
      sim::RobotParams{});
  NavigatorParams params;
  params.max_steps = 3;
  const NavigationResult result = navigate(robot, renderer, places_, plan, oracle(robot), params);
  EXPECT_FALSE(result.reached);
  EXPECT_EQ(result.steps.size(), 3u);
}

// A world of its own behind the navigator's interface: a point robot on a plane, with or
// without a wall stub (x 0.4..0.6 m, y below 0.6 m) that the lattice knows nothing of.
class PointWorld : public NavigationWorld {
 public:
  explicit PointWorld(bool wall) : wall_(wall) {}
  cv::Mat view(int) override { return {}; }
  double move(double turn_rad, double distance_m) override {
    pose_.heading_rad = wrap_angle(pose_.heading_rad + turn_rad);
    double driven = 0.0;
    for (; driven + 0.01 <= distance_m + 1e-9; driven += 0.01) {
      const double x = pose_.x_m + 0.01 * std::cos(pose_.heading_rad);
      const double y = pose_.y_m + 0.01 * std::sin(pose_.heading_rad);
      if (wall_ && x > 0.4 && x < 0.6 && y < 0.6) break;
      pose_.x_m = x;
      pose_.y_m = y;
    }
    return driven;
  }
  CameraPose truth() const override { return pose_; }

 private:
  const bool wall_;
  CameraPose pose_{0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
};

// The place whose true position (`truth`, not the lattice) is nearest to the robot, all places
// facing +x; `world` must outlive the localiser.
Localiser point_oracle(const PointWorld& world, std::vector<Eigen::Vector2d> truth) {
  return [&world, truth](const cv::Mat&) {
    PlaceMatch match;
    double best = 1e9;
    const Eigen::Vector2d at(world.truth().x_m, world.truth().y_m);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      if ((truth[i] - at).norm() < best) {
        best = (truth[i] - at).norm();
        match.place = static_cast<int>(i);
      }
    }
    match.similarity = 1000.0;
    match.heading_in_place_rad = world.truth().heading_rad;
    return match;
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
  PointWorld world(true);
  std::vector<Eigen::Vector2d> truth;
  for (const PlaceNode& place : places) truth.push_back(place.position_m);
  const Localiser oracle = point_oracle(world, truth);
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
  PointWorld looping(false);
  const NavigationResult lost =
      navigate(looping, places, plan, point_oracle(looping, truth), params);
  EXPECT_FALSE(lost.reached);

  params.loop_entries = 3;
  PointWorld world(false);
  const NavigationResult result = navigate(world, places, plan, point_oracle(world, truth), params);
  ASSERT_TRUE(result.reached) << result.steps.size() << " steps";
  EXPECT_GE(result.loops, 1);
  // Swinging, then by B, D and E: about 1 + 1 + 1.5 + 1 m, well within 40 steps of 0.15 m.
  EXPECT_LT(result.steps.size(), 40u);
}

// The robot stops on recognising the goal's place (§3.5), which may be a whole cell from the
// goal pose; homing on the goal image takes it there. Here the goal image is seen as from its
// true pose: distance and bearing exact, so the control is what is tested.
TEST(Navigator, HomesOnTheGoalImageAfterRecognisingItsPlace) {
  std::vector<PlaceNode> places;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 3; ++x) places.push_back({Eigen::Vector2d(x, y), 0.0});
  }
  std::vector<Eigen::Vector2d> truth;
  for (const PlaceNode& place : places) truth.push_back(place.position_m);
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 2);
  // The goal pose lies on the far side of place 2 at (2, 0) from the start at the origin.
  const Eigen::Vector2d goal(2.4, 0.3);
  const auto homing_for = [&goal](const PointWorld& world) -> GoalHoming {
    return [&world, &goal](const cv::Mat&) {
      const CameraPose at = world.truth();
      const Eigen::Vector2d to = goal - Eigen::Vector2d(at.x_m, at.y_m);
      return GoalCue{to.norm(), signed_difference(std::atan2(to.y(), to.x()), at.heading_rad),
                     to.norm() > 0.01};
    };
  };
  const auto miss_m = [&goal](const PointWorld& world) {
    return std::hypot(world.truth().x_m - goal.x(), world.truth().y_m - goal.y());
  };

  NavigatorParams params;
  params.home_on_goal_image = false;
  PointWorld stopping(false);
  const NavigationResult stopped =
      navigate(stopping, places, plan, point_oracle(stopping, truth), params, homing_for(stopping));
  ASSERT_TRUE(stopped.reached);
  EXPECT_GT(miss_m(stopping), 0.6);  // entered place 2's cell at x ≈ 1.5 m

  params.home_on_goal_image = true;
  PointWorld world(false);
  const NavigationResult result =
      navigate(world, places, plan, point_oracle(world, truth), params, homing_for(world));
  ASSERT_TRUE(result.reached);
  EXPECT_LE(miss_m(world), params.homing_stop_m + 1e-9);
  EXPECT_GT(result.homing_steps, 0);
  EXPECT_LE(result.homing_steps, params.homing_max_steps);
  // Homing goes straight at the goal: no longer than the way from where the robot stopped.
  EXPECT_LT(result.path_length_m, stopped.path_length_m + miss_m(stopping) + 1e-6);
}

}  // namespace
}  // namespace omninav::navigation
