#pragma once
// Pictures of navigation: a route plan, like Fig. 18 of Menegatti et al. 2004 (`omninav
// route`), and one navigation run (path.png and trial_<i>.png of `omninav navigate`).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::report {

// The lattice panel: every place, an arrow at each place that reaches the goal along its
// direction (lattice frame), the route from `start` drawn over them, start and goal marked.
// With `truth_m` (one true position per place) a second panel beside it draws the route over
// the true positions. BGR, CV_8UC3.
cv::Mat route_figure(const std::vector<navigation::PlaceNode>& places,
                     const navigation::RoutePlan& plan, int start,
                     const std::optional<std::vector<Eigen::Vector2d>>& truth_m);

// Where the run took place, beside the map: drawn under the robot's true path.
struct NavigationScene {
  std::vector<sim::FloorBox> obstacles;                // a rendered world's furniture
  std::vector<Eigen::Vector2d> grid_world_positions;   // a grid database's images
  std::optional<Eigen::Vector2d> goal_world_position;  // the goal pose, when known (trials)
};

// Two panels: the places matched, in order, over the lattice (with the goal place `goal`);
// and the robot's true path over the scene, with the places' true positions when the map has
// them. BGR, CV_8UC3.
cv::Mat navigation_path_figure(const navigation::NavigationResult& result,
                               const std::vector<navigation::PlaceNode>& places, int goal,
                               const memory::VisualMemory& memory, const NavigationScene& scene);

}  // namespace omninav::report
