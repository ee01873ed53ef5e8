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

// A world of its own behind the navigator's interface: a point robot on a plane with a wall
// stub between places 0 and 1 (x 0.4..0.6 m, y below 0.6 m) that the lattice knows nothing of.
class WallWorld : public NavigationWorld {
 public:
  cv::Mat view(int) override { return {}; }
  double move(double turn_rad, double distance_m) override {
    pose_.heading_rad = wrap_angle(pose_.heading_rad + turn_rad);
    double driven = 0.0;
    for (; driven + 0.01 <= distance_m + 1e-9; driven += 0.01) {
      const double x = pose_.x_m + 0.01 * std::cos(pose_.heading_rad);
      const double y = pose_.y_m + 0.01 * std::sin(pose_.heading_rad);
      if (x > 0.4 && x < 0.6 && y < 0.6) break;
      pose_.x_m = x;
      pose_.y_m = y;
    }
    return driven;
  }
  CameraPose truth() const override { return pose_; }

 private:
  CameraPose pose_{0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
};

TEST(Navigator, ReplansWithoutALinkThatFurnitureBlocks) {
  // 3 × 3 places 1 m apart, all facing +x; the goal is place 2 at (2, 0), straight east of the
  // start behind the wall stub.
  std::vector<PlaceNode> places;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 3; ++x) places.push_back({Eigen::Vector2d(x, y), 0.0});
  }
  const RoutePlan plan = plan_to_goal(places, lattice_neighbours(places, 1.5), 2);
  ASSERT_EQ(plan.next[0], 1);
  WallWorld world;
  const Localiser oracle = [&world, &places](const cv::Mat&) {
    PlaceMatch match;
    double best = 1e9;
    const Eigen::Vector2d at(world.truth().x_m, world.truth().y_m);
    for (std::size_t i = 0; i < places.size(); ++i) {
      if ((places[i].position_m - at).norm() < best) {
        best = (places[i].position_m - at).norm();
        match.place = static_cast<int>(i);
      }
    }
    match.similarity = 1000.0;
    match.heading_in_place_rad = world.truth().heading_rad;
    return match;
  };
  const NavigationResult result = navigate(world, places, plan, oracle, NavigatorParams{});
  ASSERT_TRUE(result.reached);
  EXPECT_GE(result.replans, 1);
  // Stopped where the goal place is the nearest: within half a cell's diagonal of it.
  EXPECT_LT(std::hypot(world.truth().x_m - 2.0, world.truth().y_m), std::hypot(0.5, 0.5));
  // Round the stub: longer than the straight 2 m, shorter than going up a whole row and back.
  EXPECT_GT(result.path_length_m, 2.0);
  EXPECT_LT(result.path_length_m, 4.0);
}

}  // namespace
}  // namespace omninav::navigation
