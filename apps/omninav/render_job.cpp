#include "render_job.hpp"

#include <opencv2/core/utility.hpp>

#include "omninav/core/progress.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::cli {

std::vector<cv::Mat> render_database(const sim::Renderer& renderer,
                                     const sim::Trajectory& trajectory,
                                     const std::filesystem::path& folder,
                                     const std::string& description, bool overwrite,
                                     std::size_t preview_frames) {
  const std::vector<sim::TimedPose>& poses = trajectory.poses;
  io::DatabaseInfo info;
  info.is_grid = trajectory.kind == "grid";
  info.camera_name = "omninav renderer";
  info.description = description;
  info.needs_unwrapping = false;
  if (poses.size() > 1 && trajectory.kind != "grid" && trajectory.kind != "csv") {
    info.frame_rate_hz = 1.0 / (poses[1].time_s - poses[0].time_s);
  }
  io::DatabaseWriter writer(folder, info, overwrite);

  const std::size_t preview_step =
      std::max<std::size_t>(1, poses.size() / std::max<std::size_t>(1, preview_frames));
  std::vector<cv::Mat> previews;
  Progress progress("rendering", poses.size());
  // Batches keep memory bounded while every core renders.
  constexpr std::size_t kBatch = 32;
  std::vector<cv::Mat> batch(kBatch);
  for (std::size_t start = 0; start < poses.size(); start += kBatch) {
    const std::size_t count = std::min(kBatch, poses.size() - start);
    cv::parallel_for_(cv::Range(0, static_cast<int>(count)), [&](const cv::Range& range) {
      for (int i = range.start; i < range.end; ++i) {
        const sim::TimedPose& pose = poses[start + i];
        batch[i] = renderer.render(pose.pose, pose.time_s, static_cast<int>(start + i));
      }
    });
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t index = start + i;
      io::Frame frame;
      frame.index = static_cast<int>(index);
      frame.time_s = poses[index].time_s;
      frame.image = batch[i];
      frame.truth = poses[index].pose;
      frame.source = "pose " + std::to_string(index);
      writer.add(frame, poses[index].grid);
      if (index % preview_step == 0 && previews.size() < preview_frames)
        previews.push_back(batch[i]);
      progress.advance();
    }
  }
  writer.finish();
  return previews;
}

void add_floor_boxes(eval::PointsPlot& plot, const std::vector<sim::FloorBox>& boxes, double grey) {
  for (const sim::FloorBox& box : boxes) {
    const std::array<cv::Point2d, 4> corners{
        cv::Point2d(box.min_x_m, box.min_y_m), cv::Point2d(box.max_x_m, box.min_y_m),
        cv::Point2d(box.max_x_m, box.max_y_m), cv::Point2d(box.min_x_m, box.max_y_m)};
    for (int side = 0; side < 4; ++side)
      plot.add_segment({corners[side], corners[(side + 1) % 4], grey, 1.0});
  }
}

eval::PointsPlot floor_plan(const sim::World& world, const sim::Trajectory& trajectory) {
  eval::PointsPlot plan("'" + world.name + "' from above: floor, obstacles, regions, trajectory",
                        "x (m)", "y (m)", cv::Size(900, 700));
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

}  // namespace omninav::cli
