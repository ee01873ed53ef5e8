#include "omninav/evaluation/robot_worlds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/memory/localisation.hpp"

namespace omninav::evaluation {

cv::Mat RenderedWorld::view(int step) {
  return renderer_.render(robot_.pose(), robot_.elapsed_s(), step);
}

double RenderedWorld::move(double turn_rad, double distance_m) {
  return robot_.move(turn_rad, distance_m);
}

GridDatabaseWorld::GridDatabaseWorld(std::vector<GridImage> images, const Pose2& start,
                                     const sim::RobotParams& params)
    : images_(std::move(images)),
      heading_rad_(start.heading_rad),
      turn_noise_deg_(params.turn_noise_deg),
      rng_(params.seed) {
  if (images_.size() < 2) {
    throw UsageError("a grid world needs at least two images, got " +
                     std::to_string(images_.size()));
  }
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < images_.size(); ++i) {
    const std::string what = "grid image " + std::to_string(i);
    require_panorama(images_[i].panorama, what);
    if (images_[i].panorama.size() != images_[0].panorama.size()) {
      throw InputError(what + ": its size differs from the first grid image's");
    }
    points.emplace_back(images_[i].pose.x_m, images_[i].pose.y_m);
  }
  spacing_m_ = memory::typical_spacing(points);
  current_ = nearest(start.x_m, start.y_m, images_.size());
}

std::size_t GridDatabaseWorld::nearest(double x_m, double y_m, std::size_t excluded) const {
  std::size_t best = excluded;
  double best_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < images_.size(); ++i) {
    const double distance = std::hypot(images_[i].pose.x_m - x_m, images_[i].pose.y_m - y_m);
    if (i != excluded && distance < best_m) {
      best_m = distance;
      best = i;
    }
  }
  return best;
}

cv::Mat GridDatabaseWorld::view(int) {
  const GridImage& image = images_[current_];
  // The stored image looks along the heading it was taken at; the robot looks along its own:
  // turning from the one to the other moves the content by that turn's columns.
  return roll_columns_fractional(
      image.panorama, shift_px_of_rotation(signed_difference(heading_rad_, image.pose.heading_rad),
                                           image.panorama.cols));
}

double GridDatabaseWorld::move(double turn_rad, double distance_m) {
  heading_rad_ = wrap_angle(heading_rad_ + turn_rad + deg_to_rad(rng_.gaussian(turn_noise_deg_)));
  const GridImage& here = images_[current_];
  const double step_m = std::max(distance_m, spacing_m_);
  const double x_m = here.pose.x_m + step_m * std::cos(heading_rad_);
  const double y_m = here.pose.y_m + step_m * std::sin(heading_rad_);
  const std::size_t next = nearest(x_m, y_m, current_);
  const GridImage& there = images_[next];
  if (std::hypot(there.pose.x_m - x_m, there.pose.y_m - y_m) > 0.75 * spacing_m_) return 0.0;
  current_ = next;
  return std::hypot(there.pose.x_m - here.pose.x_m, there.pose.y_m - here.pose.y_m);
}

CameraPose GridDatabaseWorld::truth() const {
  CameraPose pose = images_[current_].pose;
  pose.heading_rad = heading_rad_;
  return pose;
}

sim::RenderParams render_params_for_map(const memory::VisualMemory& memory,
                                        sim::RenderParams render) {
  render.geometry.width_px = memory.place(0).signature.width_px;
  render.geometry.height_px = memory.place(0).signature.rows;
  return render;
}

RenderedRobot place_robot(const sim::World& world, const sim::Renderer& renderer,
                          const memory::VisualMemory& memory, const Pose2& start,
                          const sim::RobotParams& params) {
  const double camera_z = memory.place(0).truth ? memory.place(0).truth->z_m : 1.0;
  RenderedRobot placed;
  placed.robot = std::make_unique<sim::VirtualRobot>(
      world, CameraPose{start.x_m, start.y_m, camera_z, start.heading_rad, 0.0, 0.0}, params);
  placed.world = std::make_unique<RenderedWorld>(*placed.robot, renderer);
  return placed;
}

std::vector<GridImage> read_grid_images(io::PanoramaInput& input, const std::string& name) {
  std::vector<GridImage> images;
  while (std::optional<io::Frame> frame = input.next()) {
    if (!frame->truth) {
      throw InputError(frame->source + ": no pose; a grid world needs the position of every image");
    }
    images.push_back({frame->image, *frame->truth});
  }
  if (!input.is_grid()) {
    log_info(name + " is not marked a grid database; its images are used as one");
  }
  return images;
}

}  // namespace omninav::evaluation
