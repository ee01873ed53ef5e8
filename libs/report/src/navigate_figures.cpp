#include "omninav/report/navigate_figures.hpp"

#include "omninav/eval/plot.hpp"
#include "omninav/report/floor_plan.hpp"

namespace omninav::report {
namespace {

cv::Point2d point(const Eigen::Vector2d& position) {
  return {position.x(), position.y()};
}

}  // namespace

cv::Mat navigation_path_figure(const navigation::NavigationResult& result,
                               const std::vector<navigation::PlaceNode>& places, int goal,
                               const memory::VisualMemory& memory, const NavigationScene& scene) {
  eval::PointsPlot lattice_path("The route over the lattice (places matched, in order)", "x", "y");
  std::vector<cv::Point2d> lattice_points, matched, truth_path;
  for (const navigation::PlaceNode& place : places)
    lattice_points.push_back(point(place.position_m));
  for (const navigation::NavigationStep& step : result.steps) {
    if (step.match) matched.push_back(lattice_points[step.match->place]);
    truth_path.emplace_back(step.truth.x_m, step.truth.y_m);
  }
  for (std::size_t i = 1; i < matched.size(); ++i)
    lattice_path.add_segment({matched[i - 1], matched[i], 0.2, 1.0});
  lattice_path.add_points("places", lattice_points);
  lattice_path.add_points("goal", {lattice_points[goal]});
  eval::PointsPlot room_path("The robot's true path", "x (m)", "y (m)");
  add_floor_boxes(room_path, scene.obstacles, 0.3);
  for (std::size_t i = 1; i < truth_path.size(); ++i)
    room_path.add_segment({truth_path[i - 1], truth_path[i], 0.1, 1.0});
  if (!scene.grid_world_positions.empty()) {
    std::vector<cv::Point2d> grid;
    for (const Eigen::Vector2d& position : scene.grid_world_positions)
      grid.push_back(point(position));
    room_path.add_points("grid images", grid);
  }
  if (memory.all_have_truth()) {
    std::vector<cv::Point2d> true_places;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      true_places.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
    }
    room_path.add_points("places (truth)", true_places);
    room_path.add_points("goal place", {true_places[goal]});
  }
  room_path.add_points("start", {truth_path.front()});
  if (scene.goal_world_position)
    room_path.add_points("goal pose", {point(*scene.goal_world_position)});
  cv::Mat picture;
  cv::hconcat(lattice_path.render(), room_path.render(), picture);
  return picture;
}

}  // namespace omninav::report
