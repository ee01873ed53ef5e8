// omninav navigate: the reactive loop of Menegatti et al. 2004, §3.5, driven by the organised
// visual memory towards a goal image: a virtual robot in a rendered world, or a robot on a grid
// of stored images (a BoB grid database); and the evaluation over seeded random start and goal
// pairs (--trials).
#include <iostream>
#include <memory>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/evaluation/navigation_trials.hpp"
#include "omninav/evaluation/robot_worlds.hpp"
#include "omninav/evaluation/trials_output.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/report/navigation_figures.hpp"
#include "omninav/report/navigation_output.hpp"

namespace omninav::cli {
namespace {

struct NavigateOptions {
  std::filesystem::path map;
  std::string world = "room";
  std::filesystem::path database;  // a grid of stored images instead of a rendered world
  std::string start;               // x,y,heading_deg
  std::filesystem::path goal;
  std::filesystem::path out;  // folder for steps.csv and path.png, or trials.csv
  int max_steps = 0;
  int trials = 0;
  int seed = 1;
  double goal_radius_m = 0.0;  // 0: navigation.yaml's trials.goal_radius_m
};

Pose2 parse_start(const std::string& text) {
  const std::vector<std::string> fields = split(text, ',');
  if (fields.size() != 3) throw UsageError("--start: expected x,y,heading_deg, got '" + text + "'");
  return {parse_double_argument(fields[0], "--start x"),
          parse_double_argument(fields[1], "--start y"),
          deg_to_rad(parse_double_argument(fields[2], "--start heading"))};
}

// Trials that drive more than this many times the straight line get a picture of their path.
constexpr double kDetourRatio = 2.0;

// A CSV written whole or not at all: its rows by `write`, then commit().
template <typename Write>
void write_csv_file(const std::filesystem::path& file, Write write) {
  OutputFile csv(file);
  write(csv.stream());
  csv.commit();
}

void evaluate_trials(const GlobalOptions& global, const NavigateOptions& options,
                     const memory::VisualMemory& memory,
                     const navigation::GoalNavigationSetup& setup, NavigationConfig navigation,
                     const sim::World& world, const sim::Renderer& renderer) {
  if (!memory.all_have_truth()) {
    throw UsageError(options.map.string() +
                     ": --trials scores against ground truth, and the map's places have none");
  }
  navigation.trials.count = options.trials;
  navigation.trials.seed = static_cast<std::uint32_t>(options.seed);
  if (options.goal_radius_m > 0.0) navigation.trials.goal_radius_m = options.goal_radius_m;
  const evaluation::MapTrials map_trials = evaluation::run_map_trials(
      memory, setup, {world, renderer, navigation.robot}, navigation.trials);
  const std::vector<evaluation::TrialOutcome>& outcomes = map_trials.outcomes;
  const double lattice_to_world_rad = memory.place(0).heading_rad.value_or(0.0);
  write_csv_file(options.out / "trials.csv",
                 [&](std::ostream& csv) { evaluation::write_trials_csv(csv, outcomes); });
  write_csv_file(options.out / "steps.csv", [&](std::ostream& csv) {
    evaluation::write_trial_steps_csv(csv, outcomes, lattice_to_world_rad);
  });
  // The trials worth a look: those that missed their goal and those that drove the long way.
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const evaluation::TrialOutcome& o = outcomes[i];
    if (o.result.steps.empty()) continue;  // the goal image matched no place: nothing driven
    if (!o.reached || o.result.path_length_m > kDetourRatio * o.straight_m) {
      const report::NavigationScene scene{
          world.obstacles, {}, Eigen::Vector2d(o.trial.goal.x_m, o.trial.goal.y_m)};
      measures::save_png(
          report::navigation_path_figure(o.result, setup.places, o.goal_place, memory, scene),
          options.out / ("trial_" + std::to_string(i) + ".png"));
    }
  }
  summary(global) << evaluation::summarise(outcomes).text() << " (seed " << options.seed
                  << "; reached: stopped within " << fixed(map_trials.goal_radius_m, 2)
                  << " m of the goal); trials: " << (options.out / "trials.csv").string() << "\n";
}

void run_navigate(const GlobalOptions& global, const NavigateOptions& options) {
  if (options.trials > 0 && !options.database.empty())
    throw UsageError("--trials renders its goals: it needs a --world, not a --database");
  if (options.trials == 0 && (options.start.empty() || options.goal.empty()))
    throw UsageError("navigate needs --start and --goal (or --trials N for an evaluation)");
  const CameraConfig camera = load_camera_config(global.config_dir);
  const sim::WorldsConfig worlds = load_worlds_config(global.config_dir, camera.panorama);
  const memory::MemoryConfig memory_config = load_memory_config(global.config_dir);
  NavigationConfig navigation = load_navigation_config(global.config_dir);
  if (options.max_steps > 0) navigation.navigator.max_steps = options.max_steps;
  // The output folder before the work, not after it.
  std::error_code error;
  std::filesystem::create_directories(options.out, error);
  const std::vector<std::filesystem::path> inputs = {options.map, options.database, options.goal,
                                                     options.world};
  check_output_path(options.out / (options.trials > 0 ? "trials.csv" : "steps.csv"), inputs);
  for (const char* name : {"steps.csv", "path.png"}) check_not_an_input(options.out / name, inputs);

  const memory::VisualMemory memory = memory::load_map(options.map);
  const memory::Localiser localiser(memory, memory_config.localisation);
  signature::SignatureExtractor extractor(memory.parameters().signature);
  const navigation::GoalNavigationSetup setup = navigation::goal_navigation_setup(
      memory, navigation::memory_localiser(localiser, extractor), navigation.route,
      navigation.navigator, navigation.links, navigation.belief,
      {load_compass_config(global.config_dir).min_warping, camera.panorama});

  // The robot in a rendered world, or on a grid of stored images.
  std::optional<sim::World> world;
  std::unique_ptr<sim::Renderer> renderer;
  evaluation::RenderedRobot rendered;
  std::unique_ptr<navigation::NavigationWorld> grid_world;
  navigation::NavigationWorld* body = nullptr;
  std::vector<Eigen::Vector2d> grid;  // the grid images' true positions
  if (options.database.empty()) {
    world = sim::load_world(options.world, worlds);
    renderer = std::make_unique<sim::Renderer>(
        *world, evaluation::render_params_for_map(memory, worlds.render));
    if (options.trials > 0) {
      evaluate_trials(global, options, memory, setup, navigation, *world, *renderer);
      return;
    }
    const Pose2 start = parse_start(options.start);
    if (!world->is_free(start.x_m, start.y_m)) {
      throw UsageError("--start: (" + options.start +
                       ") is inside furniture or outside the floor of " + world->name);
    }
    rendered = evaluation::place_robot(*world, *renderer, memory, start, navigation.robot);
    body = rendered.world.get();
  } else {
    io::PanoramaInput panoramas = open_panoramas(options.database, global.config_dir);
    std::vector<evaluation::GridImage> images =
        evaluation::read_grid_images(panoramas, options.database.string());
    for (const evaluation::GridImage& image : images)
      grid.emplace_back(image.pose.x_m, image.pose.y_m);
    grid_world = std::make_unique<evaluation::GridDatabaseWorld>(
        std::move(images), parse_start(options.start), navigation.robot);
    body = grid_world.get();
  }

  const navigation::GoalRun run = navigation::navigate_to_image(*body, io::read_image(options.goal),
                                                                options.goal.string(), setup);
  const navigation::NavigationResult& result = run.result;

  write_csv_file(options.out / "steps.csv", [&](std::ostream& csv) {
    report::write_navigation_steps_header(csv, false);
    report::write_navigation_steps(csv, result, memory.place(0).heading_rad.value_or(0.0));
  });
  const report::NavigationScene scene{world ? world->obstacles : std::vector<sim::FloorBox>{}, grid,
                                      std::nullopt};
  measures::save_png(
      report::navigation_path_figure(result, setup.places, run.goal.place, memory, scene),
      options.out / "path.png");
  summary(global) << (result.reached ? "reached" : "did not reach") << " the goal (place "
                  << run.goal.place << ") in " << result.steps.size() << " steps, "
                  << fixed(result.path_length_m, 2) << " m driven, " << result.jumps
                  << " jumps of the belief's place, its belief spread (lost) " << result.lost_events
                  << " times"
                  << "; steps: " << (options.out / "steps.csv").string()
                  << ", picture: " << (options.out / "path.png").string() << "\n";
}

}  // namespace

