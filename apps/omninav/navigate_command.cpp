// omninav navigate: the reactive loop of 001_5bb151a4e28490b4.txt §3.5 with a virtual robot
// in a rendered world, driven by the organised visual memory towards a goal image.
#include <fstream>
#include <iomanip>
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/eval/plot.hpp"
#include "omninav/eval/png.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/memory/map_file.hpp"
#include "omninav/navigation/memory_places.hpp"

namespace omninav::cli {
namespace {

struct NavigateOptions {
  std::filesystem::path map;
  std::string world = "room";
  std::string start;  // x,y,heading_deg
  std::filesystem::path goal;
  std::filesystem::path out;  // folder for steps.csv and path.png
  int max_steps = 0;
};

CameraPose parse_start(const std::string& text, double z_m) {
  const std::vector<std::string> fields = split(text, ',');
  if (fields.size() != 3) throw UsageError("--start: expected x,y,heading_deg, got '" + text + "'");
  return {parse_double(fields[0], "--start x"),
          parse_double(fields[1], "--start y"),
          z_m,
          deg_to_rad(parse_double(fields[2], "--start heading")),
          0.0,
          0.0};
}

void write_steps_csv(const navigation::NavigationResult& result,
                     const std::vector<navigation::PlaceNode>& places,
                     const std::filesystem::path& file) {
  std::ofstream csv(file);
  if (!csv) throw InputError(file.string() + ": cannot write");
  csv << "step,x_m,y_m,heading_deg,place,similarity,heading_estimate_deg,heading_error_deg,turn_"
         "deg,jump\n";
  for (const navigation::NavigationStep& step : result.steps) {
    csv << step.index << ',' << step.truth.x_m << ',' << step.truth.y_m << ','
        << rad_to_deg(step.truth.heading_rad) << ',' << step.match.place << ','
        << step.match.similarity << ',' << rad_to_deg(step.heading_estimate_rad) << ','
        << rad_to_deg(signed_difference(step.heading_estimate_rad + places[0].heading_rad,
                                        step.truth.heading_rad))
        << ',' << rad_to_deg(step.turn_rad) << ',' << (step.jump ? 1 : 0) << '\n';
  }
}

void run_navigate(const GlobalOptions& global, const NavigateOptions& options) {
  const CameraConfig camera = load_camera_config(global.config_dir);
  sim::WorldsConfig worlds = load_worlds_config(global.config_dir, camera.panorama);
  const memory::MemoryConfig memory_config = load_memory_config(global.config_dir);
  NavigationConfig navigation = load_navigation_config(global.config_dir);
  if (options.max_steps > 0) navigation.navigator.max_steps = options.max_steps;

  const memory::VisualMemory memory = memory::load_map(options.map);
  const std::vector<navigation::PlaceNode> places = navigation::places_from_memory(memory);
  // The robot's camera makes panoramas of the size the map was built from.
  worlds.render.geometry.width_px = memory.place(0).signature.width_px;
  worlds.render.geometry.height_px = memory.place(0).signature.rows;
  const memory::Localiser localiser(memory, memory_config.localisation);
  signature::SignatureExtractor extractor(memory.parameters().signature);
  const navigation::Localiser localise = navigation::memory_localiser(localiser, extractor);

  const navigation::PlaceMatch goal = localise(io::read_image(options.goal));
  if (goal.place < 0)
    throw InputError(options.goal.string() + ": the goal image matches no place of the map");
  const navigation::RoutePlan plan = navigation::plan_to_goal(
      places,
      navigation::lattice_neighbours(
          places, navigation.neighbour_spacings * navigation::lattice_spacing(places)),
      goal.place);

  const sim::World world = sim::load_world(options.world, worlds);
  const sim::Renderer renderer(world, worlds.render);
  const double camera_z = memory.place(0).truth ? memory.place(0).truth->z_m : 1.0;
  const CameraPose start = parse_start(options.start, camera_z);
  if (!world.is_free(start.x_m, start.y_m)) {
    throw UsageError("--start: (" + options.start +
                     ") is inside furniture or outside the floor of " + world.name);
  }
  sim::VirtualRobot robot(world, start, navigation.robot);
  const navigation::NavigationResult result =
      navigation::navigate(robot, renderer, places, plan, localise, navigation.navigator);

  std::filesystem::create_directories(options.out);
  write_steps_csv(result, places, options.out / "steps.csv");
  eval::PointsPlot lattice_path("The route over the lattice (places matched, in order)", "x (m)",
                                "y (m)");
  std::vector<cv::Point2d> lattice_points, matched, truth_path;
  for (const navigation::PlaceNode& place : places)
    lattice_points.emplace_back(place.position_m.x(), place.position_m.y());
  for (const navigation::NavigationStep& step : result.steps) {
    if (step.match.place >= 0) matched.push_back(lattice_points[step.match.place]);
    truth_path.emplace_back(step.truth.x_m, step.truth.y_m);
  }
  for (std::size_t i = 1; i < matched.size(); ++i)
    lattice_path.add_segment({matched[i - 1], matched[i], 0.2, 1.0});
  lattice_path.add_points("places", lattice_points);
  lattice_path.add_points("goal", {lattice_points[goal.place]});
  eval::PointsPlot room_path("The robot's true path in the room", "x (m)", "y (m)");
  for (const sim::FloorBox& box : world.obstacles) {
    const std::array<cv::Point2d, 4> corners{
        cv::Point2d(box.min_x_m, box.min_y_m), cv::Point2d(box.max_x_m, box.min_y_m),
        cv::Point2d(box.max_x_m, box.max_y_m), cv::Point2d(box.min_x_m, box.max_y_m)};
    for (int side = 0; side < 4; ++side)
      room_path.add_segment({corners[side], corners[(side + 1) % 4], 0.3, 1.0});
  }
  for (std::size_t i = 1; i < truth_path.size(); ++i)
    room_path.add_segment({truth_path[i - 1], truth_path[i], 0.1, 1.0});
  if (memory.all_have_truth()) {
    std::vector<cv::Point2d> true_places;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      true_places.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
    }
    room_path.add_points("places (truth)", true_places);
    room_path.add_points("goal place", {true_places[goal.place]});
  }
  room_path.add_points("start", {truth_path.front()});
  cv::Mat picture;
  cv::hconcat(lattice_path.render(), room_path.render(), picture);
  eval::save_png(picture, options.out / "path.png");

