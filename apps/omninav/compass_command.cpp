// omninav compass: the visual compass over a sequence of panoramas (libs/compass), with the
// evaluation of Tables 3-4 of the visual compass paper (Labrosse 2006) when the input has ground
// truth.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/compass/compass_run.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/core/progress.hpp"
#include "omninav/evaluation/compass_output.hpp"
#include "omninav/io/panorama_input.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/map_heading.hpp"
#include "omninav/report/compass_figures.hpp"

namespace omninav::cli {
namespace {

namespace fs = std::filesystem;

struct CompassOptions {
  fs::path input;
  std::string method = "alg1";
  std::string minimiser;    // empty: compass.yaml's
  int width_px = 0;         // 0: compass.yaml's input.width_px, else the input's own
  double threshold = -1.0;  // < 0: compass.yaml's sampling.threshold_norm_amp
  bool truth = false;
  bool unwrap = false;
  std::string out;  // CSV; "-" for stdout, each row as soon as it is computed
  std::string format = "csv";
  fs::path plot;
  fs::path stats;
  std::string label;
  io::BagOptions bag;
  fs::path map;  // --map: re-align on the places recognised in it
};

// --method: the sampling policy, and for exhaustive|fft|phase the minimiser too.
void apply_method(const std::string& method, compass::CompassParams& params) {
  compass::SamplingParams& sampling = params.sampling;
  if (method == "alg1") {
    sampling.policy = compass::SamplingPolicy::kThreshold;
  } else if (method == "alg1-paper") {
    // Algorithm 1 as written (§3.5): no rotation cap, no global fallback, no joint rotation.
    sampling.policy = compass::SamplingPolicy::kThreshold;
    sampling.max_reference_rotation_rad = 0.0;
    params.fast_turns.global_fallback = false;
    params.joint.enabled = false;
  } else if (method.rfind("fx:", 0) == 0) {
    sampling.policy = compass::SamplingPolicy::kFixedSkip;
    const int skip = parse_int_argument(method.substr(3), "--method " + method);
    if (skip < 0) throw UsageError("--method " + method + ": the skip must be 0 or more");
    sampling.fixed_skip_frames = skip;
  } else if (method == "exhaustive" || method == "fft" || method == "phase") {
    sampling.policy = compass::SamplingPolicy::kThreshold;
    params.matcher.minimiser.kind = compass::minimiser_kind_of(method);
  } else {
    throw UsageError("--method " + method +
                     ": expected alg1, alg1-paper, fx:N (N frames skipped), exhaustive, fft or "
                     "phase");
  }
}

// The compass's parameters: compass.yaml's, then --method, --minimiser and --threshold; and the
// width to resample to (--width, else compass.yaml's input.width_px, else none).
struct CompassSetup {
  compass::CompassParams params;
  std::optional<int> width;
};

CompassSetup compass_setup(const GlobalOptions& global, const CompassOptions& options) {
  compass::CompassConfig config = load_compass_config(global.config_dir);
  CompassSetup setup{config.compass, std::nullopt};
  compass::CompassParams& params = setup.params;
  apply_method(options.method, params);
  if (!options.minimiser.empty()) {
    params.matcher.minimiser.kind = compass::minimiser_kind_of(options.minimiser);
  }
  if (options.threshold >= 0.0) params.sampling.threshold_norm_amp = options.threshold;
  if (params.matcher.minimiser.kind == compass::MinimiserKind::kFft &&
      params.matcher.distance.metric == compass::Metric::kL1) {
    throw UsageError("the fft minimiser needs distance.metric l2 (compass.yaml has l1)");
  }
  setup.width = options.width_px > 0 ? std::optional<int>(options.width_px) : config.width_px;
  return setup;
}

// Logs, once the first panorama is in, what the run will do with it.
void log_start(const CompassSetup& setup, const cv::Mat& panorama, bool has_truth) {
  const compass::CompassParams& params = setup.params;
  if (setup.width && *setup.width != panorama.cols && !panorama.empty()) {
    log_info("resampling " + std::to_string(panorama.cols) + "-column panoramas to " +
             std::to_string(*setup.width) +
             " columns (circular tent filter, front kept at 0.25*width, rows unchanged)");
  }
  log_info(std::string("visual compass: ") + describe(params.sampling) + ", minimiser " +
           to_string(params.matcher.minimiser.kind) + ", field of view " +
           (params.matcher.distance.field_of_view.front_back ? "front and back bands" : "whole") +
           ", sub-pixel " + to_string(params.matcher.subpixel.mode) +
           (has_truth ? ", started at the true heading" : ", started at 0"));
}

struct CompassRows {
  std::vector<evaluation::CompassFrame> rows;
  int reference_count = 0;
  int input_width = 0;  // the first panorama's columns
};

// --map: the map and what measures headings against it (navigation::MapHeadings).
struct MapRealignment {
  std::unique_ptr<memory::VisualMemory> memory;  // held where the headings refer to it
  std::unique_ptr<navigation::MapHeadings> headings;
};

std::optional<MapRealignment> load_map_realignment(const GlobalOptions& global,
                                                   const fs::path& map) {
  if (map.empty()) return std::nullopt;
  MapRealignment result;
  result.memory = std::make_unique<memory::VisualMemory>(memory::load_map(map));
  result.headings = std::make_unique<navigation::MapHeadings>(
      *result.memory, load_memory_config(global.config_dir).localisation);
  return result;
}

// The compass over every frame of --input, raw images unwrapped first when asked or marked;
// with --map, each frame whose place the map recognises re-aligns the compass on that place's
// heading (navigation::MapHeadings). `on_frame` sees each frame's row as soon as it is computed.
CompassRows run_over_input(const GlobalOptions& global, const CompassOptions& options,
                           const CompassSetup& setup,
                           const std::function<void(const evaluation::CompassFrame&)>& on_frame) {
  std::optional<MapRealignment> map = load_map_realignment(global, options.map);
  bool in_map_frame = false;
  // Sources as the input names them: the CSV's source column.
  io::PanoramaInput reader = open_panoramas(options.input, global.config_dir,
                                            {.force_unwrap = options.unwrap,
                                             .absolute_sources = false,
                                             .topic = options.bag.topic,
                                             .pose_topic = options.bag.pose_topic});
  log_info("reading " + reader.describe());

  CompassRows result;
  compass::CompassRun compass(setup.params, setup.width);
  const auto start = std::chrono::steady_clock::now();
  {
    Progress progress("compass", reader.size());
    while (std::optional<io::Frame> frame = reader.next()) {
      const cv::Mat& panorama = frame->image;
      if (!compass.started()) {
        result.input_width = panorama.cols;
        if (options.truth && !frame->truth) {
          throw UsageError(frame->source + ": --truth needs ground truth, and " +
                           options.input.string() + " has none for its first image");
        }
        log_start(setup, panorama, frame->truth.has_value());
      }
      const std::optional<double> truth_heading =
          frame->truth ? std::optional<double>(frame->truth->heading_rad) : std::nullopt;
      // Started at a true heading, the compass is in the world's frame, which a map's headings
      // share (they are the exploration's truth or compass, started the same way).
      if (!compass.started()) in_map_frame = truth_heading.has_value();
      result.rows.push_back({compass.push(panorama, frame->index, frame->source, truth_heading),
                             frame->source, frame->time_s, frame->truth, std::nullopt});
      if (map) {
        evaluation::CompassFrame& row = result.rows.back();
        // A re-alignment when the map's reading is surer than the compass and agrees with it
        // (navigation::realigns), or puts a compass started without a true heading in the map's
        // frame.
        const std::optional<navigation::MapHeading> heading = map->headings->measure(panorama);
        if (heading && navigation::realigns(*heading, row.estimate.heading_rad,
                                            row.estimate.heading_sigma_rad, in_map_frame)) {
          in_map_frame = true;
          compass.realign(heading->heading_rad, heading->spread_rad, row.estimate);
          row.realigned_place = static_cast<int>(heading->place);
        }
      }
      on_frame(result.rows.back());
      progress.advance();
    }
  }
  if (result.rows.empty()) throw InputError(options.input.string() + ": holds no images");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log_info("processed " + std::to_string(result.rows.size()) + " frames in " + fixed(seconds, 2) +
           " s (" + fixed(result.rows.size() / std::max(seconds, 1e-9), 1) +
           " frames/s, reading and decoding included)");
  result.reference_count = compass.reference_count();
  return result;
}

// The frames that have ground truth: their estimates and truths, for the evaluation.
struct TruthRows {
  std::vector<compass::CompassEstimate> estimates;
  std::vector<evaluation::CompassTruth> truth;
};

TruthRows truth_rows(const std::vector<evaluation::CompassFrame>& rows) {
  TruthRows result;
  for (const evaluation::CompassFrame& row : rows) {
    if (!row.truth) continue;
    result.estimates.push_back(row.estimate);
    result.truth.push_back({row.truth->heading_rad, row.truth->floor_position(), row.time_s});
  }
  return result;
}

// --label, else the input's name.
std::string dataset_label(const CompassOptions& options) {
  if (!options.label.empty()) return options.label;
  fs::path input_name = fs::absolute(options.input).lexically_normal();
  if (input_name.filename().empty()) input_name = input_name.parent_path();  // "folder/"
  return input_name.filename().string();
}

// The method as Tables 3-4 name it ("Atm 0.6055", "Fx 3"), and the minimiser when not the
// paper's.
std::string method_label(const compass::CompassParams& params) {
  return describe(params.sampling) +
         (params.matcher.minimiser.kind == compass::MinimiserKind::kLocalScan
              ? std::string()
              : " (" + to_string(params.matcher.minimiser.kind) + ")");
}

// --stats: the statistics as a one-row CSV.
void write_stats(const fs::path& path, const evaluation::CompassStatsRow& row,
                 const evaluation::CompassEvaluation& evaluation) {
  std::ostringstream csv;
  evaluation::write_compass_stats_csv(csv, row, evaluation);
  write_output_file(path, csv.str());
}

// --plot: every frame's heading, with the truth when every frame has one.
void write_plot(const fs::path& path, const CompassRows& run, const TruthRows& with_truth,
                const std::string& title) {
  std::vector<compass::CompassEstimate> all;
  std::vector<double> all_truth_rad;
  for (const evaluation::CompassFrame& row : run.rows) all.push_back(row.estimate);
  if (with_truth.estimates.size() == run.rows.size()) {
    for (const evaluation::CompassTruth& t : with_truth.truth)
      all_truth_rad.push_back(t.heading_rad);
  }
  measures::save_png(report::plot_compass_run(all, all_truth_rad, title), path);
}

void run_compass(const GlobalOptions& global, const CompassOptions& options) {
  // The outputs before the work, not after it.
  if (!options.stats.empty() && !options.truth) throw UsageError("--stats needs --truth");
  if (!options.map.empty() && !fs::exists(options.map)) {
    throw InputError(options.map.string() + ": no such map");
  }
  for (const fs::path& output :
       {fs::path(options.out == "-" ? "" : options.out), options.plot, options.stats}) {
    if (!output.empty()) check_output_path(output, {options.input, options.map});
  }
  const evaluation::RowFormat format = evaluation::row_format_of(options.format);
  const CompassSetup setup = compass_setup(global, options);
  // --out -: each row to standard output as soon as it is computed, so that another program can
  // follow a live robot; the columns are set by the first frame (truth or not).
  // Each row is handed to write_standard_output, which flushes it and turns a lost standard
  // output (a full disk, a closed pipe) into an error naming why.
  std::ostringstream pending;
  std::optional<evaluation::CompassRowWriter> live;
  const auto on_frame = [&](const evaluation::CompassFrame& row) {
    if (options.out != "-") return;
    if (!live) live.emplace(pending, format, row.truth.has_value(), !options.map.empty());
    live->write(row);
    write_standard_output(pending.str());
    pending.str("");
  };
  const CompassRows run = run_over_input(global, options, setup, on_frame);

  if (!options.out.empty() && options.out != "-") {
    const bool has_truth =
        std::any_of(run.rows.begin(), run.rows.end(),
                    [](const evaluation::CompassFrame& r) { return r.truth.has_value(); });
    std::ostringstream text;
    evaluation::CompassRowWriter writer(text, format, has_truth, !options.map.empty());
    for (const evaluation::CompassFrame& row : run.rows) writer.write(row);
    write_output_file(options.out, text.str());
  }

  // Evaluation over the frames that have ground truth.
  const TruthRows with_truth = truth_rows(run.rows);
  const std::string label = dataset_label(options);
  const std::string method = method_label(setup.params);
  const bool printing = !global.quiet && options.out != "-";
  if (options.truth) {
    if (with_truth.estimates.size() < run.rows.size()) {
      log_warning(std::to_string(run.rows.size() - with_truth.estimates.size()) +
                  " frames have no ground truth and are left out of the statistics");
    }
    const evaluation::CompassEvaluation statistics =
        evaluation::evaluate_compass(with_truth.estimates, with_truth.truth, run.reference_count);
    if (printing) std::cout << evaluation::format_compass_table(label, method, statistics);
    if (!options.stats.empty()) {
      write_stats(options.stats, {label, method, setup.width ? *setup.width : run.input_width},
                  statistics);
    }
  } else if (printing) {
    evaluation::write_compass_summary(std::cout, run.rows, run.reference_count, method);
  }
  if (!options.plot.empty()) write_plot(options.plot, run, with_truth, label + ", " + method);
}

}  // namespace

void add_compass_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<CompassOptions>();
  CLI::App* command = app.add_subcommand(
      "compass",
      "The visual compass: the robot's heading from successive panoramas alone\n"
      "(Labrosse 2004, 2006). Reads compass.yaml from --config-dir (its defaults are Table 2\n"
      "of the 2006 paper). Headings are in degrees, counter-clockwise positive; the compass\n"
      "starts at the input's true heading when it has one, else at 0.\n"
      "With --truth, prints the statistics of Tables 3-4: reference frames used (total), max\n"
      "|error|, mean, standard deviation, and the slope of the error against time (deg/s) and\n"
      "distance travelled (deg/m) by Theil-Sen robust regression.\n"
      "Examples:\n"
      "  omninav compass --input rotate_db --truth --out headings.csv --plot headings.png\n"
      "  omninav compass --input route_db --method fx:3 --width 1080 --out -");
  command
      ->add_option("-i,--input", options->input,
                   "Panoramas: a folder of images, a video, a BoB image database folder, a CSV "
                   "of file,x_m,y_m,heading_deg (docs/design.md, Data formats), a ROS bag (.bag, "
                   ".mcap, .db3; docs/bags.md); or a camera, camera:0 (V4L2), read until Ctrl-C")
      ->type_name("PATH")
      ->required();
  command
      ->add_option("-m,--method", options->method,
                   "alg1: Algorithm 1, a new reference image when the normalised amplitude falls\n"
                   "      below sampling.threshold_norm_amp (\"Atm 0.6\") or, once the pair shows\n"
                   "      parallax, the rotation from the reference exceeds\n"
                   "      sampling.max_reference_rotation_deg (ours; 0 = the paper's alone);\n"
                   "alg1-paper: Algorithm 1 exactly as the 2006 paper writes it (no rotation\n"
                   "      cap, no global fallback, no joint rotation),\n"
                   "      whatever compass.yaml says;\n"
                   "fx:N: a new reference every N+1 frames (\"Fx N\"; fx:0 = successive frames);\n"
                   "exhaustive | fft | phase: Algorithm 1 with that minimiser instead of\n"
                   "      compass.yaml's (exhaustive search, FFT correlation, Fourier phase)")
      ->capture_default_str();
  command
      ->add_option("--minimiser", options->minimiser,
                   "Override compass.yaml's minimiser.kind: local_scan, exhaustive, fft or phase "
                   "(e.g. with fx:N)")
      ->type_name("KIND");
  command
      ->add_option("--threshold", options->threshold,
                   "Override sampling.threshold_norm_amp, t of Algorithm 1 (Table 2: 0.6055)")
      ->type_name("T")
      ->check(NumberRange(0.0, 1.0));
  command
      ->add_option("-w,--width", options->width_px,
                   "Resample the panoramas to this many columns first (e.g. 360 = 1 px/deg, "
                   "1080 = 3 px/deg): circular tent filter, front kept at 0.25*width, rows "
                   "unchanged. Default: compass.yaml's input.width_px, else the input's width")
      ->type_name("COLUMNS")
      ->check(NumberRange(8, 16384));
  command->add_flag("--truth", options->truth,
                    "Evaluate against the input's ground truth and print the statistics");
  command->add_flag("--unwrap", options->unwrap,
                    "The input is raw omnidirectional images: unwrap them with camera.yaml "
                    "(automatic for BoB databases marked needsUnwrapping)");
  add_bag_options(command, options->bag);
  command
      ->add_option("--map", options->map,
                   "A map (omninav explore): each frame whose place it recognises (the "
                   "navigator's rule, navigation.yaml recognition_link_ratio) re-aligns the "
                   "compass on that place's heading plus the turn the phases measure between "
                   "the place and the frame; the CSV's realigned_place names it")
      ->type_name("MAP");
  command
      ->add_option(
          "-o,--out", options->out,
          "Write one CSV row per frame (frame, source, time_s, heading_deg,\n"
          "heading_unwrapped_deg, rotation_deg, amplitude_norm, reference_frame,\n"
          "confidence, shift_px, evaluations, heading_sigma_deg; truth_heading_deg,\n"
          "error_deg, distance_m when the input has ground truth); '-' for standard output,\n"
          "each row written\n"
          "and flushed as soon as its frame is computed (to follow a live camera)")
      ->type_name("FILE");
  command
      ->add_option("--format", options->format,
                   "csv, or jsonl: one JSON object per frame, its keys the CSV's columns (null "
                   "where the CSV is empty)")
      ->capture_default_str()
      ->check(CLI::IsMember({"csv", "jsonl"}));
  command->add_option("--plot", options->plot, "Write a PNG of heading and error against frame")
      ->type_name("FILE.png");
  command
      ->add_option("--stats", options->stats,
                   "With --truth: write the statistics as a one-row CSV (for scripts)")
      ->type_name("FILE.csv");
  command->add_option("--label", options->label,
                      "Dataset name for the statistics (default: the input's name)");
  command->callback([&global, options] { run_compass(global, *options); });
}

}  // namespace omninav::cli
