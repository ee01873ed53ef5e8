#pragma once
// The navigator one view at a time (navigator.hpp says what it does): show it what the robot
// sees, get the command (turn, then drive), tell it how far the robot actually drove, show it
// the next view. `navigate` (goal_navigation.hpp) is a loop over this for a NavigationWorld;
// the live session (live_session.hpp) feeds it a robot's frames and odometry.
//
//   GoalDrive drive(setup, goal, goal_homing(goal_image, setup.homing));
//   while (!drive.finished()) {
//     const DriveCommand command = drive.step(camera_view());
//     if (command.moves) drive.moved(robot_turn_then_drive(command.turn_rad, command.distance_m));
//   }
//   drive.result().reached;
//
// Every view counts as one step of navigator.max_steps; the views between two commands are not
// the navigator's business (the live session answers them with what is left of the command).

#include <memory>
#include <opencv2/core.hpp>

#include "omninav/navigation/goal_navigation.hpp"

namespace omninav::navigation {

// What the robot is to do after a view.
struct DriveCommand {
  double turn_rad = 0.0;    // turn on the spot first, counter-clockwise positive
  double distance_m = 0.0;  // then drive forwards this far
  // False when the view ended the navigation (the goal reached): nothing to do, and moved()
  // is not called.
  bool moves = false;
  // What the navigator made of the view: the place it acted on, its heading in the map, the
  // phase, whether the belief is lost. `truth` is not known here (left default).
  NavigationStep step;
};

class GoalDrive {
 public:
  // Navigation to place `goal` of `setup` (which must outlive the drive), homing on the goal
  // image with `homing` at the end (none: stops on reaching the goal's place). Throws
  // UsageError for a goal that names no place or a setup without places.
  GoalDrive(const GoalNavigationSetup& setup, int goal, GoalHoming homing = {});
  ~GoalDrive();
  GoalDrive(const GoalDrive&) = delete;
  GoalDrive& operator=(const GoalDrive&) = delete;

  // The command for the robot's current view. UsageError when finished or while a command's
  // motion has not been reported (moved).
  DriveCommand step(const cv::Mat& view);
  // The distance the robot actually drove on the last command (0 when blocked): the belief's
  // motion and the recovery from blocks read it. UsageError when no command is waiting for it,
  // InputError for a distance that is not finite.
  void moved(double driven_m);

  // The goal reached, or navigator.max_steps views spent.
  bool finished() const;
  // What the navigation did so far; `reached` once it reached the goal's place (homing or not).
  // The steps' `truth` is left default: the drive never knows where the robot really is.
  const NavigationResult& result() const;

 private:
  class Run;
  std::unique_ptr<Run> run_;
};

}  // namespace omninav::navigation