  std::cout << std::fixed << std::setprecision(2) << (result.reached ? "reached" : "did not reach")
            << " the goal (place " << goal.place << ") in " << result.steps.size() << " steps, "
            << result.path_length_m << " m driven, " << result.jumps
            << " localisation jumps; steps: " << (options.out / "steps.csv").string()
            << ", picture: " << (options.out / "path.png").string() << "\n";
}

}  // namespace

void add_navigate_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<NavigateOptions>();
  CLI::App* command = app.add_subcommand(
      "navigate",
      "Drive a virtual robot in a world to the place of a goal image, reactively: grab a "
      "panorama, localise it in the organised memory, read the heading against the place, turn "
      "to the place's direction towards the goal, step, repeat (001_5bb151a4e28490b4.txt §3.5). "
      "Writes steps.csv (true pose, place matched, heading estimate and error) and path.png.");
  command->add_option("map", options->map, "An organised map (.vmem)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--world", options->world, "'room' or a Wavefront .obj file")
      ->capture_default_str();
  command->add_option("--start", options->start, "The robot's true start: x_m,y_m,heading_deg")
      ->required();
  command->add_option("--goal", options->goal, "The goal image (a panorama)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "Folder for steps.csv and path.png")->required();
  command->add_option("--max-steps", options->max_steps, "Step budget (default: navigation.yaml)")
      ->check(CLI::Range(1, 100000));
  command->callback([&global, options] { run_navigate(global, *options); });
}

}  // namespace omninav::cli
