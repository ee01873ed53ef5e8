#include "omninav/evaluation/render_database.hpp"

#include <opencv2/core/utility.hpp>

#include "omninav/core/progress.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::evaluation {

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
