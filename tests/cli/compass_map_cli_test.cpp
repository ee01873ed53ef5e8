// `omninav compass --map`: a rendered route through the built-in room, its frames re-aligned on
// the places of a map explored from a rendered grid of the same room (headings from the truth),
// against the renderer's true headings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "command_line_test.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::cli {
namespace {

using CompassMap = CommandLineTest;

// The error_deg column of a compass CSV, and how many frames name a realigned_place.
struct Errors {
  std::vector<double> error_deg;
  int realigned = 0;
};

Errors read_errors(const std::filesystem::path& csv) {
  const CsvTable table = CsvTable::read(csv);
  const std::size_t error = table.require_column("error_deg");
  const std::optional<std::size_t> place = table.find_column("realigned_place");
  Errors errors;
  for (const CsvTable::Row& row : table.rows()) {
    errors.error_deg.push_back(parse_double(row.fields[error], "error_deg"));
    if (place && !row.fields[*place].empty()) ++errors.realigned;
  }
  return errors;
}

double max_abs(const std::vector<double>& values, std::size_t from) {
  double largest = 0.0;
  for (std::size_t i = from; i < values.size(); ++i)
    largest = std::max(largest, std::abs(values[i]));
  return largest;
}

TEST_F(CompassMap, RecognisedPlacesBoundTheHeadingErrorWhereTheCompassAloneDrifts) {
  // The map: a 7 x 7 grid at 30 cm over the built-in room's open floor (180 x 24 panoramas),
  // explored with the grid database's true headings.
  const std::filesystem::path grid = folder_ / "grid";
  ASSERT_EQ(run_omninav({"render", "--trajectory", "grid:x0=0.6,y0=1.7,nx=7,ny=7,spacing_m=0.3",
                         "--out", grid.string(), "--width", "180", "--height", "24"}),
            0)
      << errors_;
  const std::filesystem::path map = folder_ / "grid.vmem";
  ASSERT_EQ(run_omninav({"explore", "--input", grid.string(), "--out", map.string()}), 0)
      << errors_;
  // The route: two turns of docs/compass.md's CIRCLE (radius 0.9 m) at 5 frames/s, over the
  // grid's floor; parallax over the hops drifts the compass alone.
  const std::filesystem::path circle = folder_ / "circle";
  ASSERT_EQ(run_omninav({"render", "--trajectory",
                         "circle:cx=1.5,cy=2.6,radius_m=0.9,turns=2,speed_m_s=0.2,fps=5", "--out",
                         circle.string(), "--width", "180", "--height", "24"}),
            0)
      << errors_;
  const std::filesystem::path alone = folder_ / "alone.csv";
  ASSERT_EQ(
      run_omninav({"compass", "--input", circle.string(), "--truth", "--out", alone.string()}), 0)
      << errors_;
  const std::filesystem::path with_map = folder_ / "map.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", circle.string(), "--truth", "--map", map.string(),
                         "--out", with_map.string()}),
            0)
      << errors_;
  const Errors without = read_errors(alone);
  const Errors with = read_errors(with_map);
  ASSERT_EQ(with.error_deg.size(), without.error_deg.size());
  const std::size_t last_half = with.error_deg.size() / 2;
  // The route is one where the compass alone drifts (measured 4.6° max, 180 columns), so that
  // the bound below says something.
  ASSERT_GT(max_abs(without.error_deg, 0), 3.0);
  // Re-aligned on the places it recognises (the route crosses the map; measured: 185 of 283
  // frames), the heading stays within what the phases measure between a place and a view
  // (measured 1.7°), and does not grow over the second turn.
  EXPECT_GT(with.realigned, static_cast<int>(with.error_deg.size()) / 2);
  EXPECT_LT(max_abs(with.error_deg, 0), 2.0);
  EXPECT_LT(max_abs(with.error_deg, last_half), 0.5 * max_abs(without.error_deg, last_half));
  // Without --map the CSV has no realigned_place column; a missing map is an input error.
  EXPECT_EQ(without.realigned, 0);
  EXPECT_EQ(CsvTable::read(alone).find_column("realigned_place"), std::nullopt);
  EXPECT_EQ(run_omninav({"compass", "--input", circle.string(), "--map",
                         (folder_ / "nowhere.vmem").string(), "--out", "-"}),
            1);
  EXPECT_NE(errors_.find("nowhere.vmem"), std::string::npos) << errors_;
}

}  // namespace
}  // namespace omninav::cli
