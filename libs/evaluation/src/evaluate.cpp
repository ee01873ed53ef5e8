#include "omninav/evaluation/evaluate.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <opencv2/core.hpp>

#include "omninav/compass/compass_run.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/evaluation/compass_evaluation.hpp"
#include "omninav/evaluation/home_vectors.hpp"
#include "omninav/evaluation/localisation_score.hpp"
#include "omninav/evaluation/navigation_trials.hpp"
#include "omninav/evaluation/organised_map.hpp"
#include "omninav/evaluation/render_database.hpp"
#include "omninav/evaluation/robot_worlds.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/report/compass_figures.hpp"
#include "omninav/report/lattice_figures.hpp"
#include "omninav/sim/tour.hpp"
#include "omninav/sim/trajectory.hpp"

namespace omninav::evaluation {
namespace fs = std::filesystem;
namespace {

// The length scale of a world measured at its own spacing: the suite's lengths are for 0.3 m.
constexpr double kReferenceSpacingM = 0.3;

// Specs read naturally: "1.2", not "1.200".
std::string num(double value, int decimals = 3) {
  return trimmed(value, decimals);
}

// A command-line argument quoted for a POSIX shell when it needs it.
std::string shell_quoted(const std::string& arg) {
  if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                            "0123456789_-.,/:=+") == std::string::npos) {
    return arg;
  }
  std::string quoted = "'";
  for (const char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::size_t column(const std::string& key) {
  const std::vector<Measure>& all = measures();
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i].key == key) return i;
  }
  throw UsageError("evaluation: no measure " + key);
}

// One world's run: its world, renderer and the row being filled.
class WorldRun {
 public:
  WorldRun(const SuiteWorld& world, const SuiteParams& params, const ConfigFolder& config,
           const fs::path& dir)
      : suite_world_(world), params_(params), config_(config), dir_(fs::absolute(dir)) {
    row_.world = world.label;
    row_.family = world.family;
    row_.cells.assign(measures().size(), Cell::not_applicable());
    scale_ = world.spacing_m / kReferenceSpacingM;
  }

  WorldEvaluation run() {
    fs::create_directories(dir_);
    worlds_ = config_.worlds;
    worlds_.render.geometry.width_px = params_.width_px;
    worlds_.render.geometry.height_px = params_.height_px;
    config_dir_ = config_.dir;
    if (suite_world_.obj_scale_to_m > 0.0) use_obj_scale();
    world_ = sim::load_world(suite_world_.spec, worlds_);
    renderer_ = std::make_unique<sim::Renderer>(world_, worlds_.render);
    layout_ = plan_layout(world_, suite_world_.grid_nx, suite_world_.grid_ny,
                          suite_world_.spacing_m, params_.circle_radius_m * scale_, clearance_m());
    log_stage("layout: centre " + num(layout_.centre.x(), 2) + ", " + num(layout_.centre.y(), 2) +
              " m; circle radius " + num(layout_.circle_radius_m, 2) + " m; grid " +
              std::to_string(layout_.nx) + " x " + std::to_string(layout_.ny) + " at " +
              num(layout_.spacing_m) + " m from " + num(layout_.first_point.x(), 2) + ", " +
              num(layout_.first_point.y(), 2));
    stage("compass", [this] { compass_routes(); });
    grid_map();
    zigzags();
    stage("driven", [this] { driven_map(); });
    return {row_, commands_};
  }

 private:
  // Runs a stage; a failure marks every cell of its group still empty as failed.
  void stage(const std::string& group, const std::function<void()>& body) {
    try {
      body();
    } catch (const Error& error) {
      fail_group(group, error.what());
    } catch (const std::exception& error) {
      fail_group(group, std::string("unexpected failure: ") + error.what());
    }
  }
  void fail_group(const std::string& group, const std::string& why) {
    log_warning(row_.world + ": " + group + " failed: " + why);
    row_.notes.push_back(group + ": " + why);
    const std::vector<Measure>& all = measures();
    for (std::size_t c = 0; c < all.size(); ++c) {
      if (all[c].group == group && !row_.cells[c].has_value() && !done_[c]) {
        row_.cells[c] = Cell::failed();
      }
    }
  }
  void set(const std::string& key, Cell cell) {
    const std::size_t c = column(key);
    row_.cells[c] = cell;
    done_[c] = true;
  }
  void set(const std::string& key, double value) {
    set(key, std::isfinite(value) ? Cell::of(value) : Cell::failed());
  }
  void log_stage(const std::string& text) const { log_info(row_.world + ": " + text); }

