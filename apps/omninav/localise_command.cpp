// omninav localise: hierarchical localisation of query images in a visual memory.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/json.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/evaluation/localisation_output.hpp"
#include "omninav/evaluation/query_localisation.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/report/memory_figures.hpp"

namespace omninav::cli {
namespace {

struct LocaliseOptions {
  std::filesystem::path map;
  std::vector<std::filesystem::path> queries;
  std::optional<std::string> levels;  // none: memory.yaml
  int top_k = 0;                      // 0: memory.yaml
  OutputFormat format = OutputFormat::kText;
  std::filesystem::path plot;
  bool exhaustive = false;
  bool unwrap = false;
  bool home_vector = false;
  io::BagOptions bag;
};

// The figure of query `index`: <stem>_<index><ext> next to --plot. A single query's figure is
// the --plot path itself: the first figure waits until a second query shows which it is.
std::filesystem::path numbered_plot_file(const std::filesystem::path& plot, std::size_t index) {
  return plot.parent_path() /
         fmt::format("{}_{:04}{}", plot.stem().string(), index, plot.extension().string());
}

void run_localise(const GlobalOptions& global, const LocaliseOptions& options) {
  memory::MemoryConfig config = load_memory_config(global.config_dir);
  memory::LocalisationParams params = config.localisation;
  if (options.levels) {
    if (trim(*options.levels).empty()) {
      throw UsageError(
          "--levels is empty: give the components compared at each level, e.g. 2,5,15");
    }
    params.hierarchy.levels = signature::parse_levels(*options.levels, "--levels");
  }
  if (options.top_k > 0) params.top_k = options.top_k;
  if (!options.plot.empty()) {  // before the work; neither the map nor a query may be replaced
    std::vector<std::filesystem::path> inputs = options.queries;
    inputs.push_back(options.map);
    check_output_path(options.plot, inputs);
    for (std::size_t i = 0; i < options.queries.size(); ++i) {
      check_not_an_input(numbered_plot_file(options.plot, i), inputs);
    }
  }

  const memory::VisualMemory map = memory::load_map(options.map);
  evaluation::QueryLocalisationOptions query_options;
  query_options.exhaustive = options.exhaustive;
  if (options.home_vector) {
    query_options.home_vector = load_compass_config(global.config_dir).min_warping;
    query_options.panorama = load_camera_config(global.config_dir).panorama;
  }
  // A query matches a place by route's and navigate's criterion (navigation.yaml).
  evaluation::QueryLocaliser localiser(map, options.map.string(), params,
                                       load_navigation_config(global.config_dir).route,
                                       query_options);
  if (!options.plot.empty() && !memory::place_positions(map)) {
    throw UsageError(options.map.string() +
                     ": --plot needs place positions (a lattice or ground truth); the map has "
                     "neither");
  }

  std::vector<evaluation::QueryLocalisation> results;
  cv::Mat first_figure;  // --plot: the first query's, written once the count is known
  for (const std::filesystem::path& query : options.queries) {
    io::PanoramaInput input = open_panoramas(query, global.config_dir,
                                             {.force_unwrap = options.unwrap,
                                              .topic = options.bag.topic,
                                              .pose_topic = options.bag.pose_topic});
    while (std::optional<io::Frame> frame = input.next()) {
      const signature::Signature signature = localiser.signature_of(*frame);
      evaluation::QueryLocalisation q = localiser.localise(*frame, signature);
      if (!options.plot.empty()) {
        std::optional<Eigen::Vector2d> truth;
        if (q.truth && memory::place_positions(map)->first == memory::PositionFrame::kTruth) {
          truth = q.truth->floor_position();
        }
        cv::Mat figure = report::localisation_figure(
            localiser.localiser(), signature, q.result, truth,
            "hierarchical localisation of " + std::filesystem::path(q.source).filename().string());
        if (results.empty()) {
          first_figure = std::move(figure);
        } else {
          if (results.size() == 1) {
            measures::save_png(first_figure, numbered_plot_file(options.plot, 0));
          }
          measures::save_png(figure, numbered_plot_file(options.plot, results.size()));
        }
      }
      results.push_back(std::move(q));
    }
  }
  if (results.empty()) throw UsageError("no query images");
  if (results.size() == 1 && results.front().no_match) {
    throw InputError(results.front().source + ": " + *results.front().no_match);
  }
  if (!options.plot.empty() && results.size() == 1) measures::save_png(first_figure, options.plot);
  const auto unmatched =
      std::count_if(results.begin(), results.end(),
                    [](const evaluation::QueryLocalisation& q) { return q.no_match.has_value(); });
  if (unmatched > 0) {
    log_warning(std::to_string(unmatched) + " of " + std::to_string(results.size()) +
                " queries match no place of the map");
  }

  const std::vector<int>& levels = params.hierarchy.levels;
  const std::optional<evaluation::LocalisationScore>& score = localiser.score();
  if (options.format == OutputFormat::kCsv) {
    evaluation::write_localisation_csv_header(std::cout, levels, options.home_vector);
    for (const evaluation::QueryLocalisation& q : results) {
      evaluation::write_localisation_csv_row(std::cout, q);
    }
  } else if (options.format == OutputFormat::kJson) {
    std::cout << json_text(evaluation::localisation_json(options.map, levels, results, score))
              << "\n";
  } else {
    for (const evaluation::QueryLocalisation& q : results) {
      evaluation::write_localisation_text(std::cout, q, map);
    }
    if (score && score->queries() > 1) std::cout << score->summary(levels);
  }
  if (score && score->queries() > 0 && options.format != OutputFormat::kText)
    log_info(score->summary(levels));
  if (!options.plot.empty()) {
    log_info("wrote " + std::to_string(results.size()) + " figure" +
             (results.size() == 1 ? "" : "s") + " like Figs. 8-10 to " +
             (results.size() == 1 ? options.plot.string()
                                  : numbered_plot_file(options.plot, 0).string() + " ..."));
  }
}

}  // namespace

void add_localise_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<LocaliseOptions>();
  CLI::App* command = app.add_subcommand(
      "localise",
      "Localise query images in a visual memory, coarse to fine (Menegatti et al. 2004, "
      "§2.3): for each level (number of Fourier components compared) the candidate places whose "
      "similarity passes memory.yaml's threshold, at the finest the best places with the "
      "query's heading relative to each, and a position when the places have one (lattice, "
      "else ground truth). Queries with ground truth against a map with ground truth are "
      "scored (docs/design.md, Evaluation).");
  command->add_option("map", options->map, "The map, e.g. maps/room.vmem")->required();
  command
      ->add_option("queries", options->queries,
                   "Query panoramas: image files, folders, videos, databases or ROS bags "
                   "(--topic; docs/bags.md), or a camera: camera:0 (V4L2; Ctrl-C ends it)")
      ->required();
  command->add_option("--levels", options->levels,
                      "Components compared at each level, e.g. 2,5,15 (default: memory.yaml)");
  command->add_option("--top", options->top_k, "Best places to report (default: memory.yaml)")
      ->check(NumberRange(1, 100000));
  add_format_option(command, options->format);
  command->add_option("--plot", options->plot,
                      "Write a PNG like Figs. 8-10 per query (several queries: FILE_0000.png, "
                      "...); needs place positions");
  command->add_flag("--exhaustive", options->exhaustive,
                    "Compare every place at every level (no pruning; for comparison)");
  command->add_flag("--home-vector", options->home_vector,
                    "Also the direction from each query's place to its best place, and the "
                    "rotation between them, by min-warping against the place's stored panorama "
                    "(compass.yaml's min_warping section; docs/compass.md)");
  command->add_flag("--unwrap", options->unwrap,
                    "The queries are raw omnidirectional images: unwrap them with camera.yaml");
  add_bag_options(command, options->bag);
  command->callback([&global, options] { run_localise(global, *options); });
}

}  // namespace omninav::cli
