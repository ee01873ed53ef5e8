// omninav localise: hierarchical localisation of query images in a visual memory.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/json.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/eval/png.hpp"
#include "omninav/evaluation/localisation_score.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
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
};

// The figure of query `index`: <stem>_<index><ext> next to --plot. A single query's figure is
// the --plot path itself: the first figure waits until a second query shows which it is.
std::filesystem::path numbered_plot_file(const std::filesystem::path& plot, std::size_t index) {
  return plot.parent_path() /
         fmt::format("{}_{:04}{}", plot.stem().string(), index, plot.extension().string());
}

struct QueryResult {
  std::string source;
  memory::Localisation result;
  std::optional<CameraPose> truth;
  std::optional<evaluation::LocalisationScore::Query> score;
  std::optional<std::string> no_match;  // why the query matches no place of the map
};

void print_text(const QueryResult& q, const memory::VisualMemory& map) {
  const memory::Localisation& r = q.result;
  std::cout << q.source << ":";
  if (q.no_match) {
    std::cout << ' ' << *q.no_match << "\n";
    return;
  }
  const memory::PlaceMatch& best = r.best.front();
  std::cout << " place " << best.place << " (similarity " << fixed(best.similarity, 0)
            << ", dissimilarity " << fixed(best.dissimilarity, 1) << "), heading "
            << signed_fixed(rad_to_deg(best.relative_heading_rad), 1) << " deg from the place's";
  if (best.heading_rad) {
    std::cout << " = " << fixed(rad_to_deg(*best.heading_rad), 1) << " deg ("
              << memory::to_string(map.place(best.place).heading_source) << ")";
  }
  std::cout << "\n";
  if (r.position) {
    const std::string unit = r.position->frame == memory::PositionFrame::kTruth ? " m" : "";
    std::cout << "  position " << fixed(r.position->position.x(), 2) << ", "
              << fixed(r.position->position.y(), 2) << unit << " (the best place; from "
              << (r.position->frame == memory::PositionFrame::kTruth ? "the places' ground truth"
                                                                     : "the lattice")
              << "), between places " << fixed(r.position->interpolated_position.x(), 2) << ", "
              << fixed(r.position->interpolated_position.y(), 2) << unit << "\n";
  }
  for (const signature::LevelResult& level : r.search.levels) {
    std::cout << "  m=" << level.components << ": " << level.candidates.size() << " candidate"
              << (level.candidates.size() == 1 ? "" : "s") << " of " << level.evaluated
              << " compared:";
    for (std::size_t i = 0; i < std::min<std::size_t>(level.candidates.size(), 12); ++i) {
      std::cout << ' ' << level.candidates[i].place;
    }
    if (level.candidates.size() > 12) std::cout << " ...";
    std::cout << "\n";
  }
  std::cout << "  best:";
  for (const memory::PlaceMatch& m : r.best) {
    std::cout << ' ' << m.place << " (" << fixed(m.similarity, 0) << ", "
              << signed_fixed(rad_to_deg(m.relative_heading_rad), 1) << " deg)";
  }
  std::cout << "\n";
  if (q.truth && q.score) {
    std::cout << "  truth " << fixed(q.truth->x_m, 2) << ", " << fixed(q.truth->y_m, 2)
              << " m, heading " << fixed(rad_to_deg(q.truth->heading_rad), 1)
              << " deg: nearest place " << q.score->nearest_place << ", best place "
              << fixed(q.score->error_m, 2) << " m away";
    if (q.score->heading_error_rad) {
      std::cout << ", heading error " << fixed(rad_to_deg(*q.score->heading_error_rad), 1)
                << " deg";
    }
    std::cout << "\n";
  }
}

void print_csv_header(const std::vector<int>& levels) {
  std::vector<std::string> columns{"query",          "best_place",           "similarity",
                                   "dissimilarity",  "relative_heading_deg", "heading_deg",
                                   "position_frame", "position_x",           "position_y",
                                   "interpolated_x", "interpolated_y"};
  for (int m : levels) columns.push_back("candidates_m" + std::to_string(m));
  for (const char* column : {"truth_x_m", "truth_y_m", "truth_heading_deg", "nearest_place",
                             "error_m", "heading_error_deg"}) {
    columns.emplace_back(column);
  }
  write_csv_line(std::cout, columns);
}

std::optional<double> degrees(const std::optional<double>& radians) {
  return radians ? std::optional<double>(rad_to_deg(*radians)) : std::nullopt;
}

