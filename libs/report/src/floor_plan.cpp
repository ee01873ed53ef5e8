#include "omninav/report/floor_plan.hpp"

#include <algorithm>
#include <array>

namespace omninav::report {

void add_floor_boxes(measures::PointsPlot& plot, const std::vector<sim::FloorBox>& boxes,
                     double grey) {
  for (const sim::FloorBox& box : boxes) {
    const std::array<cv::Point2d, 4> corners{
        cv::Point2d(box.min_x_m, box.min_y_m), cv::Point2d(box.max_x_m, box.min_y_m),
        cv::Point2d(box.max_x_m, box.max_y_m), cv::Point2d(box.min_x_m, box.max_y_m)};
    for (int side = 0; side < 4; ++side)
      plot.add_segment({corners[side], corners[(side + 1) % 4], grey, 1.0});
  }
}

std::vector<sim::FloorBox> boxes_around(const std::vector<sim::FloorBox>& boxes,
                                        const sim::FloorBox& frame) {
  const double margin =
      std::max(0.5, 0.25 * std::max(frame.max_x_m - frame.min_x_m, frame.max_y_m - frame.min_y_m));
  std::vector<sim::FloorBox> near;
  for (const sim::FloorBox& box : boxes) {
    if (box.max_x_m >= frame.min_x_m - margin && box.min_x_m <= frame.max_x_m + margin &&
        box.max_y_m >= frame.min_y_m - margin && box.min_y_m <= frame.max_y_m + margin) {
      near.push_back(box);
    }
  }
  return near;
}

measures::PointsPlot floor_plan(const sim::World& world, const sim::Trajectory& trajectory) {
  measures::PointsPlot plan(
      "'" + world.name + "' from above: floor, obstacles, regions, trajectory", "x (m)", "y (m)",
      cv::Size(900, 700));
  add_floor_boxes(plan, {world.floor}, 0.0);
  add_floor_boxes(plan, world.obstacles, 0.35);
  std::vector<cv::Point2d> centres;
  std::vector<std::string> names;
  for (const sim::Region& region : world.regions) {
    centres.emplace_back((region.area.min_x_m + region.area.max_x_m) / 2,
                         (region.area.min_y_m + region.area.max_y_m) / 2);
    names.push_back(region.name);
  }
  std::vector<cv::Point2d> path;
  for (const sim::TimedPose& pose : trajectory.poses)
    path.emplace_back(pose.pose.x_m, pose.pose.y_m);
  plan.add_points("trajectory", path);
  if (!centres.empty()) plan.add_points("regions", centres, names);
  return plan;
}

}  // namespace omninav::report
