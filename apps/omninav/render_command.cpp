// omninav render: synthetic panoramas with exact ground truth, written as a BoB database.
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/evaluation/render_database.hpp"
#include "omninav/measures/contact_sheet.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/report/floor_plan.hpp"

namespace omninav::cli {
namespace {

struct RenderOptions {
  std::string world = "room";
  std::string trajectory;
  std::filesystem::path out;
  int width_px = 0;  // 0: from camera.yaml
  int height_px = 0;
  int rays_per_pixel = 0;  // 0: from worlds.yaml
  double noise_stddev = -1.0;
  double exposure_gain = -1.0;
  bool occluder = false;
  bool force = false;
};

void run_render(const GlobalOptions& global, const RenderOptions& options) {
  check_output_folder(options.out, options.force);
  const CameraConfig camera = load_camera_config(global.config_dir);
  PanoramaGeometry panorama = camera.panorama;
  if (options.width_px > 0) panorama.width_px = options.width_px;
  if (options.height_px > 0) panorama.height_px = options.height_px;
  sim::WorldsConfig worlds = load_worlds_config(global.config_dir, panorama);
  if (options.rays_per_pixel > 0) worlds.render.rays_per_pixel = options.rays_per_pixel;
  if (options.noise_stddev >= 0.0) worlds.render.effects.noise_stddev = options.noise_stddev;
  if (options.exposure_gain > 0.0) worlds.render.effects.exposure_gain = options.exposure_gain;
  if (options.occluder) worlds.render.effects.occluder.enabled = true;

  const sim::World world = sim::load_world(options.world, worlds);
  const sim::Trajectory trajectory = sim::make_trajectory(options.trajectory, world);
  const sim::Renderer renderer(world, worlds.render);
  log_info("rendering " + std::to_string(trajectory.poses.size()) + " panoramas of " +
           std::to_string(panorama.width_px) + "x" + std::to_string(panorama.height_px) + " in " +
           world.name + " along '" + options.trajectory + "'");

  const std::vector<cv::Mat> previews = evaluation::render_database(
      renderer, trajectory, options.out,
      "omninav render --world " + options.world + " --trajectory " + options.trajectory,
      options.force);
  std::vector<std::string> captions;
  const std::size_t step = std::max<std::size_t>(1, trajectory.poses.size() / 12);
  for (std::size_t i = 0; i < previews.size(); ++i) {
    const CameraPose& pose = trajectory.poses[i * step].pose;
    captions.push_back("frame " + std::to_string(i * step) + "  x " + fixed(pose.x_m, 2) +
                       " m  y " + fixed(pose.y_m, 2) + " m  heading " +
                       fixed(rad_to_deg(pose.heading_rad), 0) + " deg");
  }
  const std::filesystem::path sheet = options.out / "contact_sheet.png";
  measures::save_png(measures::contact_sheet(previews, captions, 2), sheet);

  const std::filesystem::path plan = options.out / "plan.png";
  report::floor_plan(world, trajectory).save(plan);

  summary(global) << "wrote " << trajectory.poses.size() << " panoramas (" << trajectory.length_m()
                  << " m travelled) to " << options.out.string()
                  << " as a BoB database; preview: " << sheet.string()
                  << ", top view: " << plan.string() << "\n";
}

}  // namespace

void add_render_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand(
      "render",
      "Render synthetic panoramas along a trajectory, with exact ground truth, into a BoB "
      "robotics image database (images, database_entries.csv, database_metadata.yaml), a "
      "contact_sheet.png preview and plan.png (the world from above: floor, obstacles, regions, "
      "trajectory).");
  command->add_option("--world", options->world, kWorldOptionHelp)->capture_default_str();
  command
      ->add_option(
          "--trajectory", options->trajectory,
          "kind:key=value,... where kind is one of\n"
          "  rotate (x, y, heading_deg, turns, rate_deg_s)\n"
          "  line (x0, y0, x1, y1, speed_m_s)\n"
          "  circle (cx, cy, radius_m, turns, speed_m_s)\n"
          "  walk (x, y, heading_deg, steps, step_m, turn_deg, seed)\n"
          "  wander (x, y, heading_deg, length_m or duration_s, speed_m_s, turn_rate_deg_s, "
          "wobble_deg, wobble_period_s, clearance_m, seed: an animal's route, turns of varying "
          "sharpness and a wobbling heading, in the free space)\n"
          "  saccade (x, y, heading_deg, length_m or duration_s, speed_m_s, stretch_s, "
          "saccade_min_deg, saccade_max_deg, saccade_rate_deg_s, stop_share, stop_s, "
          "spot_turn_rate_deg_s, wobble_deg, wobble_period_s, clearance_m, seed: an insect's or "
          "small robot's route, straight stretches broken by sharp turns on the spot, stops and "
          "turns in place, in the free space)\n"
          "  grid (x0, y0, nx, ny, spacing_m, heading_deg)\n"
          "  zigzag (x0, y0, x1, y1, rows, speed_m_s, turn_rate_deg_s: turns on the spot at "
          "corners)\n"
          "  tour (x0, y0, x1, y1, lane_m, clearance_m, speed_m_s, turn_rate_deg_s, x, y, seed: "
          "a coverage planner's tour of the free space, every room through its doorways, in "
          "lanes lane_m apart)\n"
          "  csv (path: columns x_m, y_m, heading_deg[, time_s, z_m, pitch_deg, roll_deg])\n"
          "and every kind takes fps, z_m, pitch_noise_deg, roll_noise_deg, noise_seed, and "
          "odometry_noise, odometry_seed: write wheel odometry beside the truth (relative "
          "noise of distance and turn, for explore --odometry).\n"
          "Example: line:x0=0.5,y0=2.5,x1=5.5,y1=2.5,speed_m_s=0.2,fps=5")
      ->required();
  command->add_option("--out", options->out, "Folder to write the database into")->required();
  command
      ->add_option("--width", options->width_px, "Panorama width in pixels (default: camera.yaml)")
      ->check(NumberRange(8, 16384));
  command
      ->add_option("--height", options->height_px,
                   "Panorama height in pixels (default: camera.yaml)")
      ->check(NumberRange(1, 4096));
  command
      ->add_option("--rays-per-pixel", options->rays_per_pixel,
                   "Anti-aliasing rays per pixel (default: worlds.yaml)")
      ->check(NumberRange(1, 16));
  command
      ->add_option("--noise", options->noise_stddev,
                   "Gaussian pixel noise, grey levels (default: worlds.yaml)")
      ->check(NumberRange(0.0, 100.0));
  command
      ->add_option("--exposure", options->exposure_gain,
                   "Exposure gain multiplying every pixel (default: worlds.yaml)")
      ->check(NumberRange(0.05, 20.0));
  command->add_flag("--occluder", options->occluder,
                    "Add the moving occluder of worlds.yaml (a person walking by)");
  command->add_flag("--force", options->force, "Replace a database already in --out");
  command->callback([&global, options] { run_render(global, *options); });
}

}  // namespace omninav::cli
