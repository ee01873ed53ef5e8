// The localisation's text, CSV and JSON against a hand-built localisation.
#include "omninav/evaluation/localisation_output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "omninav/core/parse.hpp"

namespace omninav::evaluation {
namespace {

// Two levels (m = 2: places 3 and 5 of 10; m = 15: place 3 of 2); best place 3, the query
// turned 10° from it; positions from the lattice; truth at (1, 2) heading 90°, 0.5 m away.
QueryLocalisation query() {
  QueryLocalisation q;
  q.source = "q.png";
  signature::LevelResult coarse{2, 10, 0.0, 1.0, {{3, 1.0f, 1000.0f}, {5, 2.0f, 250.0f}}};
  signature::LevelResult fine{15, 2, 0.0, 1.0, {{3, 4.0f, 1000.0f}}};
  q.result.search.levels = {coarse, fine};
  memory::PlaceMatch best;
  best.place = 3;
  best.similarity = 1000.0;
  best.dissimilarity = 4.3;
  best.relative_heading_rad = 10.0 * M_PI / 180.0;
  best.heading_confidence = 0.5;
  q.result.best = {best};
  q.result.position = memory::PositionEstimate{
      memory::PositionFrame::kLattice, {1.5, 2.0}, {1.25, 2.0}, {1.125, 2.0}};
  q.truth = CameraPose{1.0, 2.0, 1.0, M_PI / 2, 0.0, 0.0};
  LocalisationScore::Query score;
  score.nearest_place = 5;
  score.error_m = 0.5;
  q.score = score;
  return q;
}

TEST(LocalisationOutput, CsvHasOneCandidateColumnPerLevel) {
  std::ostringstream csv;
  write_localisation_csv_header(csv, {2, 15});
  write_localisation_csv_row(csv, query());
  std::istringstream lines(csv.str());
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  const std::vector<std::string> columns = split(header, ',');
  const std::vector<std::string> fields = split(row, ',');
  ASSERT_EQ(columns.size(), 19u);
  ASSERT_EQ(fields.size(), columns.size());
  EXPECT_EQ(columns[11], "candidates_m2");
  EXPECT_EQ(columns[12], "candidates_m15");
  const std::vector<std::string> expected{"q.png",  "3",       "1000.0", "4.300",  "10.000",
                                          "",       "lattice", "1.5000", "2.0000", "1.2500",
                                          "2.0000", "2",       "1",      "1.0000", "2.0000",
                                          "90.000", "5",       "0.5000", ""};
  EXPECT_EQ(fields, expected);
}

TEST(LocalisationOutput, JsonHasLevelsBestPositionAndTruth) {
  const Json json = localisation_json(query());
  EXPECT_EQ(json["query"], "q.png");
  ASSERT_EQ(json["levels"].size(), 2u);
  EXPECT_EQ(json["levels"][0]["components"], 2);
  EXPECT_EQ(json["levels"][0]["compared"], 10);
  EXPECT_EQ(json["levels"][0]["candidates"][1]["place"], 5);
  EXPECT_DOUBLE_EQ(json["levels"][0]["candidates"][1]["similarity"].get<double>(), 250.0);
  EXPECT_DOUBLE_EQ(json["best"][0]["relative_heading_deg"].get<double>(), 10.0);
  EXPECT_TRUE(json["best"][0]["heading_deg"].is_null());
  EXPECT_EQ(json["position"]["frame"], "lattice");
  EXPECT_DOUBLE_EQ(json["position"]["interpolated_x"].get<double>(), 1.25);
  EXPECT_DOUBLE_EQ(json["position"]["between_x"].get<double>(), 1.125);
  EXPECT_EQ(json["truth"]["nearest_place"], 5);
  EXPECT_DOUBLE_EQ(json["truth"]["heading_deg"].get<double>(), 90.0);

  QueryLocalisation unscored = query();
  unscored.score.reset();
  EXPECT_TRUE(localisation_json(unscored)["truth"].is_null());
}

TEST(LocalisationOutput, TextNamesThePlaceThePositionAndTheError) {
  std::ostringstream text;
  write_localisation_text(text, query(), memory::VisualMemory());
  const std::string s = text.str();
  EXPECT_EQ(s.rfind("q.png: place 3 (similarity 1000, dissimilarity 4.3), heading +10.0 deg "
                    "from the place's\n",
                    0),
            0u)
      << s;
  EXPECT_NE(s.find("  position 1.50, 2.00 (the best place; from the lattice), between places "
                   "1.25, 2.00\n"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("  m=2: 2 candidates of 10 compared: 3 5\n"), std::string::npos) << s;
  EXPECT_NE(s.find("  m=15: 1 candidate of 2 compared: 3\n"), std::string::npos) << s;
  EXPECT_NE(s.find("nearest place 5, best place 0.50 m away\n"), std::string::npos) << s;

  QueryLocalisation unmatched = query();
  unmatched.no_match = "matches no place";
  std::ostringstream none;
  write_localisation_text(none, unmatched, memory::VisualMemory());
  EXPECT_EQ(none.str(), "q.png: matches no place\n");
}

}  // namespace
}  // namespace omninav::evaluation
