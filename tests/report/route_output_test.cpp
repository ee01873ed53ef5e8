// The route's text, CSV and JSON against a hand-built route.
#include "omninav/report/route_output.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "support/csv_text.hpp"

namespace omninav::report {
namespace {

// Three places: 4 -> 7 -> 2, the last the goal; the first turned 30° from the robot.
Route three_place_route() {
  Route route;
  route.map = "room.vmem";
  route.from_image = "now.png";
  route.to_image = "goal.png";
  route.from.place = 4;
  route.from.dissimilarity_per_value = 1.234;
  route.from.relative_heading_rad = 0.5;
  route.to.place = 2;
  route.to.dissimilarity_per_value = 0.5;
  route.steps = {{4, {1.0, 2.0}, 2.5, 90.0, 45.0, Eigen::Vector2d(3.0, 4.0)},
                 {7, {1.0, 3.0}, 1.25, 0.0, -10.0, std::nullopt},
                 {2, {2.25, 3.0}, 0.0, std::nullopt, std::nullopt, std::nullopt}};
  route.turn_deg = 30.0;
  return route;
}

TEST(RouteOutput, CsvHasOneRowPerPlaceWithTheTurnOnTheFirst) {
  std::ostringstream csv;
  write_route_csv(csv, three_place_route());
  const auto rows = testing::csv_text_rows(csv.str());
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"step", "place", "lattice_x", "lattice_y", "cost",
                                               "direction_deg", "direction_in_place_deg",
                                               "turn_from_robot_deg", "truth_x_m", "truth_y_m"}));
  EXPECT_EQ(rows[1], (std::vector<std::string>{"0", "4", "1.0000", "2.0000", "2.5000", "90.000",
                                               "45.000", "30.000", "3.0000", "4.0000"}));
  EXPECT_EQ(rows[2][1], "7");
  EXPECT_EQ(rows[2][6], "-10.000");
  EXPECT_EQ(rows[2][7], "");  // the turn is the start's only
  EXPECT_EQ(rows[2][8], "");  // no truth
  EXPECT_EQ(rows[3][5], "");  // the goal has no direction
  EXPECT_EQ(rows[3][2], "2.2500");
}

TEST(RouteOutput, JsonCarriesTheMatchesAndEveryPlace) {
  const Json json = route_json(three_place_route());
  EXPECT_EQ(json["map"], "room.vmem");
  EXPECT_EQ(json["from"]["image"], "now.png");
  EXPECT_EQ(json["from"]["place"], 4);
  EXPECT_NEAR(json["from"]["heading_in_place_deg"].get<double>(), 28.6479, 1e-4);
  EXPECT_EQ(json["to"]["place"], 2);
  EXPECT_DOUBLE_EQ(json["length"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(json["turn_from_robot_deg"].get<double>(), 30.0);
  ASSERT_EQ(json["route"].size(), 3u);
  EXPECT_DOUBLE_EQ(json["route"][0]["truth_y_m"].get<double>(), 4.0);
  EXPECT_FALSE(json["route"][1].contains("truth_x_m"));
  EXPECT_FALSE(json["route"][2].contains("direction_deg"));
  EXPECT_DOUBLE_EQ(json["route"][2]["lattice_x"].get<double>(), 2.25);
}

TEST(RouteOutput, TextNamesTheImagesTheTurnAndTheGoal) {
  std::ostringstream text;
  write_route_text(text, three_place_route());
  const std::string s = text.str();
  EXPECT_NE(s.find("route from now.png (place 4, dissimilarity 1.23 per value) to goal.png "
                   "(place 2, 0.50): 3 places, 2.50 lattice units\n"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("now: turn +30.0 deg"), std::string::npos) << s;
  EXPECT_NE(s.find("(truth 3.00, 4.00 m)"), std::string::npos) << s;
  EXPECT_NE(s.find("     goal\n"), std::string::npos) << s;

  Route arrived = three_place_route();
  arrived.turn_deg.reset();
  std::ostringstream again;
  write_route_text(again, arrived);
  EXPECT_NE(again.str().find("already matches the goal's place"), std::string::npos);
}

}  // namespace
}  // namespace omninav::report
