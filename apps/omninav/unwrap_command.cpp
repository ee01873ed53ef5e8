// omninav unwrap: raw omnidirectional images in, panoramas (docs/design.md's column convention)
// out.

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/progress.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/omni/unwrap.hpp"

namespace omninav::cli {
namespace {

namespace fs = std::filesystem;

struct UnwrapOptions {
  fs::path input;
  fs::path out;
  double centre_x = 0.0;
  double centre_y = 0.0;
  double inner = 0.0;
  double outer = 0.0;
  std::string units = "pixels";
  int width_px = 0;
  int height_px = 0;
  double front_offset_deg = 0.0;
  bool detect = false;
  bool nearest = false;
  bool bilinear = false;
  bool flip = false;
  bool no_flip = false;
  bool force = false;
  io::BagOptions bag;
  // Which of the options above the user gave (the others keep camera.yaml's values).
  CLI::Option* centre_x_option = nullptr;
  CLI::Option* centre_y_option = nullptr;
  CLI::Option* inner_option = nullptr;
  CLI::Option* outer_option = nullptr;
  CLI::Option* width_option = nullptr;
  CLI::Option* height_option = nullptr;
  CLI::Option* front_offset_option = nullptr;
};

// Command-line values override the file's. Lengths are converted to pixels first, because the
// command line's unit (--units) need not be the file's.
omni::UnwrapParams apply_overrides(omni::UnwrapParams params, const UnwrapOptions& options,
                                   int raw_width_px) {
  params = omni::in_pixels(params, raw_width_px);
  if (options.detect) {
    params.centre_x.reset();
    params.centre_y.reset();
    params.inner_radius.reset();
    params.outer_radius.reset();
  }
  const double scale = options.units == "fraction" ? raw_width_px : 1.0;
  if (options.centre_x_option->count() > 0) params.centre_x = options.centre_x * scale;
  if (options.centre_y_option->count() > 0) params.centre_y = options.centre_y * scale;
  if (options.inner_option->count() > 0) params.inner_radius = options.inner * scale;
  if (options.outer_option->count() > 0) params.outer_radius = options.outer * scale;
  if (options.width_option->count() > 0) params.width_px = options.width_px;
  if (options.height_option->count() > 0) params.height_px = options.height_px;
  if (options.nearest) params.interpolation = omni::Interpolation::kNearest;
  if (options.bilinear) params.interpolation = omni::Interpolation::kBilinear;
  if (options.flip) params.flip = true;
  if (options.no_flip) params.flip = false;
  if (options.front_offset_option->count() > 0) {
    params.front_offset_rad = deg_to_rad(options.front_offset_deg);
  }
  return params;
}

// `<stem of the source>.png`, or `frame_00012.png` for a video; a stem seen before (a.jpg and
// a.png in one folder) gets the frame index appended rather than overwriting the first.
std::string output_name(const io::Frame& frame, bool video, std::set<std::string>& used) {
  const std::string numbered = fmt::format("frame_{:05}", frame.index);
  std::string stem = video ? numbered : fs::path(frame.source).stem().string();
  if (stem.empty()) stem = numbered;
  if (!used.insert(stem).second) {
    const std::string renamed = stem + "_" + std::to_string(frame.index);
    log_warning(frame.source + ": another input has the name '" + stem + "'; writing " + renamed +
                ".png");
    stem = renamed;
    used.insert(stem);
  }
  return stem + ".png";
}

void run_unwrap(const UnwrapOptions& options, const GlobalOptions& global) {
  const fs::path config_file = global.config_dir / "camera.yaml";
  const omni::UnwrapParams from_file = load_camera_config(global.config_dir).unwrap;
  check_output_folder(options.out, options.force, options.input);

  std::unique_ptr<io::SequenceReader> reader = io::open_sequence(options.input, options.bag);
  log_info("reading " + reader->describe());
  std::optional<io::Frame> frame = reader->next();
  if (!frame) throw InputError(options.input.string() + ": holds no images");

  const omni::UnwrapParams params = apply_overrides(from_file, options, frame->image.cols);
  std::optional<omni::Unwrapper> unwrapper;
  try {
    unwrapper.emplace(omni::make_unwrapper(params, frame->image));
  } catch (const ConfigError& error) {
    throw ConfigError(config_file.string() + " and the command line: " + error.what());
  } catch (const InputError& error) {
    throw InputError(frame->source + ": " + error.what());
  }

  std::error_code error;
  fs::create_directories(options.out, error);
  if (error) {
    throw UsageError(options.out.string() + ": cannot create the folder: " + error.message());
  }
  // Frames of a video or a bag have no file names of their own: they are numbered.
  const bool video = reader->is_video() || io::is_bag(options.input);
  std::set<std::string> used_names;
  std::size_t written = 0;
  {
    Progress progress("unwrap", reader->size());
    for (; frame; frame = reader->next()) {
      cv::Mat panorama;
      try {
        panorama = unwrapper->unwrap(frame->image);
      } catch (const InputError& unwrap_error) {
        throw InputError(frame->source + ": " + unwrap_error.what());
      }
      const fs::path file = options.out / output_name(*frame, video, used_names);
      measures::save_png(panorama, file);
      ++written;
      progress.advance();
    }
  }
  if (!global.quiet) {
    const cv::Size raw = unwrapper->raw_size();
    const cv::Size panorama = unwrapper->panorama_size();
    std::cout << "unwrapped " << written << (written == 1 ? " image" : " images") << " ("
              << raw.width << "×" << raw.height << " px raw) into " << panorama.width << "×"
              << panorama.height << " px panoramas in " << options.out.string() << "\n";
  }
}

}  // namespace

void add_unwrap_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<UnwrapOptions>();
  CLI::App* command = app.add_subcommand(
      "unwrap",
      "Unwrap raw omnidirectional images into panoramas.\n"
      "Reads camera.yaml (sections panorama: and unwrap:) from --config-dir; the options below\n"
      "override it. Each panorama has the robot's front at column 0.25*width, its left at\n"
      "column 0, and (by default) the mirror's rim at the top; camera.yaml explains each key.\n"
      "Without a centre in camera.yaml or on the command line, the mirror is detected in the\n"
      "first image. Writes <out>/<input file stem>.png, or <out>/frame_00000.png ... for a\n"
      "video, and prints a one-line summary.");
  command
      ->add_option("-i,--input", options->input,
                   "Raw images: a folder of images, a video file, a BoB image database folder, "
                   "or a CSV of file,x_m,y_m,heading_deg")
      ->type_name("PATH")
      ->required();
  command
      ->add_option("-o,--out", options->out,
                   "Folder for the panoramas (created if missing; must be empty unless --force)")
      ->type_name("FOLDER")
      ->required();