void add_navigate_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<NavigateOptions>();
  CLI::App* command = app.add_subcommand(
      "navigate",
      "Drive a robot to the place of a goal image: grab a panorama, update the belief over "
      "the map's places with it, read the heading against the belief's place, turn to that "
      "place's direction towards the goal over the map's confirmed links, step, repeat "
      "(Menegatti et al. 2004, §3.5; docs/navigation.md). The robot is a virtual "
      "one in a rendered --world, or stands on the images of a grid --database (a step goes to "
      "the nearest grid image, a turn rolls the panorama). Writes steps.csv (true pose, place "
      "matched, heading estimate and error) and path.png. With --trials N: N seeded random "
      "start and goal pairs in the mapped area, clear of furniture, each goal image rendered at "
      "its pose; prints the share reached and the path over the straight line, writes "
      "trials.csv, steps.csv (every step of every trial) and trial_<i>.png for each trial that "
      "missed its goal or drove more than twice the straight line (needs a map with ground "
      "truth).");
  command->add_option("map", options->map, "An organised map (.vmem)")->required();
  CLI::Option* world =
      command->add_option("--world", options->world, kWorldOptionHelp)->capture_default_str();
  command
      ->add_option("--database", options->database,
                   "A grid of stored panoramas with poses (a BoB grid database) to navigate in, "
                   "instead of a rendered world")
      ->excludes(world);
  CLI::Option* start = command->add_option(
      "--start", options->start,
      "The robot's true start: x_m,y_m,heading_deg (on a grid: the nearest grid image)");
  CLI::Option* goal = command->add_option("--goal", options->goal, "The goal image (a panorama)");
  command
      ->add_option(
          "--out", options->out,
          "Folder for steps.csv and path.png (with --trials: trials.csv, steps.csv, trial_<i>.png)")
      ->required();
  command->add_option("--max-steps", options->max_steps, "Step budget (default: navigation.yaml)")
      ->check(NumberRange(1, 100000));
  command
      ->add_option("--trials", options->trials,
                   "Evaluate over this many seeded random start and goal pairs instead")
      ->check(NumberRange(1, 100000))
      ->excludes(start)
      ->excludes(goal);
  command
      ->add_option("--seed", options->seed,
                   "Seed of the --trials start and goal poses (motion noise: navigation.yaml "
                   "robot.seed + the trial's index)")
      ->check(NumberRange(0, 1'000'000'000))
      ->capture_default_str();
  command
      ->add_option("--goal-radius-m", options->goal_radius_m,
                   "--trials: a goal counts as reached when the robot stops within this distance "
                   "of its position, metres (default: navigation.yaml trials.goal_radius_m)")
      ->check(NumberRange(0.01, 100.0));
  command->callback([&global, options] { run_navigate(global, *options); });
}

}  // namespace omninav::cli
