#pragma once
// The worlds the navigator can drive a robot in (navigation/navigator.hpp, NavigationWorld):
//   - RenderedWorld: a virtual robot in a world drawn by libs/sim's renderer, moving freely
//     (with motion noise) and stopped by walls and furniture;
//   - GridDatabaseWorld: a grid of stored panoramas (a BoB grid database): the robot stands on
//     one grid image at a time, a step takes it to the grid image nearest to where the step
//     would end, and turning on the spot is simulated by rolling the panorama (core/panorama.hpp:
//     a counter-clockwise turn by δ moves the content by δ·W/(2π) columns).

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/io/panorama_input.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/virtual_robot.hpp"

namespace omninav::evaluation {

class RenderedWorld : public navigation::NavigationWorld {
 public:
  // `robot` and `renderer` must outlive this world.
  RenderedWorld(sim::VirtualRobot& robot, const sim::Renderer& renderer)
      : robot_(robot), renderer_(renderer) {}

  cv::Mat view(int step) override;
  double move(double turn_rad, double distance_m) override;
  CameraPose truth() const override { return robot_.pose(); }

 private:
  sim::VirtualRobot& robot_;
  const sim::Renderer& renderer_;
};

// One stored image of a grid, with the pose it was taken at.
struct GridImage {
  cv::Mat panorama;
  CameraPose pose;
};

class GridDatabaseWorld : public navigation::NavigationWorld {
 public:
  // The robot starts on the grid image nearest to `start`, with start's heading. Turns get
  // params.turn_noise_deg of seeded noise, as the virtual robot's; distances are the grid's.
  // Throws UsageError for fewer than two images, InputError for an image that is not a
  // panorama or differs in size from the first.
  GridDatabaseWorld(std::vector<GridImage> images, const Pose2& start,
                    const sim::RobotParams& params);

  cv::Mat view(int step) override;
  // A step shorter than the grid spacing still goes to the next grid image (the grid holds
  // no image in between): the robot goes to the image nearest to the point `distance_m` (at
  // least one spacing) ahead, unless that point lies farther than 3/4 of a spacing from every
  // image other than the current one (off the grid, or in a hole of it such as furniture):
  // then it is blocked and stays, as at a wall.
  double move(double turn_rad, double distance_m) override;
  CameraPose truth() const override;

  double spacing_m() const { return spacing_m_; }
  std::size_t current() const { return current_; }

 private:
  std::size_t nearest(double x_m, double y_m, std::size_t excluded) const;

  std::vector<GridImage> images_;
  double spacing_m_ = 1.0;
  std::size_t current_ = 0;
  double heading_rad_ = 0.0;
  double turn_noise_deg_ = 0.0;
  cv::RNG rng_;
};

// The render parameters of a robot's camera on `memory`'s map: `render` with the panorama size
// the map was built from (its first place's signature), so that its views compare with the
// places. `memory` must hold a place.
sim::RenderParams render_params_for_map(const memory::VisualMemory& memory,
                                        sim::RenderParams render);

// A virtual robot in a rendered world, and the world the navigator drives it in.
struct RenderedRobot {
  std::unique_ptr<sim::VirtualRobot> robot;
  std::unique_ptr<RenderedWorld> world;
};

// The robot of `omninav navigate --world` at `start` in `world` (drawn by `renderer`, both of
// which must outlive it), its camera at the height of `memory`'s first place (1 m when the place
// has no ground truth).
RenderedRobot place_robot(const sim::World& world, const sim::Renderer& renderer,
                          const memory::VisualMemory& memory, const Pose2& start,
                          const sim::RobotParams& params);

// The images of a grid database (or any input whose images have poses), as panoramas, for a
// GridDatabaseWorld; `name` names the input in messages. Throws InputError for an image
// without a pose; logs when the input is not marked a grid database.
std::vector<GridImage> read_grid_images(io::PanoramaInput& input, const std::string& name);

}  // namespace omninav::evaluation
