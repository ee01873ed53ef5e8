#include "omninav/report/navigation_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/measures/plot.hpp"
#include "omninav/report/floor_plan.hpp"

namespace omninav::report {
namespace {

using measures::plot_point;
using measures::plot_points;

// An arrow as three segments: the shaft and two barbs 25° off it.
void add_arrow(measures::PointsPlot& plot, const Eigen::Vector2d& from, double direction_rad,
               double length) {
  const auto along = [](double angle) { return Eigen::Vector2d(std::cos(angle), std::sin(angle)); };
  const Eigen::Vector2d tip = from + length * along(direction_rad);
  const double barb_rad = deg_to_rad(25.0);
  plot.add_segment({plot_point(from), plot_point(tip), 0.55, 1.0});
  for (const double side : {-1.0, 1.0}) {
    const Eigen::Vector2d barb = tip - 0.35 * length * along(direction_rad + side * barb_rad);
    plot.add_segment({plot_point(tip), plot_point(barb), 0.55, 1.0});
  }
}

void add_route(measures::PointsPlot& plot, const std::vector<Eigen::Vector2d>& positions,
               const std::vector<int>& route, int start, int goal) {
  for (std::size_t i = 1; i < route.size(); ++i) {
    plot.add_segment(
        {plot_point(positions[route[i - 1]]), plot_point(positions[route[i]]), 0.0, 1.0});
  }
  std::vector<cv::Point2d> on_route;
  for (const int place : route) on_route.push_back(plot_point(positions[place]));
  plot.add_points("places", plot_points(positions));
  plot.add_points("route", on_route);
  plot.add_points("start", {plot_point(positions[start])});
  plot.add_points("goal", {plot_point(positions[goal])});
}

std::vector<Eigen::Vector2d> lattice_positions(const std::vector<navigation::PlaceNode>& places) {
  std::vector<Eigen::Vector2d> positions;
  for (const navigation::PlaceNode& place : places) positions.push_back(place.position_m);
  return positions;
}

// A polyline as segments of grey level `grey`.
void add_path(measures::PointsPlot& plot, const std::vector<cv::Point2d>& path, double grey) {
  for (std::size_t i = 1; i < path.size(); ++i) plot.add_segment({path[i - 1], path[i], grey, 1.0});
}

// The places the run matched, in order, over the lattice.
cv::Mat matched_path_panel(const navigation::NavigationResult& result,
                           const std::vector<navigation::PlaceNode>& places, int goal) {
  const std::vector<cv::Point2d> lattice = plot_points(lattice_positions(places));
  std::vector<cv::Point2d> matched;
  for (const navigation::NavigationStep& step : result.steps) {
    if (step.match) matched.push_back(lattice[step.match->place]);
  }
  measures::PointsPlot plot("The route over the lattice (places matched, in order)", "x", "y");
  add_path(plot, matched, 0.2);
  plot.add_points("places", lattice);
  plot.add_points("goal", {lattice[goal]});
  return plot.render();
}

// The rectangle round the points of `sets` (none empty: the path has its start).
sim::FloorBox extent(const std::vector<const std::vector<cv::Point2d>*>& sets) {
  sim::FloorBox box{
      std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const std::vector<cv::Point2d>* set : sets) {
    for (const cv::Point2d& point : *set) {
      box.min_x_m = std::min(box.min_x_m, point.x);
      box.min_y_m = std::min(box.min_y_m, point.y);
      box.max_x_m = std::max(box.max_x_m, point.x);
      box.max_y_m = std::max(box.max_y_m, point.y);
    }
  }
  return box;
}

// The robot's true path over the scene near it and the places' true positions.
cv::Mat true_path_panel(const navigation::NavigationResult& result, int goal,
                        const memory::VisualMemory& memory, const NavigationScene& scene) {
  std::vector<cv::Point2d> path;
  for (const navigation::NavigationStep& step : result.steps) {
    path.emplace_back(step.truth.x_m, step.truth.y_m);
  }
  std::vector<cv::Point2d> true_places;
  if (memory.all_have_truth()) {
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      true_places.push_back(plot_point(memory.place(i).truth->floor_position()));
    }
  }
  const std::vector<cv::Point2d> grid_images = plot_points(scene.grid_world_positions);
  measures::PointsPlot plot("The robot's true path", "x (m)", "y (m)");
  add_floor_boxes(plot, boxes_around(scene.obstacles, extent({&path, &true_places, &grid_images})),
                  0.3);
  add_path(plot, path, 0.1);
  if (!grid_images.empty()) plot.add_points("grid images", grid_images);
  if (!true_places.empty()) {
    plot.add_points("places (truth)", true_places);
    plot.add_points("goal place", {true_places[goal]});
  }
  plot.add_points("start", {path.front()});
  if (scene.goal_world_position) {
    plot.add_points("goal pose", {plot_point(*scene.goal_world_position)});
  }
  return plot.render();
}

}  // namespace

cv::Mat route_figure(const std::vector<navigation::PlaceNode>& places,
                     const navigation::RoutePlan& plan, int start,
                     const std::optional<std::vector<Eigen::Vector2d>>& truth_m) {
  const std::vector<int> route = plan.route_from(start);
  measures::PointsPlot lattice_plot("Route on the lattice: each place's direction to the goal",
                                    "lattice x", "lattice y");
  const double arrow = 0.45 * navigation::lattice_spacing(places);
  for (std::size_t place = 0; place < places.size(); ++place) {
    if (plan.next[place] >= 0)
      add_arrow(lattice_plot, places[place].position_m, plan.direction_rad[place], arrow);
  }
  add_route(lattice_plot, lattice_positions(places), route, start, plan.goal);
  cv::Mat picture = lattice_plot.render();
  if (truth_m) {
    measures::PointsPlot truth_plot("The route over the places' true positions", "x (m)", "y (m)");
    add_route(truth_plot, *truth_m, route, start, plan.goal);
    cv::hconcat(picture, truth_plot.render(), picture);
  }
  return picture;
}

cv::Mat navigation_path_figure(const navigation::NavigationResult& result,
                               const std::vector<navigation::PlaceNode>& places, int goal,
                               const memory::VisualMemory& memory, const NavigationScene& scene) {
  cv::Mat picture;
  cv::hconcat(matched_path_panel(result, places, goal),
              true_path_panel(result, goal, memory, scene), picture);
  return picture;
}

}  // namespace omninav::report
