// omninav demo: the main job on the built-in room, with no arguments. For now (the foundation
// issue) it renders a short exploration run with exact ground truth and writes its panoramas
// and a contact sheet; the later stages (explore, organise, localise, navigate) join it as
// they land.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/eval/contact_sheet.hpp"
#include "omninav/eval/png.hpp"
#include "render_job.hpp"

namespace omninav::cli {
namespace {

struct DemoOptions {
  std::filesystem::path report = "report/demo";
  int steps = 150;
  int seed = 7;
};

// A free spot near the room's centre for the walk to start from (furniture may stand there).
cv::Point2d free_start(const sim::World& world) {
  const double cx = (world.floor.min_x_m + world.floor.max_x_m) / 2.0;
  const double cy = (world.floor.min_y_m + world.floor.max_y_m) / 2.0;
  for (double radius = 0.0; radius < 5.0; radius += 0.1) {
    for (double angle = 0.0; angle < kTwoPi; angle += 0.2) {
      const double x = cx + radius * std::cos(angle), y = cy + radius * std::sin(angle);
      if (world.is_free(x, y, 0.4)) return {x, y};
    }
  }
  throw UsageError("demo: the room has no free floor to start from");
}

void run_demo(const GlobalOptions& global, const DemoOptions& options) {
  const CameraConfig camera = load_camera_config(global.config_dir);
  const sim::WorldsConfig worlds = load_worlds_config(global.config_dir, camera.panorama);
  const sim::World world = sim::load_world("room", worlds);
  const cv::Point2d start = free_start(world);
  std::ostringstream spec;
  spec << "walk:x=" << start.x << ",y=" << start.y << ",steps=" << options.steps
       << ",step_m=0.05,seed=" << options.seed << ",fps=10";
  const sim::Trajectory trajectory = sim::make_trajectory(spec.str(), world);
  const sim::Renderer renderer(world, worlds.render);

  std::filesystem::create_directories(options.report);
  const std::filesystem::path database = options.report / "exploration";
  const std::vector<cv::Mat> previews =
      render_database(renderer, trajectory, database, "omninav demo: " + spec.str(), true);
  std::vector<std::string> captions;
  const std::size_t step = std::max<std::size_t>(1, trajectory.poses.size() / 12);
  for (std::size_t i = 0; i < previews.size(); ++i) {
    const CameraPose& pose = trajectory.poses[i * step].pose;
    std::ostringstream caption;
    caption << std::fixed << std::setprecision(2) << "frame " << i * step << "  (" << pose.x_m
            << ", " << pose.y_m << ") m  heading " << std::setprecision(0)
            << rad_to_deg(pose.heading_rad) << " deg";
    captions.push_back(caption.str());
  }
  const std::filesystem::path sheet = options.report / "contact_sheet.png";
  eval::save_png(eval::contact_sheet(previews, captions, 2), sheet);

  std::cout << "omninav demo\n"
            << "  world:        built-in room " << worlds.room.size_x_m << " x "
            << worlds.room.size_y_m << " m, " << world.obstacles.size() << " furniture boxes\n"
            << "  exploration:  " << trajectory.poses.size() << " panoramas of "
            << camera.panorama.width_px << "x" << camera.panorama.height_px << ", " << std::fixed
            << std::setprecision(1) << trajectory.length_m() << " m random walk -> "
            << database.string() << "\n"
            << "  contact sheet: " << sheet.string() << "\n";
}

}  // namespace

void add_demo_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* command = app.add_subcommand(
      "demo",
      "The whole pipeline on the built-in room, no arguments needed: renders an exploration "
      "run with exact ground truth and writes its panoramas and pictures into the report "
      "folder.");
  command->add_option("--report", options->report, "Folder for the demo's outputs")
      ->capture_default_str();
  command->add_option("--steps", options->steps, "Frames of the exploration walk")
      ->capture_default_str()
      ->check(CLI::Range(2, 100000));
  command->add_option("--seed", options->seed, "Seed of the exploration walk")
      ->capture_default_str();
  command->callback([&global, options] { run_demo(global, *options); });
}

}  // namespace omninav::cli
