#pragma once
// Navigation trials over seeded random start and goal poses: the evaluation of docs/design.md
// ("share of start/goal pairs reached, and path length"), whose target is at least 95% of 100
// random pairs in the built-in room reached with a mean path at most 1.5 times the straight
// line. The trials read ground truth (the goal's pose, the robot's true path) only to score;
// the navigator itself never sees it.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/virtual_robot.hpp"
#include "omninav/sim/world.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::evaluation {

struct TrialParams {
  int count = 100;         // start and goal pairs
  std::uint32_t seed = 1;  // draws the start and goal poses
  // Start and goal at least this many place spacings apart (a shorter straight line makes
  // the path ratio meaningless).
  double min_separation_spacings = 3.0;
  // A trial reaches its goal when the navigator stops there and the robot truly stands within
  // this distance of the goal's position, metres: the same on every map, however dense (a
  // map's own spacing would make the same robot score differently on another map of the
  // room). 0.3 m: one spacing of the suites' grids.
  double goal_radius_m = 0.3;

  // The ranges of navigation.yaml's trials section (min_separation_spacings, goal_radius_m;
  // count and seed are checked on the command line). Throws UsageError naming the key
  // (core/param_check.hpp); the loader and random_trials call it.
  void check() const;
};

// Reads the `trials:` section of navigation.yaml (count and seed are command-line values).
void load_trial_params(const ConfigReader& section, TrialParams& params);

struct Trial {
  CameraPose start;
  CameraPose goal;
};

// `params.count` seeded random pairs of poses in the mapped area: uniform over the bounding
// box of `mapped_m` (the places' true positions), kept where `world` is free with
// `clearance_m` and within one `spacing_m` of a place (no holes of the map, nothing outside
// it), start and goal at least min_separation_spacings · spacing_m apart, headings uniform,
// at height z_m. Throws UsageError when the area leaves no room for such pairs.
std::vector<Trial> random_trials(const sim::World& world,
                                 const std::vector<Eigen::Vector2d>& mapped_m, double spacing_m,
                                 double clearance_m, double z_m, const TrialParams& params);

// Where the trials run: a rendered world, its renderer (which renders the goal images and the
// robot's views) and the robot's motion (the noise of trial i seeded by robot.seed + i). The
// world and the renderer must outlive the scene.
struct TrialScene {
  const sim::World& world;
  const sim::Renderer& renderer;
  sim::RobotParams robot;
};

struct TrialOutcome {
  Trial trial;
  int goal_place = -1;                  // -1: the goal image matched no place (the trial fails)
  bool stopped_at_goal = false;         // the navigator recognised the goal place and stopped
  bool reached = false;                 // ... and truly stands within the goal radius
  double final_error_m = 0.0;           // from where the robot stopped to the goal pose (truth)
  double straight_m = 0.0;              // from start to goal, straight
  CameraPose end;                       // where the robot stopped (truth)
  navigation::NavigationResult result;  // the run, step by step (empty when the goal matched
                                        // no place)
  // How far the robot stood outside the mapped area (the convex hull of the places' true
  // positions; evaluate.hpp's distance_outside) at each step, at most over the run (the end
  // included) and where it stopped; set by run_map_trials, which knows the mapped area.
  std::vector<double> step_outside_m;
  double outside_m = 0.0;
  double end_outside_m = 0.0;
};

// Runs every trial: the goal image rendered at the goal pose, a fresh virtual robot at the
// start, navigate_to_image; a trial is reached within `goal_radius_m` of its goal pose.
std::vector<TrialOutcome> run_trials(const std::vector<Trial>& trials, const TrialScene& scene,
                                     const navigation::GoalNavigationSetup& setup,
                                     double goal_radius_m);

// The evaluation of `navigate --trials` (and of `omninav evaluate`) on a map whose places have
// ground truth: random_trials over the places' true positions (height: the first place's
// camera height) with `params`' count and seed, the robot's radius as clearance, then
// run_trials with the goal radius of `params` in metres. The spacing (trials near a place,
// start and goal apart, outside the map in spacings) is `spacing_m` when given, else the map's
// own (map_spacing_m). Throws UsageError when the places lack ground truth.
struct MapTrials {
  double spacing_m = 0.0;
  double goal_radius_m = 0.0;
  std::vector<TrialOutcome> outcomes;
};
MapTrials run_map_trials(const memory::VisualMemory& memory,
                         const navigation::GoalNavigationSetup& setup, const TrialScene& scene,
                         const TrialParams& params, std::optional<double> spacing_m = {});

// The spacing a map was made at: a grid database's (VisualMemory::grid_spacing_m), else the
// exploration's every_m (exploration_spacing_m), else the places' typical spacing (the median
// distance from a place's true position to its nearest other).
double map_spacing_m(const memory::VisualMemory& memory);

struct TrialSummary {
  int trials = 0;
  int reached = 0;
  double reached_share = 0.0;
  double mean_path_ratio = 0.0;    // mean over reached trials of path / straight line
  double median_path_ratio = 0.0;  // the same, median
  double mean_steps = 0.0;         // over reached trials
  int lost = 0;                    // trials whose robot found itself lost at least once
  double outside_m = 0.0;          // the farthest any robot stood outside the mapped area

  // "reached 96 of 100 goals (96.0%); path / straight line: mean 1.31, median 1.22; ...; the
  // belief spread (lost) in 3 trials; at most 0.12 m outside the mapped area".
  std::string text() const;
};

TrialSummary summarise(const std::vector<TrialOutcome>& outcomes);

}  // namespace omninav::evaluation