  void command(const std::vector<std::string>& args) {
    std::string line = "omninav --config-dir ";
    line.append(shell_quoted(config_dir_.string()));
    for (const std::string& arg : args) {
      line.push_back(' ');
      line.append(shell_quoted(arg));
    }
    commands_.push_back(line);
  }
  void comment(const std::string& text) { commands_.push_back("# " + text); }

  // An OBJ world at another scale: a copy of the configuration folder with worlds.yaml's
  // obj.scale_to_m replaced, so that the commands read the same world.
  void use_obj_scale() {
    worlds_.obj.scale_to_m = suite_world_.obj_scale_to_m;
    config_dir_ = dir_ / "config";
    fs::create_directories(config_dir_);
    for (const fs::directory_entry& entry : fs::directory_iterator(config_.dir)) {
      if (entry.path().extension() != ".yaml") continue;
      fs::copy_file(entry.path(), config_dir_ / entry.path().filename(),
                    fs::copy_options::overwrite_existing);
    }
    YAML::Node worlds = YAML::LoadFile((config_.dir / "worlds.yaml").string());
    worlds["obj"]["scale_to_m"] = suite_world_.obj_scale_to_m;
    YAML::Emitter out;
    out << worlds;
    std::ofstream file(config_dir_ / "worlds.yaml");
    file << "# worlds.yaml of " << config_.dir.string() << " with obj.scale_to_m "
         << suite_world_.obj_scale_to_m << " (omninav evaluate)\n"
         << out.c_str() << "\n";
    if (!file) throw InputError((config_dir_ / "worlds.yaml").string() + ": cannot be written");
  }

  std::string with_height(const std::string& spec) const {
    return spec + ",z_m=" + num(suite_world_.camera_height_m);
  }

  // `omninav render`: the trajectory into a database <dir>/<name> (its poses into `made` when
  // given).
  fs::path render(const std::string& name, const std::string& spec,
                  sim::Trajectory* made = nullptr) {
    const fs::path folder = dir_ / name;
    const sim::Trajectory trajectory = sim::make_trajectory(spec, world_);
    if (made != nullptr) *made = trajectory;
    if (spec.rfind("wander:", 0) == 0) {
      // A wander that cannot leave its start only turns on the spot: not the route measured.
      const double wanted_m = params_.wander_length_m * scale_;
      if (trajectory.length_m() < 0.5 * wanted_m) {
        throw InputError("the wander travelled " + num(trajectory.length_m(), 2) + " m of " +
                         num(wanted_m, 2) + " m: it could not leave its start");
      }
    }
    log_stage("rendering " + name + " (" + std::to_string(trajectory.poses.size()) + " frames)");
    render_database(*renderer_, trajectory, folder,
                    "omninav render --world " + suite_world_.spec + " --trajectory " + spec, true);
    command({"render", "--world", suite_world_.spec, "--trajectory", spec, "--width",
             std::to_string(params_.width_px), "--height", std::to_string(params_.height_px),
             "--out", folder.string(), "--force"});
    return folder;
  }

  // `omninav compass --truth` on a database: (max |e|, mean e, end e) in degrees.
  void compass_route(const std::string& name, const std::string& spec) {
    try {
      const fs::path folder = render(name, spec);
      compass::CompassRun run(config_.compass.compass, config_.compass.width_px);
      std::vector<compass::CompassEstimate> estimates;
      std::vector<CompassTruth> truth;
      std::vector<double> truth_heading_rad;
      std::unique_ptr<io::SequenceReader> reader = io::open_sequence(folder);
      while (std::optional<io::Frame> frame = reader->next()) {
        if (!frame->truth) throw InputError(frame->source + ": no ground truth");
        estimates.push_back(
            run.push(frame->image, frame->index, frame->source, frame->truth->heading_rad));
        truth.push_back({frame->truth->heading_rad, frame->truth->floor_position(), frame->time_s});
        truth_heading_rad.push_back(frame->truth->heading_rad);
      }
      const CompassEvaluation evaluation =
          evaluate_compass(estimates, truth, run.reference_count());
      const fs::path plot = dir_ / (name + ".compass.png");
      measures::save_png(
          report::plot_compass_run(estimates, truth_heading_rad, row_.world + ", " + name), plot);
      command({"compass", "--input", folder.string(), "--truth", "--plot", plot.string()});
      set("compass_" + name + "_max_deg", evaluation.error_deg.max_abs);
      set("compass_" + name + "_mean_deg", evaluation.error_deg.mean);
      set("compass_" + name + "_end_deg", evaluation.final_error_deg);
      sigma_frames_ += evaluation.total_frames;
      within_1_sigma_ += evaluation.within_1_sigma;
      within_2_sigma_ += evaluation.within_2_sigma;
      log_stage("compass " + name + ": max |e| " + num(evaluation.error_deg.max_abs, 2) + ", end " +
                num(evaluation.final_error_deg, 2) + " deg, " +
                std::to_string(run.reference_count()) + " references in " +
                std::to_string(estimates.size()) + " frames");
    } catch (const Error& error) {
      for (const char* what : {"_max_deg", "_mean_deg", "_end_deg"}) {
        set("compass_" + name + what, Cell::failed());
      }
      row_.notes.push_back("compass " + name + ": " + error.what());
      log_warning(row_.world + ": compass " + name + " failed: " + error.what());
    }
  }