void print_csv(const QueryResult& q) {
  const memory::Localisation& r = q.result;
  std::vector<std::string> row{q.source};
  if (!r.best.empty()) {
    const memory::PlaceMatch& b = r.best.front();
    row.insert(row.end(), {std::to_string(b.place), fixed(b.similarity, 1),
                           fixed(b.dissimilarity, 3), fixed(rad_to_deg(b.relative_heading_rad), 3),
                           fixed_or_empty(degrees(b.heading_rad), 3)});
  } else {
    row.resize(row.size() + 5);
  }
  if (r.position) {
    row.insert(row.end(),
               {memory::to_string(r.position->frame), fixed(r.position->position.x(), 4),
                fixed(r.position->position.y(), 4), fixed(r.position->interpolated_position.x(), 4),
                fixed(r.position->interpolated_position.y(), 4)});
  } else {
    row.resize(row.size() + 5);
  }
  for (const signature::LevelResult& level : r.search.levels) {
    row.push_back(std::to_string(level.candidates.size()));
  }
  if (q.truth) {
    row.insert(row.end(), {fixed(q.truth->x_m, 4), fixed(q.truth->y_m, 4),
                           fixed(rad_to_deg(q.truth->heading_rad), 3)});
  } else {
    row.resize(row.size() + 3);
  }
  if (q.score) {
    row.insert(row.end(), {std::to_string(q.score->nearest_place), fixed(q.score->error_m, 4),
                           fixed_or_empty(degrees(q.score->heading_error_rad), 3)});
  } else {
    row.resize(row.size() + 3);
  }
  write_csv_line(std::cout, row);
}

Json to_json(const QueryResult& q) {
  const memory::Localisation& r = q.result;
  Json levels = Json::array();
  for (const signature::LevelResult& level : r.search.levels) {
    Json candidates = Json::array();
    for (const auto& candidate : level.candidates) {
      candidates.push_back(
          {{"place", candidate.place}, {"similarity", json_number(candidate.similarity, 1)}});
    }
    levels.push_back({{"components", level.components},
                      {"compared", level.evaluated},
                      {"candidates", std::move(candidates)}});
  }
  Json best = Json::array();
  for (const memory::PlaceMatch& m : r.best) {
    best.push_back({{"place", m.place},
                    {"similarity", json_number(m.similarity, 1)},
                    {"dissimilarity", json_number(m.dissimilarity, 3)},
                    {"relative_heading_deg", json_number(rad_to_deg(m.relative_heading_rad), 3)},
                    {"heading_confidence", json_number(m.heading_confidence, 3)},
                    {"heading_deg", json_number(degrees(m.heading_rad), 3)}});
  }
  Json position = nullptr;
  if (r.position) {
    position = {{"frame", memory::to_string(r.position->frame)},
                {"x", json_number(r.position->position.x(), 4)},
                {"y", json_number(r.position->position.y(), 4)},
                {"interpolated_x", json_number(r.position->interpolated_position.x(), 4)},
                {"interpolated_y", json_number(r.position->interpolated_position.y(), 4)}};
  }
  Json truth = nullptr;
  if (q.truth && q.score) {
    truth = {{"x_m", json_number(q.truth->x_m, 4)},
             {"y_m", json_number(q.truth->y_m, 4)},
             {"heading_deg", json_number(rad_to_deg(q.truth->heading_rad), 3)},
             {"nearest_place", q.score->nearest_place},
             {"error_m", json_number(q.score->error_m, 4)},
             {"heading_error_deg", json_number(degrees(q.score->heading_error_rad), 3)}};
  }
  return {{"query", q.source},
          {"levels", std::move(levels)},
          {"best", std::move(best)},
          {"position", std::move(position)},
          {"truth", std::move(truth)}};
}

