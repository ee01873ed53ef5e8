#include "omninav/evaluation/navigation_trials.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/progress.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/evaluation/evaluate.hpp"
#include "omninav/evaluation/robot_worlds.hpp"
#include "omninav/memory/localisation.hpp"

namespace omninav::evaluation {
namespace {

// Draws tried per pose before the area is declared too small: a mapped area that is mostly
// furniture still yields poses within a few hundred draws.
constexpr int kDrawsPerPose = 10000;

double nearest_m(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& at) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& point : points) best = std::min(best, (point - at).norm());
  return best;
}

}  // namespace

void TrialParams::check() const {
  check_range("trials.min_separation_spacings", min_separation_spacings, 0.0, 1000.0);
  check_range("trials.goal_radius_m", goal_radius_m, 0.01, 100.0);
}

void load_trial_params(const ConfigReader& section, TrialParams& params) {
  section.read("min_separation_spacings", params.min_separation_spacings);
  section.read("goal_radius_m", params.goal_radius_m);
  check_loaded(section.source_name(), [&] { params.check(); });
}

std::vector<Trial> random_trials(const sim::World& world,
                                 const std::vector<Eigen::Vector2d>& mapped_m, double spacing_m,
                                 double clearance_m, double z_m, const TrialParams& params) {
  params.check();
  if (mapped_m.empty()) throw UsageError("trials: the map has no places");
  Eigen::Vector2d low = mapped_m.front(), high = mapped_m.front();
  for (const Eigen::Vector2d& point : mapped_m) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  cv::RNG rng(params.seed);
  const auto draw_position = [&](const std::function<bool(const Eigen::Vector2d&)>& accept) {
    for (int draw = 0; draw < kDrawsPerPose; ++draw) {
      const Eigen::Vector2d at(rng.uniform(low.x(), high.x()), rng.uniform(low.y(), high.y()));
      if (world.is_free(at.x(), at.y(), clearance_m) && nearest_m(mapped_m, at) <= spacing_m &&
          accept(at)) {
        return at;
      }
    }
    throw UsageError("trials: no free pose found in the mapped area of " + world.name +
                     " (clear of furniture by " + std::to_string(clearance_m) + " m, " +
                     std::to_string(params.min_separation_spacings) +
                     " spacings from the other end)");
  };
  std::vector<Trial> trials;
  for (int i = 0; i < params.count; ++i) {
    const Eigen::Vector2d start = draw_position([](const Eigen::Vector2d&) { return true; });
    const Eigen::Vector2d goal = draw_position([&](const Eigen::Vector2d& at) {
      return (at - start).norm() >= params.min_separation_spacings * spacing_m;
    });
    const double start_heading = rng.uniform(-kPi, kPi);
    const double goal_heading = rng.uniform(-kPi, kPi);
    trials.push_back({{start.x(), start.y(), z_m, start_heading, 0.0, 0.0},
                      {goal.x(), goal.y(), z_m, goal_heading, 0.0, 0.0}});
  }
  return trials;
}

std::vector<TrialOutcome> run_trials(const std::vector<Trial>& trials, const TrialScene& scene,
                                     const navigation::GoalNavigationSetup& setup,
                                     double goal_radius_m) {
  std::vector<TrialOutcome> outcomes;
  Progress progress("navigation trials", trials.size());
  for (std::size_t i = 0; i < trials.size(); ++i) {
    TrialOutcome outcome;
    outcome.trial = trials[i];
    const CameraPose& start = trials[i].start;
    const CameraPose& goal = trials[i].goal;
    outcome.straight_m = std::hypot(goal.x_m - start.x_m, goal.y_m - start.y_m);
    sim::RobotParams noise = scene.robot;
    noise.seed = scene.robot.seed + static_cast<std::uint32_t>(i);
    sim::VirtualRobot virtual_robot(scene.world, start, noise);
    RenderedWorld rendered(virtual_robot, scene.renderer);
    try {
      navigation::GoalRun run = navigation::navigate_to_image(
          rendered, scene.renderer.render(goal), "trial " + std::to_string(i) + "'s goal", setup);
      outcome.goal_place = static_cast<int>(run.goal.place);
      outcome.stopped_at_goal = run.result.reached;
      outcome.result = std::move(run.result);
    } catch (const InputError&) {
      // The goal image matched no place: the trial fails, the others go on.
    }
    const CameraPose& end = virtual_robot.pose();
    outcome.end = end;
    outcome.final_error_m = std::hypot(goal.x_m - end.x_m, goal.y_m - end.y_m);
    outcome.reached = outcome.stopped_at_goal && outcome.final_error_m <= goal_radius_m;
    outcomes.push_back(outcome);
    progress.advance();
  }
  return outcomes;
}

