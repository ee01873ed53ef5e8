#include "omninav/report/navigation_figures.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/eval/plot.hpp"

namespace omninav::report {
namespace {

cv::Point2d point(const Eigen::Vector2d& position) {
  return {position.x(), position.y()};
}

// An arrow as three segments: the shaft and two barbs 25° off it.
void add_arrow(eval::PointsPlot& plot, const Eigen::Vector2d& from, double direction_rad,
               double length) {
  const auto along = [](double angle) { return Eigen::Vector2d(std::cos(angle), std::sin(angle)); };
  const Eigen::Vector2d tip = from + length * along(direction_rad);
  const double barb_rad = deg_to_rad(25.0);
  plot.add_segment({point(from), point(tip), 0.55, 1.0});
  for (const double side : {-1.0, 1.0}) {
    const Eigen::Vector2d barb = tip - 0.35 * length * along(direction_rad + side * barb_rad);
    plot.add_segment({point(tip), point(barb), 0.55, 1.0});
  }
}

void add_route(eval::PointsPlot& plot, const std::vector<Eigen::Vector2d>& positions,
               const std::vector<int>& route, int start, int goal) {
  for (std::size_t i = 1; i < route.size(); ++i)
    plot.add_segment({point(positions[route[i - 1]]), point(positions[route[i]]), 0.0, 1.0});
  std::vector<cv::Point2d> all, on_route;
  for (const Eigen::Vector2d& position : positions) all.push_back(point(position));
  for (const int place : route) on_route.push_back(point(positions[place]));
  plot.add_points("places", all);
  plot.add_points("route", on_route);
  plot.add_points("start", {point(positions[start])});
  plot.add_points("goal", {point(positions[goal])});
}

}  // namespace

cv::Mat route_figure(const std::vector<navigation::PlaceNode>& places,
                     const navigation::RoutePlan& plan, int start,
                     const std::optional<std::vector<Eigen::Vector2d>>& truth_m) {
  const std::vector<int> route = plan.route_from(start);
  std::vector<Eigen::Vector2d> lattice;
  for (const navigation::PlaceNode& place : places) lattice.push_back(place.position_m);
  eval::PointsPlot lattice_plot("Route on the lattice: each place's direction to the goal",
                                "lattice x", "lattice y");
  const double arrow = 0.45 * navigation::lattice_spacing(places);
  for (std::size_t place = 0; place < places.size(); ++place) {
    if (plan.next[place] >= 0)
      add_arrow(lattice_plot, places[place].position_m, plan.direction_rad[place], arrow);
  }
  add_route(lattice_plot, lattice, route, start, plan.goal);
  cv::Mat picture = lattice_plot.render();
  if (truth_m) {
    eval::PointsPlot truth_plot("The route over the places' true positions", "x (m)", "y (m)");
    add_route(truth_plot, *truth_m, route, start, plan.goal);
    cv::hconcat(picture, truth_plot.render(), picture);
  }
  return picture;
}

}  // namespace omninav::report
