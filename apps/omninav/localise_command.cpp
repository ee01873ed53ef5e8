// omninav localise: hierarchical localisation of query images in a visual memory.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/eval/png.hpp"
#include "omninav/evaluation/localisation_score.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/report/memory_figures.hpp"
#include "panorama_input.hpp"

namespace omninav::cli {
namespace {

struct LocaliseOptions {
  std::filesystem::path map;
  std::vector<std::filesystem::path> queries;
  std::optional<std::string> levels;  // none: memory.yaml
  int top_k = 0;                      // 0: memory.yaml
  std::string format = "text";
  std::filesystem::path plot;
  bool exhaustive = false;
  bool unwrap = false;
};

std::string number(double value, int digits) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}

std::string signed_number(double value, int digits) {
  return (value >= 0.0 ? "+" : "") + number(value, digits);
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The figure of query `index`: <stem>_<index><ext> next to --plot. A single query's figure is
// the --plot path itself: the first figure waits until a second query shows which it is.
std::filesystem::path numbered_plot_file(const std::filesystem::path& plot, std::size_t index) {
  std::ostringstream name;
  name << plot.stem().string() << '_' << std::setw(4) << std::setfill('0') << index
       << plot.extension().string();
  return plot.parent_path() / name.str();
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
  std::cout << " place " << best.place << " (similarity " << number(best.similarity, 0)
            << ", dissimilarity " << number(best.dissimilarity, 1) << "), heading "
            << signed_number(rad_to_deg(best.relative_heading_rad), 1) << " deg from the place's";
  if (best.heading_rad) {
    std::cout << " = " << number(rad_to_deg(*best.heading_rad), 1) << " deg ("
              << memory::to_string(map.place(best.place).heading_source) << ")";
  }
  std::cout << "\n";
  if (r.position) {
    const std::string unit = r.position->frame == memory::PositionFrame::kTruth ? " m" : "";
    std::cout << "  position " << number(r.position->position.x(), 2) << ", "
              << number(r.position->position.y(), 2) << unit << " (the best place; from "
              << (r.position->frame == memory::PositionFrame::kTruth ? "the places' ground truth"
                                                                     : "the lattice")
              << "), between places " << number(r.position->interpolated_position.x(), 2) << ", "
              << number(r.position->interpolated_position.y(), 2) << unit << "\n";
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
    std::cout << ' ' << m.place << " (" << number(m.similarity, 0) << ", "
              << signed_number(rad_to_deg(m.relative_heading_rad), 1) << " deg)";
  }
  std::cout << "\n";
  if (q.truth && q.score) {
    std::cout << "  truth " << number(q.truth->x_m, 2) << ", " << number(q.truth->y_m, 2)
              << " m, heading " << number(rad_to_deg(q.truth->heading_rad), 1)
              << " deg: nearest place " << q.score->nearest_place << ", best place "
              << number(q.score->error_m, 2) << " m away";
    if (q.score->heading_error_rad) {
      std::cout << ", heading error " << number(rad_to_deg(*q.score->heading_error_rad), 1)
                << " deg";
    }
    std::cout << "\n";
  }
}

void print_csv_header(const std::vector<int>& levels) {
  std::cout << "query,best_place,similarity,dissimilarity,relative_heading_deg,heading_deg,"
               "position_frame,position_x,position_y,interpolated_x,interpolated_y";
  for (int m : levels) std::cout << ",candidates_m" << m;
  std::cout << ",truth_x_m,truth_y_m,truth_heading_deg,nearest_place,error_m,heading_error_deg\n";
}

void print_csv(const QueryResult& q) {
  const memory::Localisation& r = q.result;
  std::cout << csv_field(q.source) << ',';
  if (!r.best.empty()) {
    const memory::PlaceMatch& b = r.best.front();
    std::cout << b.place << ',' << number(b.similarity, 1) << ',' << number(b.dissimilarity, 3)
              << ',' << number(rad_to_deg(b.relative_heading_rad), 3) << ','
              << (b.heading_rad ? number(rad_to_deg(*b.heading_rad), 3) : "") << ',';
  } else {
    std::cout << ",,,,,";
  }
  if (r.position) {
    std::cout << memory::to_string(r.position->frame) << ',' << number(r.position->position.x(), 4)
              << ',' << number(r.position->position.y(), 4) << ','
              << number(r.position->interpolated_position.x(), 4) << ','
              << number(r.position->interpolated_position.y(), 4);
  } else {
    std::cout << ",,,,";
  }
  for (const signature::LevelResult& level : r.search.levels) {
    std::cout << ',' << level.candidates.size();
  }
  if (q.truth) {
    std::cout << ',' << number(q.truth->x_m, 4) << ',' << number(q.truth->y_m, 4) << ','
              << number(rad_to_deg(q.truth->heading_rad), 3) << ',';
  } else {
    std::cout << ",,,,";
  }
  if (q.score) {
    std::cout << q.score->nearest_place << ',' << number(q.score->error_m, 4) << ','
              << (q.score->heading_error_rad ? number(rad_to_deg(*q.score->heading_error_rad), 3)
                                             : "");
  } else {
    std::cout << ",,";
  }
  std::cout << "\n";
}

std::string to_json(const QueryResult& q) {
  const memory::Localisation& r = q.result;
  std::ostringstream j;
  j << "{\"query\": " << json_string(q.source) << ", \"levels\": [";
  for (std::size_t l = 0; l < r.search.levels.size(); ++l) {
    const signature::LevelResult& level = r.search.levels[l];
    j << (l ? ", " : "") << "{\"components\": " << level.components
      << ", \"compared\": " << level.evaluated << ", \"candidates\": [";
    for (std::size_t i = 0; i < level.candidates.size(); ++i) {
      j << (i ? ", " : "") << "{\"place\": " << level.candidates[i].place
        << ", \"similarity\": " << number(level.candidates[i].similarity, 1) << "}";
    }
    j << "]}";
  }
  j << "], \"best\": [";
  for (std::size_t i = 0; i < r.best.size(); ++i) {
    const memory::PlaceMatch& m = r.best[i];
    j << (i ? ", " : "") << "{\"place\": " << m.place
      << ", \"similarity\": " << number(m.similarity, 1)
      << ", \"dissimilarity\": " << number(m.dissimilarity, 3)
      << ", \"relative_heading_deg\": " << number(rad_to_deg(m.relative_heading_rad), 3)
      << ", \"heading_confidence\": " << number(m.heading_confidence, 3)
      << ", \"heading_deg\": " << (m.heading_rad ? number(rad_to_deg(*m.heading_rad), 3) : "null")
      << "}";
  }
  j << "], \"position\": ";
  if (r.position) {
    j << "{\"frame\": " << json_string(memory::to_string(r.position->frame))
      << ", \"x\": " << number(r.position->position.x(), 4)
      << ", \"y\": " << number(r.position->position.y(), 4)
      << ", \"interpolated_x\": " << number(r.position->interpolated_position.x(), 4)
      << ", \"interpolated_y\": " << number(r.position->interpolated_position.y(), 4) << "}";
  } else {
    j << "null";
  }
  j << ", \"truth\": ";
  if (q.truth && q.score) {
    j << "{\"x_m\": " << number(q.truth->x_m, 4) << ", \"y_m\": " << number(q.truth->y_m, 4)
      << ", \"heading_deg\": " << number(rad_to_deg(q.truth->heading_rad), 3)
      << ", \"nearest_place\": " << q.score->nearest_place
      << ", \"error_m\": " << number(q.score->error_m, 4) << ", \"heading_error_deg\": "
      << (q.score->heading_error_rad ? number(rad_to_deg(*q.score->heading_error_rad), 3) : "null")
      << "}";
  } else {
    j << "null";
  }
  j << "}";
  return j.str();
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
    PanoramaInput input(query, global.config_dir, options.unwrap);
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
  if (options.format == "csv") {
    print_csv_header(levels);
    for (const QueryResult& q : results) print_csv(q);
  } else if (options.format == "json") {
    std::cout << "{\"map\": " << json_string(options.map.string()) << ", \"levels\": [";
    for (std::size_t l = 0; l < levels.size(); ++l) std::cout << (l ? ", " : "") << levels[l];
    std::cout << "], \"queries\": [\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
      std::cout << "  " << to_json(results[i]) << (i + 1 < results.size() ? ",\n" : "\n");
    }
    std::cout << "]";
    if (score && score->queries() > 0) {
      std::cout << ", \"summary\": {\"queries\": " << score->queries()
                << ", \"off_grid_not_scored\": " << score->outside()
                << ", \"spacing_m\": " << number(score->spacing_m(), 4)
                << ", \"within_one_spacing\": " << number(score->within_spacing_share(), 4)
                << ", \"at_nearest_place\": " << number(score->nearest_share(), 4)
                << ", \"mean_error_m\": " << number(score->mean_error_m(), 4)
                << ", \"level_contains_nearest\": [";
      const auto contains = score->level_contains_share();
      for (std::size_t l = 0; l < contains.size(); ++l) {
        std::cout << (l ? ", " : "") << number(contains[l], 4);
      }
      std::cout << "], \"level_mean_candidates\": [";
      const auto sizes = score->level_mean_size();
      for (std::size_t l = 0; l < sizes.size(); ++l) {
        std::cout << (l ? ", " : "") << number(sizes[l], 2);
      }
      std::cout << "]}";
    }
    std::cout << "}\n";
  } else {
    for (const QueryResult& q : results) print_text(q, map);
    if (score && score->queries() > 1) std::cout << score->summary(levels);
  }
  if (score && score->queries() > 0 && options.format != "text") log_info(score->summary(levels));
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
  command->add_option("--format", options->format, "text, csv or json")
      ->check(CLI::IsMember({"text", "csv", "json"}))
      ->capture_default_str();
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
