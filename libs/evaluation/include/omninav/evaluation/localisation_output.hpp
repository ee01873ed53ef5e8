// The results of `omninav localise` (hierarchical localisation, Menegatti et al. 2004, §2.3) as
// text, CSV or JSON, with each query's score when it has ground truth. Here rather than in
// libs/report because the scores are the evaluation layer's.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "omninav/core/json.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/evaluation/localisation_score.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::evaluation {

// `localise --home-vector`: min-warping (compass/min_warping.hpp) of the query against its best
// place's stored thumbnail, the place as the snapshot.
struct HomeVector {
  double direction_rad = 0.0;  // from the query's place to the best place, in the query's frame
  double rotation_rad = 0.0;   // the query's heading minus the place's
  std::optional<double> world_direction_rad;  // the same in the world, when the place has a
                                              // heading
  bool featureless = false;                   // no estimate (the angles are 0)
};

// One query image localised.
struct QueryLocalisation {
  std::string source;
  memory::Localisation result;
  std::optional<CameraPose> truth;
  std::optional<LocalisationScore::Query> score;  // with truth against a map with truth
  std::optional<std::string> no_match;            // why the query matches no place of the map
  std::optional<HomeVector> home;                 // --home-vector
};

// The best place, its heading, the position, each level's candidates, the best places and the
// score: a few lines per query. `map` names the places' heading sources.
void write_localisation_text(std::ostream& out, const QueryLocalisation& query,
                             const memory::VisualMemory& map);

// The CSV header for hierarchies of `levels` (one candidates_m<m> column per level; with
// `home_vector`, the columns home_deg, home_world_deg, home_rotation_deg and home_featureless
// last), and one query's row (those columns when it has a home vector).
void write_localisation_csv_header(std::ostream& out, const std::vector<int>& levels,
                                   bool home_vector = false);
void write_localisation_csv_row(std::ostream& out, const QueryLocalisation& query);

// One query as JSON.
Json localisation_json(const QueryLocalisation& query);
// The whole --format json document: the map, its levels, one object per query, and the
// scores' summary when some queries were scored.
Json localisation_json(const std::filesystem::path& map, const std::vector<int>& levels,
                       const std::vector<QueryLocalisation>& queries,
                       const std::optional<LocalisationScore>& score);

}  // namespace omninav::evaluation
