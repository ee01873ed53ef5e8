// omninav explore: a stream of panoramas into places of a visual memory (a .vmem map).
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/map_store.hpp"

namespace omninav::cli {
namespace {

struct ExploreOptions {
  std::filesystem::path input;
  std::filesystem::path out;
  std::string dissimilarity;  // empty: from memory.yaml
  int every_n_frames = -1;
  double every_m = -1.0;
  std::string heading_source;
  std::string colour;
  std::string brightness;
  int components = 0;
  bool all_frames = false;
  bool unwrap = false;
  bool force = false;  // --force: replace the map at --out
  bool odometry = false;
  io::BagOptions bag;
};

void run_explore(const GlobalOptions& global, const ExploreOptions& options) {
  memory::MemoryConfig config = load_memory_config(global.config_dir);
  memory::ExplorationParams& params = config.exploration;
  if (options.dissimilarity == "auto") {
    params.new_place_dissimilarity.reset();
  } else if (!options.dissimilarity.empty()) {
    // Checked by the option's validator: a finite number in [0, 1000].
    params.new_place_dissimilarity =
        parse_double_argument(options.dissimilarity, "--dissimilarity");
  }
  if (options.every_n_frames >= 0) params.every_n_frames = options.every_n_frames;
  if (options.every_m >= 0.0) params.every_m = options.every_m;
  params.odometry = options.odometry;
  if (!options.heading_source.empty()) {
    params.heading_source = memory::heading_policy_from_string(options.heading_source);
  }
  use_compass_config(global.config_dir, params);
  if (!options.colour.empty()) {
    config.map.signature.colour = signature::colour_mode_from_string(options.colour);
  }
  if (options.components > 0) config.map.signature.components = options.components;
  if (!options.brightness.empty()) {
    config.map.signature.normalise_brightness = options.brightness == "normalised";
  }

  // The map is checked before the work: only a map may be replaced, never the input.
  check_not_an_input(options.out, {options.input});
  memory::MapStore store(options.out);
  if (options.force) store.check_replaceable();
  std::error_code error;
  const bool extending = std::filesystem::exists(options.out, error) && !options.force;
  memory::VisualMemory memory = extending ? store.load() : memory::VisualMemory(config.map);
  if (extending) {
    const memory::MapParameters& map = memory.parameters();
    if (map.signature.colour != config.map.signature.colour ||
        map.signature.components != config.map.signature.components ||
        map.signature.normalise_brightness != config.map.signature.normalise_brightness ||
        map.weights.alpha != config.map.weights.alpha) {
      log_warning(options.out.string() + " was made with colour " +
                  signature::to_string(map.signature.colour) + ", " +
                  std::to_string(map.signature.components) + " components, weights " +
                  signature::to_string(map.weights) + ", brightness " +
                  (map.signature.normalise_brightness ? "normalised" : "raw") +
                  ": extending it with those");
    }
  }
  const std::size_t places_before = memory.place_count();

  io::PanoramaInput input = open_panoramas(options.input, global.config_dir,
                                           {.force_unwrap = options.unwrap,
                                            .topic = options.bag.topic,
                                            .pose_topic = options.bag.pose_topic});
  const bool every_frame = options.all_frames || input.is_grid();
  log_info("exploring " + input.describe() + (extending ? " into " : " into a new map ") +
           options.out.string() +
           (every_frame
                ? " (every frame a place: " +
                      std::string(input.is_grid() ? "a grid database" : "--all-frames") + ")"
                : ""));
  const memory::Run run = memory::explore_frames(memory, params,
                                                 {.name = options.input.string(),
                                                  .is_grid = input.is_grid(),
                                                  .all_frames = options.all_frames,
                                                  .frame_count = input.size(),
                                                  .grid_spacing_m = input.grid_spacing_m(),
                                                  .next = [&input] { return input.next(); }});
  // A camera's dropped frames and stop by Ctrl-C stay with the run they shaped.
  memory.add_run_note(memory.runs().size() - 1, input.notes());
  store.save(memory, {.overwrite = options.force, .after_place = {}});
  const std::size_t added = memory.place_count() - places_before;
  summary(global) << "explored " << run.frames << " frames of " << options.input.string()
                  << ": added " << added << (added == 1 ? " place" : " places") << " ("
                  << memory.place_count() << " in the map, " << memory.edge_count() << " edges, "
                  << memory.runs().size() << (memory.runs().size() == 1 ? " run" : " runs")
                  << ", headings: " << memory::to_string(run.heading_source) << ") to "
                  << options.out.string() << "\n";
}

}  // namespace

void add_explore_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<ExploreOptions>();
  CLI::App* command = app.add_subcommand(
      "explore",
      "Turn a stream of panoramas into places of a visual memory (Menegatti et al. 2004, "
      "§2-3): each place keeps its Fourier signature, heading, a thumbnail, its source and "
      "frame (and the ground truth when the input has it, for evaluation), with an edge to the "
      "previous place (relative heading and direction of motion from the phases). Exploring "
      "into an existing map extends it. Every image of a BoB grid database becomes a place; "
      "otherwise memory.yaml's exploration rules (or the options below) decide.");
  command
      ->add_option("--input", options->input,
                   "Images: a folder, a video, a BoB database, a CSV of "
                   "file,x_m,y_m,heading_deg, a ROS bag (.bag, .mcap, .db3); or a camera, "
                   "camera:0 (V4L2), explored until Ctrl-C")
      ->required();
  command->add_option("--out", options->out, "The map to write or extend, e.g. maps/room.vmem")
      ->required();
  command
      ->add_option("--dissimilarity", options->dissimilarity,
                   "New place when the mean magnitude difference per value to the last place "
                   "reaches this, grey levels, or auto: memory.yaml's new_place_plateau_share of "
                   "the plateau the stream's dissimilarity saturates at; 0 = off (default: "
                   "memory.yaml)")
      ->check(CLI::Validator(
          [range = NumberRange(0.0, 1000.0)](std::string& text) mutable {
            if (text == "auto") return std::string();
            const std::string error = range(text);
            return error.empty() ? error : error + ", nor auto";
          },
          "auto or NUMBER in [0, 1000]", "auto or a number"));
  command
      ->add_option("--every-n-frames", options->every_n_frames,
                   "Also a place every n frames; 0 = off (default: memory.yaml)")
      ->check(NumberRange(0, 1000000));
  command
      ->add_option("--every-m", options->every_m,
                   "Also a place every d metres travelled (inputs with poses); 0 = off")
      ->check(NumberRange(0.0, 1000.0));
  command->add_flag("--all-frames", options->all_frames, "Make every frame a place");
  command->add_flag("--odometry", options->odometry,
                    "Measure the distance travelled (--every-m) by the input's odometry, as a "
                    "robot without ground truth does: a BoB database's Odometry X/Y/Heading "
                    "columns (render writes them with the trajectory key odometry_noise), a "
                    "CSV's odometry_x_m, odometry_y_m, odometry_heading_deg, or a bag's "
                    "--pose-topic; the poses stay the ground truth kept for evaluation");
  command
      ->add_option("--heading-source", options->heading_source,
                   "Headings of places: auto (the visual compass along a stream; a grid "
                   "database's own headings when it records them), compass (the visual compass "
                   "over every frame, compass.yaml: Algorithm 1 along a stream, each grid image "
                   "against the most similar earlier one), truth (the input's poses) or none "
                   "(default: memory.yaml)")
      ->check(CLI::IsMember({"auto", "compass", "truth", "none"}));
  command
      ->add_option("--colour", options->colour,
                   "Signature of a new map: luminance or per_channel (default: memory.yaml)")
      ->check(CLI::IsMember({"luminance", "per_channel"}));
  command
      ->add_option("--brightness", options->brightness,
                   "Signature of a new map: raw magnitudes (the paper) or normalised per channel "
                   "to a mean of 128 (default: memory.yaml)")
      ->check(CLI::IsMember({"raw", "normalised"}));
  command
      ->add_option("--components", options->components,
                   "Fourier components per row of a new map (default: memory.yaml)")
      ->check(NumberRange(1, 4096));
  command->add_flag("--unwrap", options->unwrap,
                    "The images are raw omnidirectional images: unwrap them with camera.yaml");
  command->add_flag("--force", options->force, "Replace the map at --out instead of extending it");
  add_old_flag_name(command, "--overwrite", "--force", options->force);
  add_bag_options(command, options->bag);
  command->callback([&global, options] { run_explore(global, *options); });
}

}  // namespace omninav::cli