  // Lengths: in --units, overriding camera.yaml's unwrap: keys.
  const auto add_length = [&](const char* name, double& value, const char* help) {
    return command->add_option(name, value, help)
        ->type_name("LENGTH")
        ->check(NumberRange(0.0, std::numeric_limits<double>::max()));
  };
  options->centre_x_option = add_length("--centre-x", options->centre_x,
                                        "Mirror centre, x (to the right); overrides "
                                        "unwrap.centre_x");
  options->centre_y_option = add_length("--centre-y", options->centre_y,
                                        "Mirror centre, y (downwards); overrides unwrap.centre_y");
  options->inner_option = add_length("--inner", options->inner,
                                     "Inner radius (the robot and camera, left out); overrides "
                                     "unwrap.inner_radius");
  options->outer_option = add_length("--outer", options->outer,
                                     "Outer radius (the mirror's rim); overrides "
                                     "unwrap.outer_radius");
  command
      ->add_option("--units", options->units,
                   "Unit of --centre-x, --centre-y, --inner and --outer: pixels of the raw "
                   "image (x right, y down, pixel centres at whole numbers), or fraction of the "
                   "raw image's width")
      ->check(CLI::IsMember({"pixels", "fraction"}))
      ->capture_default_str();
  command->add_flag("--detect", options->detect,
                    "Ignore camera.yaml's centre and radii: detect the mirror in the first image");

  options->width_option = command
                              ->add_option("--width", options->width_px,
                                           "Panorama width, pixels (columns; 360 = one per "
                                           "degree); overrides panorama.width_px")
                              ->type_name("PX")
                              ->check(NumberRange(8, 16384));
  options->height_option = command
                               ->add_option("--height", options->height_px,
                                            "Panorama height, pixels (rows); overrides "
                                            "panorama.height_px")
                               ->type_name("PX")
                               ->check(NumberRange(1, 4096));
  CLI::Option* nearest =
      command->add_flag("--nearest", options->nearest,
                        "Take the nearest raw pixel (the papers' unsmoothed unwrapping)");
  CLI::Option* bilinear =
      command->add_flag("--bilinear", options->bilinear, "Interpolate the four nearest raw pixels");
  nearest->excludes(bilinear);
  CLI::Option* flip = command->add_flag(
      "--flip", options->flip,
      "The raw image is mirrored: the robot's left lies clockwise from its front, as a camera "
      "looking up at a mirror sees it");
  CLI::Option* no_flip =
      command->add_flag("--no-flip", options->no_flip,
                        "The raw image looks like the robot seen from above: its left lies "
                        "counter-clockwise from its front");
  flip->excludes(no_flip);
  options->front_offset_option =
      command
          ->add_option("--front-offset", options->front_offset_deg,
                       "Where the robot's front is in the raw image: degrees counter-clockwise "
                       "from the top (0 = top, 90 = left edge); overrides unwrap.front_offset_deg")
          ->type_name("DEG")
          ->check(NumberRange(-360.0, 360.0));
  command->add_flag("--force", options->force,
                    "Write into a non-empty output folder (files of the same name are replaced)");
  add_bag_options(command, options->bag);
  command->callback([options, &global] { run_unwrap(*options, global); });
}

}  // namespace omninav::cli