MapTrials run_map_trials(const memory::VisualMemory& memory,
                         const navigation::GoalNavigationSetup& setup, const TrialScene& scene,
                         const TrialParams& params, std::optional<double> spacing_m) {
  if (memory.place_count() == 0 || !memory.all_have_truth()) {
    throw UsageError("trials score against ground truth, and the map's places have none");
  }
  std::vector<Eigen::Vector2d> mapped;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    mapped.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
  }
  MapTrials result;
  result.spacing_m = spacing_m ? *spacing_m : map_spacing_m(memory);
  result.goal_radius_m = params.goal_radius_m;
  const std::vector<Trial> trials =
      random_trials(scene.world, mapped, result.spacing_m, scene.robot.radius_m,
                    memory.place(0).truth->z_m, params);
  result.outcomes = run_trials(trials, scene, setup, result.goal_radius_m);
  const std::vector<Eigen::Vector2d> hull = convex_hull(mapped);
  for (TrialOutcome& outcome : result.outcomes) {
    for (const navigation::NavigationStep& step : outcome.result.steps) {
      outcome.step_outside_m.push_back(distance_outside(hull, step.truth.floor_position()));
      outcome.outside_m = std::max(outcome.outside_m, outcome.step_outside_m.back());
    }
    outcome.end_outside_m = distance_outside(hull, outcome.end.floor_position());
    outcome.outside_m = std::max(outcome.outside_m, outcome.end_outside_m);
  }
  return result;
}

double map_spacing_m(const memory::VisualMemory& memory) {
  if (memory.grid_spacing_m()) return *memory.grid_spacing_m();
  if (memory.exploration_spacing_m()) return *memory.exploration_spacing_m();
  std::vector<Eigen::Vector2d> mapped;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    if (memory.place(i).truth) mapped.push_back(memory.place(i).truth->floor_position());
  }
  return memory::typical_spacing(mapped);
}

TrialSummary summarise(const std::vector<TrialOutcome>& outcomes) {
  TrialSummary summary;
  summary.trials = static_cast<int>(outcomes.size());
  std::vector<double> ratios;
  double steps = 0.0;
  for (const TrialOutcome& outcome : outcomes) {
    summary.lost += outcome.result.lost_events > 0 ? 1 : 0;
    summary.outside_m = std::max(summary.outside_m, outcome.outside_m);
    if (!outcome.reached) continue;
    ++summary.reached;
    ratios.push_back(outcome.result.path_length_m / outcome.straight_m);
    steps += static_cast<double>(outcome.result.steps.size());
  }
  if (summary.trials > 0) summary.reached_share = double(summary.reached) / summary.trials;
  if (!ratios.empty()) {
    for (const double ratio : ratios) summary.mean_path_ratio += ratio / ratios.size();
    summary.median_path_ratio = median(ratios);
    summary.mean_steps = steps / summary.reached;
  }
  return summary;
}

std::string TrialSummary::text() const {
  return "reached " + std::to_string(reached) + " of " + std::to_string(trials) + " goals (" +
         fixed(100.0 * reached_share, 1) + "%); path / straight line over those reached: mean " +
         fixed(mean_path_ratio, 2) + ", median " + fixed(median_path_ratio, 2) + "; mean " +
         fixed(mean_steps, 1) + " steps; the belief spread (lost) in " + std::to_string(lost) +
         " trials; at most " + fixed(outside_m, 2) + " m outside the mapped area";
}

}  // namespace omninav::evaluation
