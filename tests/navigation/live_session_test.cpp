// The live session (live_session.hpp) on frames rendered along a path through the room's grid
// map (tests/support/room_navigation_map.hpp): its compass against the renderer's headings and
// against the offline compass on the same frames, its recognised places against the renderer's
// positions, bad frames skipped without changing what the good ones give, and exploring into a
// map file.
#include "omninav/navigation/live_session.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "measures/scratch_dir.hpp"
#include "omninav/compass/compass_run.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::navigation {
namespace {

using measures::testing::ScratchDir;
using testing::kRoomGridSpacing_m;
using testing::RoomNavigation;

class LiveSessionTest : public RoomNavigation {
 protected:
  // A robot driving forwards across the grid on an arc that turns it 30° clockwise over 2.2 m,
  // 5 cm a frame at 10 frames/s.
  static std::vector<LiveFrame> path_frames(std::vector<CameraPose>& truth) {
    const double radius_m = 2.2 / deg_to_rad(30.0);
    std::vector<LiveFrame> frames;
    for (int i = 0; i <= 44; ++i) {
      const double turn = 0.05 * i / radius_m;
      const CameraPose pose{1.4 + radius_m * std::sin(turn),
                            1.75 - radius_m * (1.0 - std::cos(turn)),
                            1.0,
                            -turn,
                            0.0,
                            0.0};
      truth.push_back(pose);
      frames.push_back({map().renderer->render(pose), 100.0 + 0.1 * i, pose.on_floor()});
    }
    return frames;
  }

  // The room's map in a file, for the session to load.
  static std::filesystem::path saved_map(const ScratchDir& scratch) {
    const std::filesystem::path file = scratch / "room.vmem";
    memory::MapStore(file).save(map().memory);
    return file;
  }
};

TEST_F(LiveSessionTest, CompassAndPlacesAgainstTheRenderer) {
  ScratchDir scratch("live_session");
  LiveSession session(LiveSessionParams{}, saved_map(scratch));
  ASSERT_FALSE(session.no_belief_reason()) << *session.no_belief_reason();
  std::vector<CameraPose> truth;
  const std::vector<LiveFrame> frames = path_frames(truth);
  // The offline compass (`omninav compass`'s) on the same frames, started at the same heading.
  compass::CompassRun offline(compass::CompassParams{}, std::nullopt);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_TRUE(map().world.is_free(truth[i].x_m, truth[i].y_m, 0.1)) << i;
    const std::optional<LiveOutput> output = session.push(frames[i]);
    ASSERT_TRUE(output);
    EXPECT_EQ(output->frame, static_cast<int>(i));
    const compass::CompassEstimate expected =
        offline.push(frames[i].image, static_cast<int>(i), "frame", truth.front().heading_rad);
    EXPECT_EQ(output->compass.heading_rad, expected.heading_rad) << i;
    EXPECT_EQ(output->compass.heading_sigma_rad, expected.heading_sigma_rad) << i;
    // The compass over 2.2 m and 30° of turn in the room at 180 columns: within 3° (a column is
    // 2°; the sub-pixel fit gains on that).
    EXPECT_LT(std::fabs(signed_difference(output->compass.heading_rad, truth[i].heading_rad)),
              deg_to_rad(3.0))
        << i;
    ASSERT_TRUE(output->place);
    // From the fourth frame on (the belief starts uniform and gathers over three views), the
    // belief is confident and on a place of the robot's grid 8-neighbourhood.
    if (i >= 3) {
      const CameraPose& place = map().grid[output->place->place].pose;
      EXPECT_LT(std::hypot(place.x_m - truth[i].x_m, place.y_m - truth[i].y_m),
                1.5 * kRoomGridSpacing_m)
          << i;
      EXPECT_FALSE(output->place->lost) << i << ": confidence " << output->place->confidence;
    }
    EXPECT_GE(output->place->confidence, output->place->probability);
    EXPECT_LE(output->place->similarity, 1000.0);
    EXPECT_FALSE(output->new_place);  // not exploring
  }
}