  void compass_routes() {
    comment("compass: Tables 3-4 on five routes");
    const std::string at = "x=" + num(layout_.centre.x()) + ",y=" + num(layout_.centre.y());
    const std::string fps = ",fps=" + num(params_.fps);
    const double speed = params_.speed_m_s * scale_;
    compass_route("rotate", with_height("rotate:" + at + ",turns=" + num(params_.rotate_turns) +
                                        ",rate_deg_s=" + num(params_.rotate_rate_deg_s) + fps));
    compass_route("circle", with_height("circle:cx=" + num(layout_.centre.x()) +
                                        ",cy=" + num(layout_.centre.y()) +
                                        ",radius_m=" + num(layout_.circle_radius_m) +
                                        ",speed_m_s=" + num(speed) + fps));
    const std::string wander = free_route_spec("wander", at, speed);
    compass_route("wander", with_height(wander));
    compass_route("bumpy", with_height(wander + ",pitch_noise_deg=" + num(params_.tilt_noise_deg) +
                                       ",roll_noise_deg=" + num(params_.tilt_noise_deg) +
                                       ",noise_seed=" + std::to_string(suite_world_.seed)));
    compass_route("saccade", with_height(free_route_spec("saccade", at, speed)));
    if (sigma_frames_ > 0) {
      set("compass_within_1_sigma", static_cast<double>(within_1_sigma_) / sigma_frames_);
      set("compass_within_2_sigma", static_cast<double>(within_2_sigma_) / sigma_frames_);
    }
  }

  // A route in the free space (sim's `wander` or `saccade`, `kind`) of wander_length_m from the
  // centre, kept as clear of obstacles as the centre is (the robot's radius).
  std::string free_route_spec(const std::string& kind, const std::string& at,
                              double speed_m_s) const {
    return kind + ":" + at + ",length_m=" + num(params_.wander_length_m * scale_) +
           ",speed_m_s=" + num(speed_m_s) + ",clearance_m=" + num(clearance_m()) +
           ",seed=" + std::to_string(suite_world_.seed) + ",fps=" + num(params_.fps);
  }
  double clearance_m() const { return config_.navigation.robot.radius_m * scale_; }

  std::string grid_spec() const {
    return with_height("grid:x0=" + num(layout_.first_point.x()) +
                       ",y0=" + num(layout_.first_point.y()) + ",nx=" + std::to_string(layout_.nx) +
                       ",ny=" + std::to_string(layout_.ny) +
                       ",spacing_m=" + num(layout_.spacing_m));
  }
  // The grid's last point (greatest x and y).
  Eigen::Vector2d grid_last_point() const {
    return layout_.first_point +
           Eigen::Vector2d(layout_.nx - 1, layout_.ny - 1) * layout_.spacing_m;
  }

