#include "omninav/evaluation/localisation_output.hpp"

#include <algorithm>

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/format.hpp"

namespace omninav::evaluation {
namespace {

std::optional<double> degrees(const std::optional<double>& radians) {
  return radians ? std::optional<double>(rad_to_deg(*radians)) : std::nullopt;
}

}  // namespace

void write_localisation_text(std::ostream& out, const QueryLocalisation& q,
                             const memory::VisualMemory& map) {
  const memory::Localisation& r = q.result;
  out << q.source << ":";
  if (q.no_match) {
    out << ' ' << *q.no_match << "\n";
    return;
  }
  const memory::PlaceMatch& best = r.best.front();
  out << " place " << best.place << " (similarity " << fixed(best.similarity, 0)
      << ", dissimilarity " << fixed(best.dissimilarity, 1) << "), heading "
      << signed_fixed(rad_to_deg(best.relative_heading_rad), 1) << " deg from the place's";
  if (best.heading_rad) {
    out << " = " << fixed(rad_to_deg(*best.heading_rad), 1) << " deg ("
        << memory::to_string(map.place(best.place).heading_source) << ")";
  }
  out << "\n";
  if (r.position) {
    const std::string unit = r.position->frame == memory::PositionFrame::kTruth ? " m" : "";
    out << "  position " << fixed(r.position->position.x(), 2) << ", "
        << fixed(r.position->position.y(), 2) << unit << " (the best place; from "
        << (r.position->frame == memory::PositionFrame::kTruth ? "the places' ground truth"
                                                               : "the lattice")
        << "), between places " << fixed(r.position->interpolated_position.x(), 2) << ", "
        << fixed(r.position->interpolated_position.y(), 2) << unit << "\n";
  }
  for (const signature::LevelResult& level : r.search.levels) {
    out << "  m=" << level.components << ": " << level.candidates.size() << " candidate"
        << (level.candidates.size() == 1 ? "" : "s") << " of " << level.evaluated << " compared:";
    for (std::size_t i = 0; i < std::min<std::size_t>(level.candidates.size(), 12); ++i) {
      out << ' ' << level.candidates[i].place;
    }
    if (level.candidates.size() > 12) out << " ...";
    out << "\n";
  }
  out << "  best:";
  for (const memory::PlaceMatch& m : r.best) {
    out << ' ' << m.place << " (" << fixed(m.similarity, 0) << ", "
        << signed_fixed(rad_to_deg(m.relative_heading_rad), 1) << " deg)";
  }
  out << "\n";
  if (q.truth && q.score) {
    out << "  truth " << fixed(q.truth->x_m, 2) << ", " << fixed(q.truth->y_m, 2) << " m, heading "
        << fixed(rad_to_deg(q.truth->heading_rad), 1) << " deg: nearest place "
        << q.score->nearest_place << ", best place " << fixed(q.score->error_m, 2) << " m away";
    if (q.score->heading_error_rad) {
      out << ", heading error " << fixed(rad_to_deg(*q.score->heading_error_rad), 1) << " deg";
    }
    out << "\n";
  }
  if (q.home) {
    if (q.home->featureless) {
      out << "  home vector: none (featureless pair)\n";
    } else {
      out << "  home vector to place " << best.place << ": "
          << signed_fixed(rad_to_deg(q.home->direction_rad), 1) << " deg from the query's front";
      if (q.home->world_direction_rad) {
        out << " = " << fixed(rad_to_deg(*q.home->world_direction_rad), 1) << " deg in the world";
      }
      out << ", rotation " << signed_fixed(rad_to_deg(q.home->rotation_rad), 1)
          << " deg from the place's (min-warping)\n";
    }
  }
}

void write_localisation_csv_header(std::ostream& out, const std::vector<int>& levels,
                                   bool home_vector) {
  std::vector<std::string> columns{"query",          "best_place",           "similarity",
                                   "dissimilarity",  "relative_heading_deg", "heading_deg",
                                   "position_frame", "position_x",           "position_y",
                                   "interpolated_x", "interpolated_y"};
  for (int m : levels) columns.push_back("candidates_m" + std::to_string(m));
  for (const char* column : {"truth_x_m", "truth_y_m", "truth_heading_deg", "nearest_place",
                             "error_m", "heading_error_deg"}) {
    columns.emplace_back(column);
  }
  if (home_vector) {
    for (const char* column :
         {"home_deg", "home_world_deg", "home_rotation_deg", "home_featureless"}) {
      columns.emplace_back(column);
    }
  }
  write_csv_line(out, columns);
}

void write_localisation_csv_row(std::ostream& out, const QueryLocalisation& q) {
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
  if (q.home) {
    const bool none = q.home->featureless;
    row.insert(row.end(),
               {none ? "" : fixed(rad_to_deg(q.home->direction_rad), 3),
                none ? "" : fixed_or_empty(degrees(q.home->world_direction_rad), 3),
                none ? "" : fixed(rad_to_deg(q.home->rotation_rad), 3), none ? "1" : "0"});
  }
  write_csv_line(out, row);
}

Json localisation_json(const QueryLocalisation& q) {
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
                {"interpolated_y", json_number(r.position->interpolated_position.y(), 4)},
                {"between_x", json_number(r.position->between_places.x(), 4)},
                {"between_y", json_number(r.position->between_places.y(), 4)}};
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
  Json document = {{"query", q.source},
                   {"levels", std::move(levels)},
                   {"best", std::move(best)},
                   {"position", std::move(position)},
                   {"truth", std::move(truth)}};
  if (q.home) {
    const bool none = q.home->featureless;
    document["home_vector"] = {
        {"featureless", none},
        {"direction_deg", none ? Json(nullptr) : json_number(rad_to_deg(q.home->direction_rad), 3)},
        {"world_direction_deg",
         none ? Json(nullptr) : json_number(degrees(q.home->world_direction_rad), 3)},
        {"rotation_deg", none ? Json(nullptr) : json_number(rad_to_deg(q.home->rotation_rad), 3)}};
  }
  return document;
}

Json localisation_json(const std::filesystem::path& map, const std::vector<int>& levels,
                       const std::vector<QueryLocalisation>& queries,
                       const std::optional<LocalisationScore>& score) {
  Json document{{"map", map.string()}, {"levels", levels}, {"queries", Json::array()}};
  for (const QueryLocalisation& q : queries) document["queries"].push_back(localisation_json(q));
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

}  // namespace omninav::evaluation