TEST_F(LiveSessionTest, BadFramesAreSkippedAndCountedWithoutChangingTheOthers) {
  ScratchDir scratch("live_session_bad");
  const std::filesystem::path file = saved_map(scratch);
  std::vector<CameraPose> truth;
  std::vector<LiveFrame> frames = path_frames(truth);
  frames.resize(12);
  LiveSession clean(LiveSessionParams{}, file);
  LiveSession noisy(LiveSessionParams{}, file);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const LiveFrame& frame = frames[i];
    if (i == 3) {  // junk between frames 2 and 3
      const double stamp = frames[i - 1].stamp_s + 0.01;
      EXPECT_FALSE(noisy.push({cv::Mat(), stamp, std::nullopt}));
      EXPECT_EQ(noisy.last_skip()->first, SkipReason::kBadImage);
      EXPECT_FALSE(noisy.push({cv::Mat(24, 180, CV_16UC3, cv::Scalar::all(9)), stamp, {}}));
      EXPECT_FALSE(noisy.push({cv::Mat(24, 90, CV_8UC3, cv::Scalar::all(9)), stamp, {}}));
      EXPECT_EQ(noisy.last_skip()->first, SkipReason::kSizeChange);
      EXPECT_FALSE(noisy.push({cv::Mat(24, 180, CV_8UC1, cv::Scalar::all(9)), stamp, {}}));
      EXPECT_FALSE(noisy.push({frame.image, frames[i - 1].stamp_s, frame.odometry}));  // again
      EXPECT_EQ(noisy.last_skip()->first, SkipReason::kStamp);
      EXPECT_FALSE(noisy.push({frame.image, std::nan(""), frame.odometry}));
    }
    const std::optional<LiveOutput> a = clean.push(frame);
    const std::optional<LiveOutput> b = noisy.push(frame);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->frame, b->frame);
    EXPECT_EQ(a->compass.heading_rad, b->compass.heading_rad);
    ASSERT_TRUE(a->place && b->place);
    EXPECT_EQ(a->place->place, b->place->place);
    EXPECT_EQ(a->place->confidence, b->place->confidence);
  }
  EXPECT_EQ(noisy.skipped(SkipReason::kBadImage), 2);
  EXPECT_EQ(noisy.skipped(SkipReason::kSizeChange), 2);
  EXPECT_EQ(noisy.skipped(SkipReason::kStamp), 2);
  EXPECT_EQ(clean.skipped(SkipReason::kStamp), 0);
  // A map's panoramas fix the rows a stream may have, from its first frame on.
  LiveSession session(LiveSessionParams{}, file);
  EXPECT_FALSE(session.push({cv::Mat(30, 180, CV_8UC3, cv::Scalar::all(9)), 1.0, {}}));
  EXPECT_EQ(session.last_skip()->first, SkipReason::kSizeChange);
}

TEST_F(LiveSessionTest, ItsCommandsDriveARenderedRobotToTheGoal) {
  // The closed loop of a robot: the session sees the rendered frame at the robot's true pose,
  // with that pose as odometry; the robot carries out what is left of the command (turn, then
  // drive, with the virtual robot's motion noise) and the next frame is pushed. Start and goal
  // as in the navigator's own short run (tests/evaluation/navigation_trials_test.cpp): 1.8 m
  // apart past the end of a table.
  ScratchDir scratch("live_session_navigate");
  LiveSession session(LiveSessionParams{}, saved_map(scratch));
  const CameraPose start{2.55, 1.15, 1.0, deg_to_rad(150.0), 0.0, 0.0};
  const CameraPose goal{2.3, 2.9, 1.0, deg_to_rad(-60.0), 0.0, 0.0};
  EXPECT_FALSE(session.push({map().renderer->render(start), 1.0, start.on_floor()})->command);
  const memory::PlaceMatch goal_place = session.navigate_to(map().renderer->render(goal), "goal");
  // The goal's place is one the goal image was taken beside (recognise_goal): here the goal lies
  // 0.14 m from its nearest place and 0.22 m from the one min-warping matches best. Homing on
  // the goal image covers the rest.
  EXPECT_LT(place_distance_m(goal_place.place, goal.x_m, goal.y_m), kRoomGridSpacing_m);
  sim::VirtualRobot robot(map().world, start, sim::RobotParams{});
  std::optional<LiveCommand> command;
  double path_m = 0.0;
  int steps = 0;
  // navigator.max_steps views, each followed by a few frames that finish its command.
  for (int frame = 1; frame < 2000; ++frame) {
    const CameraPose pose = robot.pose();
    const std::optional<LiveOutput> output =
        session.push({map().renderer->render(pose), 1.0 + 0.1 * frame, pose.on_floor()});
    ASSERT_TRUE(output && output->command) << frame;
    command = output->command;
    if (command->new_step) {
      EXPECT_EQ(command->step, steps++);
    }
    if (command->state != LiveNavigationState::kDriving) break;
    path_m += robot.move(command->turn_rad, command->distance_m);
  }
  ASSERT_EQ(command->state, LiveNavigationState::kReached) << steps << " steps";
  // The trials' criterion (trials.goal_radius_m): the robot truly stands within 0.3 m of the
  // goal, and it did not wander (the navigator's own run drives less than 1.5 × the straight
  // line here; the live commands are finished by odometry, so a little more is allowed).
  EXPECT_LT(std::hypot(robot.pose().x_m - goal.x_m, robot.pose().y_m - goal.y_m), 0.3);
  EXPECT_LT(path_m, 2.0 * std::hypot(goal.x_m - start.x_m, goal.y_m - start.y_m));
  // Reached, the robot is told to stand still, frame after frame, until told otherwise.
  const CameraPose pose = robot.pose();
  const std::optional<LiveOutput> after =
      session.push({map().renderer->render(pose), 1000.0, pose.on_floor()});
  ASSERT_TRUE(after && after->command);
  EXPECT_EQ(after->command->state, LiveNavigationState::kReached);
  EXPECT_EQ(after->command->turn_rad, 0.0);
  EXPECT_EQ(after->command->distance_m, 0.0);
  session.stop_navigating();
  EXPECT_FALSE(session.push({map().renderer->render(pose), 1001.0, pose.on_floor()})->command);
}