  // `omninav explore` of a database into a new map; every_m > 0: a place every every_m metres
  // (and no other rule), travelled by the input's odometry when `odometry` is set.
  fs::path explore(const fs::path& input, const std::string& name, double every_m,
                   bool odometry = false) {
    memory::MemoryConfig memory_config = config_.memory;
    memory::ExplorationParams& params = memory_config.exploration;
    std::vector<std::string> args = {"explore", "--input", input.string()};
    if (every_m > 0.0) {
      params.every_m = every_m;
      params.new_place_dissimilarity = 0.0;
      args.insert(args.end(), {"--every-m", num(every_m), "--dissimilarity", "0"});
    }
    if (odometry) {
      params.odometry = true;
      args.emplace_back("--odometry");
    }
    memory::use_compass_config(config_.compass, params);
    const fs::path map_file = dir_ / (name + ".vmem");
    args.insert(args.end(), {"--out", map_file.string(), "--force"});
    memory::VisualMemory memory(memory_config.map);
    std::unique_ptr<io::SequenceReader> reader = io::open_sequence(input);
    const bool is_grid = reader->is_grid();
    const memory::Run run = memory::explore_frames(memory, params,
                                                   {.name = input.string(),
                                                    .is_grid = is_grid,
                                                    .all_frames = false,
                                                    .frame_count = reader->size(),
                                                    .grid_spacing_m = reader->grid_spacing_m(),
                                                    .next = [&reader] { return reader->next(); }});
    memory::MapStore(map_file).save(memory, {.overwrite = true, .after_place = {}});
    command(args);
    log_stage("explored " + name + ": " + std::to_string(run.places) + " places, headings " +
              memory::to_string(run.heading_source));
    return map_file;
  }

  // `omninav organise` (the scale: step_m, or the map's when 0), scored into lattice_<key>_*.
  void organise(const fs::path& map_file, const std::string& key, double step_m) {
    lattice::OrganiseParams params = config_.lattice;
    std::vector<std::string> args = {"organise", map_file.string()};
    if (step_m > 0.0) {
      params.step_m = step_m;
      args.insert(args.end(), {"--step-m", num(step_m)});
    }
    memory::MapStore store(map_file);
    const OrganisedMap result = organise_stored_map(store, params);
    const std::optional<LatticeScore>& evaluation = result.score;
    const fs::path picture = dir_ / (key + ".lattice.png");
    measures::save_png(report::lattice_picture(result.memory, result.organised,
                                               evaluation ? &*evaluation : nullptr),
                       picture);
    store.save(result.memory);
    args.insert(args.end(), {"--picture", picture.string()});
    command(args);
    if (!evaluation) throw InputError(map_file.string() + ": no ground truth to score against");
    // An RMSE is NaN when the lattice has no interior (or no boundary) place: not applicable.
    const auto rmse = [](double value) {
      return std::isfinite(value) ? Cell::of(value) : Cell::not_applicable();
    };
    set("lattice_" + key + "_rmse", evaluation->rmse.all);
    set("lattice_" + key + "_rmse_interior", rmse(evaluation->rmse.interior));
    set("lattice_" + key + "_rmse_boundary", rmse(evaluation->rmse.boundary));
    set("lattice_" + key + "_folds", static_cast<double>(evaluation->folded.size()));
    log_stage("lattice " + key + ": RMSE " + num(evaluation->rmse.all, 2) + " spacings, " +
              std::to_string(evaluation->folded.size()) + " of " +
              std::to_string(evaluation->neighbour_triangles) + " triangles folded; quality " +
              num(result.organised.quality.motions_off, 3) + " of motions off, " +
              std::to_string(result.organised.quality.pieces) + " piece(s), residual " +
              num(result.organised.quality.motion_residual_steps, 2) + " steps");
  }

  void grid_map() {
    comment("memory, lattice (grid) and navigation: a grid explored and organised");
    fs::path map_file;
    try {
      const fs::path grid = render("grid", grid_spec());
      try {
        home_vectors(grid);
      } catch (const Error& error) {
        set("memory_home_median_deg", Cell::failed());
        set("memory_home_p90_deg", Cell::failed());
        log_warning(row_.world + ": home vectors failed: " + error.what());
        row_.notes.push_back(std::string("home vectors: ") + error.what());
      }
      map_file = explore(grid, "grid", 0.0);
    } catch (const Error& error) {
      for (const char* key : {"rmse", "rmse_interior", "rmse_boundary", "folds"}) {
        set(std::string("lattice_grid_") + key, Cell::failed());
      }
      fail_group("memory", std::string("grid: ") + error.what());
      fail_group("navigation", std::string("grid: ") + error.what());
      return;
    }
    bool organised = false;
    stage("lattice", [&] {
      // The scale from the database's metadata (grid.separationMM), as organise reads it.
      organise(map_file, "grid", 0.0);
      organised = true;
    });
    stage("memory", [&] { localise(map_file); });
    if (organised) {
      stage("navigation", [&] { navigate(map_file, "navigation", "trials"); });
    } else {
      fail_group("navigation", "the grid map could not be organised");
    }
  }

