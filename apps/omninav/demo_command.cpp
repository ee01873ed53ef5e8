// omninav demo: the main job on the built-in room, with no arguments. It runs the same
// subcommands a user would, in order, and prints each one's command line and report, so that
// the demo is also the tutorial: render an exploration of the room (a 30 cm grid, the
// reference images of Menegatti et al. 2004, §3.3), explore it into a map, organise the map into a
// lattice, localise query images rendered at random poses, plan a route and drive to a goal image.
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/memory/map_store.hpp"

namespace omninav::cli {
namespace {

struct DemoOptions {
  std::filesystem::path report = "report/demo";
  std::filesystem::path map = "maps/demo.vmem";
  int queries = 12;
  int trials = 10;
  int seed = 7;
};

// The exploration: a 10 × 8 grid every 30 cm over the middle of the default room (places inside
// furniture are left out), as in Menegatti et al. 2004, §3.3 (Fig. 14).
constexpr const char* kGrid = "grid:x0=1.2,y0=1.0,nx=10,ny=8,spacing_m=0.3";
constexpr const char* kGridSpacing = "0.3";  // metres, as organise --step-m takes it

class Demo {
 public:
  Demo(const GlobalOptions& global, const DemoOptions& options)
      : global_(global), options_(options) {}

  // Runs `omninav <args>` as a user would, after printing it; its standard output goes to the
  // terminal, or into `capture` when given. A failing stage stops the demo with its message.
  void step(const std::string& what, const std::vector<std::string>& args,
            const std::filesystem::path& capture = {}) {
    std::cout << "\n== " << what << "\n$ omninav";
    for (const std::string& arg : args) std::cout << ' ' << arg;
    std::cout << (capture.empty() ? "" : " > " + capture.string()) << "\n" << std::flush;
    std::vector<std::string> command = {"--config-dir", global_.config_dir.string()};
    if (global_.quiet) command.push_back("--quiet");
    command.insert(command.end(), args.begin(), args.end());
    int status = 0;
    if (capture.empty()) {
      status = run(command);
    } else {
      OutputFile file(capture);
      std::streambuf* terminal = std::cout.rdbuf(file.stream().rdbuf());
      status = run(command);
      std::cout.rdbuf(terminal);
      if (status == 0) file.commit();
    }
    if (status != 0) {
      throw Error("demo: '" + what + "' failed (exit status " + std::to_string(status) + ")");
    }
  }

  void run_all() {
    const std::filesystem::path& report = options_.report;
    std::filesystem::create_directories(report);
    std::filesystem::create_directories(options_.map.parent_path());
    const std::string exploration = (report / "exploration").string();
    const std::string map = options_.map.string();
    std::cout << "omninav demo: the whole pipeline on the built-in room; pictures and tables go "
                 "into "
              << report.string() << "\n";

    step("1. render an exploration of the room (exact poses, a BoB database)",
         {"render", "--trajectory", kGrid, "--out", exploration, "--force"});
    step("2. explore: every image a place (Fourier signature, heading, thumbnail)",
         {"explore", "--input", exploration, "--out", map, "--force"});
    step("3. organise the places into a lattice (springs and motions, Ceres)",
         {"organise", map, "--step-m", kGridSpacing, "--plot", (report / "lattice.png").string()});

    // Queries: a random walk with long steps and sharp turns over the same floor.
    const std::string queries = (report / "queries").string();
    const std::string walk =
        fmt::format("walk:x=2.55,y=2.05,steps={},step_m=0.23,turn_deg=150,seed={}",
                    options_.queries, options_.seed);
    step("4. render query images at random poses and headings",
         {"render", "--trajectory", walk, "--out", queries, "--force"});
    step("5. localise them, coarse to fine (scored against the truth; one picture per query)",
         {"localise", map, queries, "--format", "csv", "--plot",
          (report / "localisation.png").string()},
         report / "localisation.csv");

    // A route and a drive from one corner of the map to the image of the other.
    const memory::VisualMemory memory = memory::load_map(options_.map);
    const memory::Place& goal = memory.place(memory.place_count() - 1);
    const memory::Place& start = memory.place(0);
    const std::string start_pose =
        general(start.truth->x_m) + ',' + general(start.truth->y_m) + ",90";
    step("6. plan a route from the first place's image to the last's",
         {"route", map, "--from", start.source, "--to", goal.source, "--plot",
          (report / "route.png").string()});
    step(
        "7. drive there: grab a panorama, update the belief, turn towards the next place by its "
        "image, step, repeat",
        {"navigate", map, "--start", start_pose, "--goal", goal.source, "--out",
         (report / "navigation").string()});
    step("8. and over seeded random start and goal poses",
         {"navigate", map, "--trials", std::to_string(options_.trials), "--seed",
          std::to_string(options_.seed), "--out", (report / "trials").string()});
    std::cout << "\nomninav demo: done; the map is " << map << ", the pictures are in "
              << report.string() << "\n";
  }

 private:
  const GlobalOptions& global_;
  const DemoOptions& options_;
};

}  // namespace

void add_demo_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* command = app.add_subcommand(
      "demo",
      "The whole pipeline on the built-in room, no arguments needed: renders a 30 cm grid "
      "exploration, explores it into a map, organises the lattice, localises random query "
      "images, plans a route and drives to a goal image, then over random start and goal "
      "pairs. Prints every command it runs with its report; pictures and tables go into the "
      "report folder.");
  command->add_option("--out", options->report, "Folder for the demo's outputs")
      ->capture_default_str();
  add_old_option_name(command, "--report", "--out", options->report);
  command->add_option("--map", options->map, "Where to write the demo's map")
      ->capture_default_str();
  command->add_option("--queries", options->queries, "Query images to localise")
      ->capture_default_str()
      ->check(NumberRange(1, 10000));
  command->add_option("--trials", options->trials, "Random start and goal pairs to drive")
      ->capture_default_str()
      ->check(NumberRange(1, 10000));
  command->add_option("--seed", options->seed, "Seed of the queries and the trials")
      ->capture_default_str();
  command->callback([&global, options] { Demo(global, *options).run_all(); });
}

}  // namespace omninav::cli