TEST_F(LiveSessionTest, ARobotThatStopsMovingEndsItsCommandAsBlocked) {
  // Frames of a robot that turns as told, then does not get anywhere (its odometry's position
  // stays): the frame after the turn still waits for the drive; the next, with no motion since,
  // ends the command as blocked and is the navigator's next view. A robot that moves on, by
  // contrast, keeps the command until it has driven its distance.
  ScratchDir scratch("live_session_blocked");
  const std::filesystem::path file = saved_map(scratch);
  const CameraPose start{2.55, 1.15, 1.0, deg_to_rad(150.0), 0.0, 0.0};
  const cv::Mat goal = map().renderer->render({2.3, 2.9, 1.0, deg_to_rad(-60.0), 0.0, 0.0});
  const auto frame = [&](const CameraPose& pose, double stamp_s) {
    return LiveFrame{map().renderer->render(pose), stamp_s, pose.on_floor()};
  };
  for (const bool moving : {false, true}) {
    LiveSession session(LiveSessionParams{}, file);
    session.navigate_to(goal, "goal");
    const LiveCommand first = *session.push(frame(start, 1.0))->command;
    ASSERT_EQ(first.state, LiveNavigationState::kDriving);
    ASSERT_TRUE(first.new_step);
    ASSERT_GT(first.distance_m, 0.0);
    CameraPose turned = start;
    turned.heading_rad = wrap_angle(start.heading_rad + first.turn_rad);
    const LiveCommand after_turn = *session.push(frame(turned, 1.1))->command;
    EXPECT_FALSE(after_turn.new_step);
    EXPECT_EQ(after_turn.turn_rad, 0.0);
    EXPECT_EQ(after_turn.distance_m, first.distance_m);
    CameraPose next = turned;  // a third of the way, or nowhere
    if (moving) {
      next.x_m += first.distance_m / 3.0 * std::cos(turned.heading_rad);
      next.y_m += first.distance_m / 3.0 * std::sin(turned.heading_rad);
    }
    const LiveCommand third = *session.push(frame(next, 1.2))->command;
    EXPECT_EQ(third.new_step, !moving);
    EXPECT_EQ(third.step, moving ? 0 : 1);
    if (moving) {
      EXPECT_NEAR(third.distance_m, first.distance_m * 2.0 / 3.0, 1e-9);
    }
  }
}

TEST_F(LiveSessionTest, AGoalImageThatMatchesNoPlaceIsRefused) {
  ScratchDir scratch("live_session_bad_goal");
  LiveSession session(LiveSessionParams{}, saved_map(scratch));
  EXPECT_THROW(session.navigate_to(cv::Mat(30, 180, CV_8UC3, cv::Scalar::all(9)), "goal.png"),
               InputError);
  EXPECT_FALSE(session.navigating());
  EXPECT_THROW(LiveSession(LiveSessionParams{}, std::nullopt)
                   .navigate_to(map().renderer->render({2.3, 2.9, 1.0, 0.0, 0.0, 0.0}), "goal"),
               UsageError);
}

TEST_F(LiveSessionTest, ExploresIntoAMapFileAndSavesIt) {
  ScratchDir scratch("live_session_explore");
  const std::filesystem::path file = scratch / "new.vmem";
  LiveSession session(LiveSessionParams{}, file);
  EXPECT_EQ(session.no_belief_reason(), "the map has no places");
  std::vector<CameraPose> truth;
  const std::vector<LiveFrame> frames = path_frames(truth);
  int places = 0;
  // The first half without exploring, the second into the map: only its frames make places.
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == frames.size() / 2) session.start_exploring();
    const std::optional<LiveOutput> output = session.push(frames[i]);
    ASSERT_TRUE(output);
    EXPECT_FALSE(output->place);
    if (i < frames.size() / 2) {
      EXPECT_FALSE(output->new_place);
    } else if (output->new_place) {
      EXPECT_EQ(*output->new_place, static_cast<std::size_t>(places++));
    }
  }
  session.stop_exploring();
  EXPECT_FALSE(session.exploring());
  ASSERT_GE(places, 2);                         // the first frame explored and at least one more
  EXPECT_FALSE(std::filesystem::exists(file));  // nothing written before save
  session.save();
  const memory::VisualMemory saved = memory::load_map(file);
  EXPECT_EQ(saved.place_count(), static_cast<std::size_t>(places));
  EXPECT_EQ(saved.place_count(), session.place_count());
  EXPECT_THROW(LiveSession(LiveSessionParams{}, std::nullopt).save(), UsageError);
}

}  // namespace
}  // namespace omninav::navigation