  // Min-warping's home vectors between the grid's places 1-3 spacings apart, against the truth
  // (no command line: `localise --home-vector` gives them one query at a time).
  void home_vectors(const fs::path& grid) {
    std::vector<io::Frame> frames;
    std::unique_ptr<io::SequenceReader> reader = io::open_sequence(grid);
    while (std::optional<io::Frame> frame = reader->next()) frames.push_back(std::move(*frame));
    const compass::MinWarping warping(config_.compass.min_warping, worlds_.render.geometry);
    const HomeVectorErrors errors = grid_home_vector_errors(warping, frames, layout_.spacing_m);
    set("memory_home_median_deg", errors.median_deg());
    set("memory_home_p90_deg", errors.p90_deg());
    log_stage("home vectors: " + std::to_string(errors.errors_rad.size()) + " pairs 1-3 spacings " +
              "apart (" + std::to_string(errors.featureless) + " featureless), |error| median " +
              num(errors.median_deg(), 1) + ", p90 " + num(errors.p90_deg(), 1) + " deg");
  }

  void localise(const fs::path& map_file) {
    comment("memory: queries at random free poses and headings in the grid's rectangle");
    const std::vector<CameraPose> poses =
        random_free_poses(world_, layout_.first_point, grid_last_point(), params_.queries,
                          suite_world_.seed, suite_world_.camera_height_m);
    const fs::path poses_csv = dir_ / "queries.csv";
    {
      std::ofstream csv(poses_csv);
      write_csv_line(csv, {"x_m", "y_m", "heading_deg", "z_m"});
      for (const CameraPose& pose : poses) {
        write_csv_line(csv, {general(pose.x_m, 10), general(pose.y_m, 10),
                             general(rad_to_deg(pose.heading_rad), 10), general(pose.z_m, 10)});
      }
      if (!csv) throw InputError(poses_csv.string() + ": cannot be written");
    }
    const fs::path queries = render("queries", "csv:path=" + poses_csv.string());

    const memory::VisualMemory map = memory::load_map(map_file);
    const memory::Localiser localiser(map, config_.memory.localisation);
    signature::SignatureExtractor extractor(map.parameters().signature);
    LocalisationScore score(map);
    std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> localised;
    std::unique_ptr<io::SequenceReader> reader = io::open_sequence(queries);
    while (std::optional<io::Frame> frame = reader->next()) {
      const signature::Signature signature = extractor.compute(frame->image, frame->source);
      const memory::Localisation result = localiser.localise(signature);
      const LocalisationScore::Query q = score.add(result, *frame->truth);
      if (q.outside || result.best.empty()) continue;
      const CameraPose& best = *map.place(result.best.front().place).truth;
      localised.emplace_back(frame->truth->floor_position(), best.floor_position());
    }
    command({"localise", map_file.string(), queries.string(), "--format", "csv"});
    if (score.queries() == 0) throw InputError("no query lay within the grid: none scored");
    set("memory_within_spacing", score.within_spacing_share());
    set("memory_at_nearest", score.nearest_share());
    const std::optional<double> heading = score.median_heading_error_rad();
    set("memory_heading_error_deg", heading ? Cell::of(rad_to_deg(*heading)) : Cell::failed());
    if (const std::optional<double> share = right_region_share(world_, localised)) {
      set("memory_right_room", *share);
    }
    log_stage("localised " + std::to_string(score.queries()) + " queries (" +
              std::to_string(score.outside()) + " off the grid): " +
              num(100.0 * score.within_spacing_share(), 1) + "% within one spacing");
  }

