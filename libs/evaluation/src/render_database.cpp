#include "omninav/evaluation/render_database.hpp"

#include <algorithm>
#include <opencv2/core/utility.hpp>

#include "omninav/core/progress.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::evaluation {
namespace {

// A grid sweep's geometry (BoB's `grid` metadata) from its points, which lie on an axis-aligned
// grid: along each axis, the separation from two points whose indices differ along it, the
// first point (index 0) from any point, the size from the largest index. Nothing for poses
// without grid indices.
std::optional<io::GridGeometry> grid_geometry(const std::vector<sim::TimedPose>& poses) {
  const auto first = std::find_if(poses.begin(), poses.end(),
                                  [](const sim::TimedPose& pose) { return pose.grid.has_value(); });
  if (first == poses.end()) return std::nullopt;
  io::GridGeometry grid;
  const std::array<double, 3> at_mm = {first->pose.x_m * 1000.0, first->pose.y_m * 1000.0,
                                       first->pose.z_m * 1000.0};
  const std::array<int, 3>& index = *first->grid;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (const sim::TimedPose& pose : poses) {
      if (!pose.grid || (*pose.grid)[axis] == index[axis]) continue;
      const double along_mm = 1000.0 * (axis == 0   ? pose.pose.x_m
                                        : axis == 1 ? pose.pose.y_m
                                                    : pose.pose.z_m);
      grid.separation_mm[axis] = (along_mm - at_mm[axis]) / ((*pose.grid)[axis] - index[axis]);
      break;
    }
    grid.begin_mm[axis] = at_mm[axis] - index[axis] * grid.separation_mm[axis];
    for (const sim::TimedPose& pose : poses) {
      if (pose.grid) grid.size[axis] = std::max(grid.size[axis], (*pose.grid)[axis] + 1);
    }
  }
  return grid;
}

}  // namespace

std::vector<cv::Mat> render_database(const sim::Renderer& renderer,
                                     const sim::Trajectory& trajectory,
                                     const std::filesystem::path& folder,
                                     const std::string& description, bool overwrite,
                                     std::size_t preview_frames) {
  const std::vector<sim::TimedPose>& poses = trajectory.poses;
  io::DatabaseInfo info;
  info.is_grid = trajectory.kind == sim::TrajectoryKind::kGrid;
  info.camera_name = "omninav renderer";
  info.description = description;
  info.needs_unwrapping = false;
  if (info.is_grid) info.grid = grid_geometry(poses);
  if (poses.size() > 1 && trajectory.kind != sim::TrajectoryKind::kGrid &&
      trajectory.kind != sim::TrajectoryKind::kCsv) {
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
      frame.odometry = poses[index].odometry;
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

}  // namespace omninav::evaluation