// The whole --format json document: the map, its levels, one object per query, and the
// scores when the queries have ground truth.
Json localisation_json(const std::filesystem::path& map, const std::vector<int>& levels,
                       const std::vector<QueryResult>& results,
                       const std::optional<evaluation::LocalisationScore>& score) {
  Json document{{"map", map.string()}, {"levels", levels}, {"queries", Json::array()}};
  for (const QueryResult& q : results) document["queries"].push_back(to_json(q));
  if (score && score->queries() > 0) {
    Json contains = Json::array(), sizes = Json::array();
    for (const double share : score->level_contains_share()) {
      contains.push_back(json_number(share, 4));
    }
    for (const double size : score->level_mean_size()) sizes.push_back(json_number(size, 2));
    document["summary"] = {{"queries", score->queries()},
                           {"off_grid_not_scored", score->outside()},
                           {"spacing_m", json_number(score->spacing_m(), 4)},
                           {"within_one_spacing", json_number(score->within_spacing_share(), 4)},
                           {"at_nearest_place", json_number(score->nearest_share(), 4)},
                           {"mean_error_m", json_number(score->mean_error_m(), 4)},
                           {"level_contains_nearest", std::move(contains)},
                           {"level_mean_candidates", std::move(sizes)}};
  }
  return document;
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
  if (!options.plot.empty()) check_output_path(options.plot);  // before the work

  const memory::VisualMemory map = memory::load_map(options.map);
  if (map.place_count() == 0) throw InputError(options.map.string() + ": the map has no places");
  const memory::Localiser localiser(map, params);
  signature::SignatureExtractor extractor(map.parameters().signature);
  // A query matches a place by route's and navigate's criterion (navigation.yaml).
  const double match_limit =
      navigation::match_limit(map, load_navigation_config(global.config_dir).route);
  std::optional<evaluation::LocalisationScore> score;
  if (map.all_have_truth()) score.emplace(map);
  if (!options.plot.empty() && !memory::place_positions(map)) {
    throw UsageError(options.map.string() +
                     ": --plot needs place positions (a lattice or ground truth); the map has "
                     "neither");
  }

  std::vector<QueryResult> results;
  cv::Mat first_figure;  // --plot: the first query's, written once the count is known
  for (const std::filesystem::path& query : options.queries) {
    io::PanoramaInput input =
        open_panoramas(query, global.config_dir, {.force_unwrap = options.unwrap});
    while (std::optional<io::Frame> frame = input.next()) {
      const signature::Signature signature = extractor.compute(frame->image, frame->source);
      if (signature.rows != map.parameters().panorama_rows) {
        throw InputError(frame->source + ": a panorama of " + std::to_string(signature.rows) +
                         " rows; the map's have " + std::to_string(map.parameters().panorama_rows));
      }
      QueryResult q;
      q.source = frame->source;
      q.truth = frame->truth;
      q.result = options.exhaustive ? localiser.localise_exhaustive(signature)
                                    : localiser.localise(signature);
      q.no_match = navigation::no_match_reason(q.result, match_limit);
      if (q.no_match) {
        q.result.best.clear();
        q.result.position.reset();
      }
      if (score && q.truth) q.score = score->add(q.result, *q.truth);
      if (!options.plot.empty()) {
        std::optional<Eigen::Vector2d> truth;
        if (q.truth && memory::place_positions(map)->first == memory::PositionFrame::kTruth) {
          truth = q.truth->floor_position();
        }
        cv::Mat figure = report::localisation_figure(
            localiser, signature, q.result, truth,
            "hierarchical localisation of " + std::filesystem::path(q.source).filename().string());
        if (results.empty()) {
          first_figure = std::move(figure);
        } else {
          if (results.size() == 1) {
            eval::save_png(first_figure, numbered_plot_file(options.plot, 0));
          }
          eval::save_png(figure, numbered_plot_file(options.plot, results.size()));
        }
      }
      results.push_back(std::move(q));
    }
  }
  if (results.empty()) throw UsageError("no query images");
  if (results.size() == 1 && results.front().no_match) {
    throw InputError(results.front().source + ": " + *results.front().no_match);
  }
  if (!options.plot.empty() && results.size() == 1) eval::save_png(first_figure, options.plot);
  const auto unmatched = std::count_if(results.begin(), results.end(),
                                       [](const QueryResult& q) { return q.no_match.has_value(); });
  if (unmatched > 0) {
    log_warning(std::to_string(unmatched) + " of " + std::to_string(results.size()) +
                " queries match no place of the map");
  }

  const std::vector<int>& levels = params.hierarchy.levels;
  if (options.format == OutputFormat::kCsv) {
    print_csv_header(levels);
    for (const QueryResult& q : results) print_csv(q);
  } else if (options.format == OutputFormat::kJson) {
    std::cout << json_text(localisation_json(options.map, levels, results, score)) << "\n";
  } else {
    for (const QueryResult& q : results) print_text(q, map);
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
      "Localise query images in a visual memory, coarse to fine (001_5bb151a4e28490b4.txt "
      "§2.3): for each level (number of Fourier components compared) the candidate places whose "
      "similarity passes memory.yaml's threshold, at the finest the best places with the "
      "query's heading relative to each, and a position when the places have one (lattice, "
      "else ground truth). Queries with ground truth against a map with ground truth are "
      "scored (DESIGN.md, Evaluation).");
  command->add_option("map", options->map, "The map, e.g. maps/room.vmem")->required();
  command
      ->add_option("queries", options->queries,
                   "Query panoramas: image files, folders, videos or databases")
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
  command->add_flag("--unwrap", options->unwrap,
                    "The queries are raw omnidirectional images: unwrap them with camera.yaml");
  command->callback([&global, options] { run_localise(global, *options); });
}

}  // namespace omninav::cli