  // `navigate --trials` on an organised map, scored into <prefix>_reached, _path_ratio,
  // _outside_m and _outside_spacings (in the suite's spacing); trials in <dir>/<folder>.
  void navigate(const fs::path& map_file, const std::string& prefix, const std::string& folder) {
    comment("navigation: seeded random start and goal pairs on " + map_file.filename().string());
    const memory::VisualMemory memory = memory::load_map(map_file);
    const memory::Localiser localiser(memory, config_.memory.localisation);
    signature::SignatureExtractor extractor(memory.parameters().signature);
    const navigation::GoalNavigationSetup setup = navigation::goal_navigation_setup(
        memory, navigation::memory_localiser(localiser, extractor), config_.navigation.route,
        config_.navigation.navigator, config_.navigation.links, config_.navigation.belief,
        {config_.compass.min_warping, worlds_.render.geometry});
    // As navigate: the robot's camera makes panoramas of the size the map was built from.
    const sim::Renderer renderer(world_, render_params_for_map(memory, worlds_.render));
    NavigationConfig navigation = config_.navigation;
    navigation.trials.count = params_.trials;
    navigation.trials.seed = suite_world_.seed;
    navigation.trials.goal_radius_m = params_.goal_radius_m;
    const fs::path out = dir_ / folder;
    command({"navigate", map_file.string(), "--world", suite_world_.spec, "--trials",
             std::to_string(params_.trials), "--seed", std::to_string(suite_world_.seed),
             "--goal-radius-m", num(params_.goal_radius_m), "--out", out.string()});
    log_stage(prefix + ": " + std::to_string(params_.trials) + " trials");
    // The spacing is the world's (the map's own median would differ between map kinds).
    const MapTrials trials = run_map_trials(memory, setup, {world_, renderer, navigation.robot},
                                            navigation.trials, layout_.spacing_m);
    const TrialSummary summary = summarise(trials.outcomes);
    std::vector<Eigen::Vector2d> mapped;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      mapped.push_back(memory.place(i).truth->floor_position());
    }
    const std::vector<Eigen::Vector2d> hull = convex_hull(std::move(mapped));
    double outside_m = 0.0;
    for (const TrialOutcome& outcome : trials.outcomes) {
      for (const navigation::NavigationStep& step : outcome.result.steps) {
        outside_m = std::max(outside_m, distance_outside(hull, step.truth.floor_position()));
      }
    }
    set(prefix + "_reached", summary.reached_share);
    if (summary.reached > 0) set(prefix + "_path_ratio", summary.mean_path_ratio);
    set(prefix + "_outside_m", outside_m);
    set(prefix + "_outside_spacings", outside_m / trials.spacing_m);
    log_stage(prefix + ": " + summary.text() + "; at most " + num(outside_m, 2) +
              " m outside the mapped area");
  }

  // The driven map: the `tour` a robot with a coverage planner drives over the grid's rectangle
  // (lanes a spacing apart, the robot's radius kept from obstacles), with odometry beside the
  // truth; explored with a place every spacing travelled by that odometry, organised, and
  // navigated as the grid map is. tour_coverage: the share of the rectangle's free floor within
  // one lane of the tour.
  void driven_map() {
    comment(
        "driven map: a tour of the grid's rectangle explored by odometry, organised, navigated");
    const Eigen::Vector2d low = layout_.first_point, high = grid_last_point();
    const std::string spec = with_height(
        "tour:x0=" + num(low.x()) + ",y0=" + num(low.y()) + ",x1=" + num(high.x()) +
        ",y1=" + num(high.y()) + ",lane_m=" + num(layout_.spacing_m) +
        ",clearance_m=" + num(clearance_m()) + ",speed_m_s=" + num(params_.speed_m_s * scale_) +
        ",turn_rate_deg_s=" + num(params_.tour_turn_rate_deg_s) + ",fps=" + num(params_.tour_fps) +
        ",seed=" + std::to_string(suite_world_.seed) + ",odometry_noise=" +
        num(params_.odometry_noise) + ",odometry_seed=" + std::to_string(suite_world_.seed));
    sim::Trajectory tour;
    const fs::path folder = render("tour", spec, &tour);
    std::vector<Eigen::Vector2d> route;
    for (const sim::TimedPose& pose : tour.poses) route.push_back(pose.pose.floor_position());
    const sim::Coverage coverage = sim::route_coverage(
        world_, route, {low.x(), low.y(), high.x(), high.y()}, layout_.spacing_m);
    set("tour_coverage", coverage.share);
    std::string rooms;
    for (const sim::Coverage::RegionShare& region : coverage.regions) {
      rooms += ", " + region.name + " " + num(region.share, 3);
    }
    log_stage("tour: " + num(tour.length_m(), 1) + " m, " + std::to_string(tour.poses.size()) +
              " frames; " + num(coverage.share, 3) + " of " + num(coverage.free_m2, 1) +
              " m2 of free floor within one lane" + rooms);
    const fs::path map_file = explore(folder, "driven", layout_.spacing_m, true);
    organise(map_file, "driven", 0.0);
    navigate(map_file, "navigation_driven", "driven_trials");
  }

  // Zig-zag streams over the grid's rectangle with rows as far apart as their places: every
  // spacing (all the grid's rows) and every two spacings (every other row).
  void zigzags() {
    comment("lattice: zig-zag streams over the grid's rectangle, places every 1 and 2 spacings");
    for (const int spacings : {1, 2}) {
      const std::string key = spacings == 1 ? "zigzag30" : "zigzag60";
      stage("lattice", [&] {
        const int rows = (layout_.ny - 1) / spacings + 1;
        const double y1 = layout_.first_point.y() + (rows - 1) * spacings * layout_.spacing_m;
        const fs::path zigzag = render(
            key, with_height("zigzag:x0=" + num(layout_.first_point.x()) + ",y0=" +
                             num(layout_.first_point.y()) + ",x1=" + num(grid_last_point().x()) +
                             ",y1=" + num(y1) + ",rows=" + std::to_string(rows) + ",speed_m_s=" +
                             num(params_.speed_m_s * scale_) + ",fps=" + num(params_.fps)));
        const fs::path map_file = explore(zigzag, key, spacings * layout_.spacing_m);
        organise(map_file, key, 0.0);
      });
    }
  }

  const SuiteWorld& suite_world_;
  const SuiteParams& params_;
  const ConfigFolder& config_;
  fs::path dir_;
  fs::path config_dir_;
  double scale_ = 1.0;
  sim::WorldsConfig worlds_;
  sim::World world_;
  std::unique_ptr<sim::Renderer> renderer_;
  WorldLayout layout_;
  Row row_;
  std::map<std::size_t, bool> done_;
  // Frames of the compass routes, and those within 1 and 2 heading standard deviations.
  int sigma_frames_ = 0;
  int within_1_sigma_ = 0;
  int within_2_sigma_ = 0;
  std::vector<std::string> commands_;
};

}  // namespace

WorldLayout plan_layout(const sim::World& world, int nx, int ny, double spacing_m,
                        double circle_radius_m, double clearance_m) {
  const sim::FloorBox& floor = world.floor;
  const double width = floor.max_x_m - floor.min_x_m, depth = floor.max_y_m - floor.min_y_m;
  const Eigen::Vector2d middle((floor.min_x_m + floor.max_x_m) / 2,
                               (floor.min_y_m + floor.max_y_m) / 2);
  WorldLayout layout;
  layout.spacing_m = spacing_m;
  // The grid: at most nx x ny, a spacing's margin from the floor's edges, centred.
  layout.nx = std::min(nx, static_cast<int>(std::floor((width - 2 * spacing_m) / spacing_m)) + 1);
  layout.ny = std::min(ny, static_cast<int>(std::floor((depth - 2 * spacing_m) / spacing_m)) + 1);
  if (layout.nx < 2 || layout.ny < 2) {
    throw InputError(world.name + ": the floor (" + num(width, 2) + " x " + num(depth, 2) +
                     " m) has no room for a grid at " + num(spacing_m) + " m");
  }
  layout.first_point = {middle.x() - (layout.nx - 1) * spacing_m / 2,
                        middle.y() - (layout.ny - 1) * spacing_m / 2};

  // Candidate centres: a lattice of free points, nearest the middle first.
  const double step = spacing_m / 2;
  std::vector<Eigen::Vector2d> candidates;
  for (double x = floor.min_x_m + step; x < floor.max_x_m; x += step) {
    for (double y = floor.min_y_m + step; y < floor.max_y_m; y += step) {
      if (world.is_free(x, y, clearance_m)) candidates.emplace_back(x, y);
    }
  }
  if (candidates.empty()) {
    throw InputError(world.name + ": no free point with " + num(clearance_m, 2) + " m clearance");
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
                     return (a - middle).norm() < (b - middle).norm();
                   });
  const auto circle_free = [&](const Eigen::Vector2d& centre, double radius) {
    for (int k = 0; k < 72; ++k) {
      const double angle = 2 * kPi * k / 72;
      if (!world.is_free(centre.x() + radius * std::cos(angle),
                         centre.y() + radius * std::sin(angle), clearance_m)) {
        return false;
      }
    }
    return true;
  };
  // The largest free circle (radius steps of 5 % of the largest) over the nearest candidates.
  layout.centre = candidates.front();
  layout.circle_radius_m = 0.0;
  const std::size_t tried = std::min<std::size_t>(candidates.size(), 400);
  for (std::size_t i = 0; i < tried && layout.circle_radius_m < circle_radius_m; ++i) {
    for (int k = 20; k >= 1; --k) {
      const double radius = circle_radius_m * k / 20.0;
      if (radius <= layout.circle_radius_m) break;
      if (circle_free(candidates[i], radius)) {
        layout.centre = candidates[i];
        layout.circle_radius_m = radius;
        break;
      }
    }
  }
  if (layout.circle_radius_m == 0.0) layout.circle_radius_m = circle_radius_m / 20.0;
  return layout;
}

std::vector<CameraPose> random_free_poses(const sim::World& world, const Eigen::Vector2d& min,
                                          const Eigen::Vector2d& max, int count, std::uint32_t seed,
                                          double z_m) {
  cv::RNG rng(seed);
  std::vector<CameraPose> poses;
  constexpr int kDrawsPerPose = 10000;
  for (int i = 0; i < count; ++i) {
    bool found = false;
    for (int draw = 0; draw < kDrawsPerPose && !found; ++draw) {
      const double x = rng.uniform(min.x(), max.x()), y = rng.uniform(min.y(), max.y());
      if (!world.is_free(x, y, 0.05)) continue;
      poses.push_back({x, y, z_m, rng.uniform(-kPi, kPi), 0.0, 0.0});
      found = true;
    }
    if (!found) throw InputError(world.name + ": no free pose in the grid's rectangle");
  }
  return poses;
}

std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  if (points.size() < 3) return points;
  // Andrew's monotone chain: the lower then the upper chain of the points sorted by x, then y,
  // dropping every point that does not turn left.
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point is the first
  return hull;
}

double distance_outside(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p) {
  if (hull.empty()) return std::numeric_limits<double>::infinity();
  const auto segment_distance = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double length2 = ab.dot(ab);
    const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
  };
  if (hull.size() == 1) return (p - hull.front()).norm();
  if (hull.size() == 2) return segment_distance(hull[0], hull[1]);
  // Inside when on the same side of every edge (either orientation).
  bool any_left = false, any_right = false;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    const Eigen::Vector2d ab = b - a, ap = p - a;
    const double cross = ab.x() * ap.y() - ab.y() * ap.x();
    any_left = any_left || cross > 1e-12;
    any_right = any_right || cross < -1e-12;
    nearest = std::min(nearest, segment_distance(a, b));
  }
  return any_left && any_right ? nearest : 0.0;
}

std::optional<double> right_region_share(
    const sim::World& world,
    const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& localised) {
  int in_regions = 0, right = 0;
  for (const auto& [truth, found] : localised) {
    const sim::Region* region = world.region_at(truth.x(), truth.y());
    if (region == nullptr) continue;
    ++in_regions;
    right += world.region_at(found.x(), found.y()) == region ? 1 : 0;
  }
  if (in_regions == 0) return std::nullopt;
  return double(right) / in_regions;
}

WorldEvaluation evaluate_world(const SuiteWorld& world, const SuiteParams& params,
                               const ConfigFolder& config, const fs::path& dir) {
  return WorldRun(world, params, config, dir).run();
}

SuiteEvaluation evaluate_suite(const Suite& suite, const ConfigFolder& config, const fs::path& out,
                               const std::function<void(const Row&, std::size_t)>& on_row) {
  SuiteEvaluation result;
  for (std::size_t i = 0; i < suite.worlds.size(); ++i) {
    const SuiteWorld& world = suite.worlds[i];
    log_info("evaluate: world " + std::to_string(i + 1) + " of " +
             std::to_string(suite.worlds.size()) + ", " + world.label + " (" + world.spec +
             ", camera " + num(world.camera_height_m) + " m)");
    WorldEvaluation evaluation;
    try {
      evaluation = evaluate_world(world, suite.params, config, out / world.label);
    } catch (const Error& error) {
      // The world itself could not be loaded or laid out: every cell fails.
      evaluation.row.world = world.label;
      evaluation.row.family = world.family;
      evaluation.row.cells.assign(measures().size(), Cell::failed());
      evaluation.row.notes.push_back(error.what());
      log_warning(world.label + ": " + error.what());
      result.failed_worlds.push_back(world.label + ": " + error.what());
    }
    result.commands.push_back("# " + world.label + ": " + world.spec + ", camera " +
                              num(world.camera_height_m) + " m");
    result.commands.insert(result.commands.end(), evaluation.commands.begin(),
                           evaluation.commands.end());
    result.rows.push_back(evaluation.row);
    if (on_row) on_row(result.rows.back(), i);
  }
  return result;
}

}  // namespace omninav::evaluation
