// omninav evaluate end to end on a small suite: the table has every column, with a finite value
// for every world (or "not applicable" only where docs/evaluation.md says a measure can be),
// the worst rows name real rows, the commands it prints remake its figures, and two runs give
// the same table.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <set>

#include "command_line_test.hpp"
#include "omninav/evaluation/table.hpp"

namespace omninav::cli {
namespace {

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A suite small enough for CI: every stage runs, on few and small panoramas.
constexpr const char* kSuite = R"(name: test
panorama: {width_px: 96, height_px: 14}
compass: {fps: 5, rotate_turns: 1, rotate_rate_deg_s: 90, circle_radius_m: 0.6, wander_length_m: 1.5}
memory: {grid_nx: 6, grid_ny: 5, queries: 12}
navigation: {trials: 3}
worlds:
  - {name: room, world: room}
)";

// Measures that may be "not applicable": right room outside worlds with rooms, an interior
// RMSE when no place of the lattice is interior, a path ratio when no trial reached its goal.
bool may_be_empty(const std::string& key) {
  return key == "memory_right_room" || key.ends_with("_rmse_interior") ||
         key == "navigation_path_ratio" || key == "navigation_driven_path_ratio";
}

class EvaluateCommand : public CommandLineTest {
 protected:
  std::filesystem::path write_suite(const std::string& text) {
    const std::filesystem::path file = folder_ / "suite.yaml";
    std::ofstream(file) << text;
    return file;
  }
};

TEST_F(EvaluateCommand, WritesATableWithEveryMeasureForEveryWorldTheSameTwice) {
  const std::filesystem::path suite = write_suite(kSuite);
  ASSERT_EQ(run_omninav({"evaluate", "--suite", suite.string(), "--out", (folder_ / "a").string()}),
            0)
      << errors_;
  const std::string printed = output_;
  const std::string csv = read_file(folder_ / "a" / "evaluation.csv");
  const std::vector<std::vector<std::string>> rows = csv_rows(csv);

  const std::vector<evaluation::Measure>& measures = evaluation::measures();
  ASSERT_EQ(rows.size(), 1u + 1u);  // header, one world
  const std::vector<std::vector<std::string>> worst =
      csv_rows(read_file(folder_ / "a" / "evaluation_worst.csv"));
  ASSERT_EQ(worst.size(), 1u + 3u);  // header, family, world, value
  ASSERT_EQ(worst[0].size(), 1 + measures.size());
  EXPECT_EQ(worst[1][0], "family");
  EXPECT_EQ(worst[2][0], "world");
  EXPECT_EQ(worst[3][0], "value");
  ASSERT_EQ(rows[0].size(), 2 + measures.size());
  EXPECT_EQ(rows[0][0], "world");
  EXPECT_EQ(rows[0][1], "family");
  for (std::size_t c = 0; c < measures.size(); ++c) EXPECT_EQ(rows[0][2 + c], measures[c].key);
  const std::vector<std::string>& room = rows[1];
  EXPECT_EQ(room[0], "room");
  for (std::size_t c = 0; c < measures.size(); ++c) {
    const std::string& cell = room[2 + c];
    EXPECT_EQ(worst[1 + 2][1 + c], cell) << measures[c].key;  // the only row is the worst
    if (cell.empty() && may_be_empty(measures[c].key)) continue;
    ASSERT_FALSE(cell.empty()) << measures[c].key << "\n" << printed;
    EXPECT_TRUE(std::isfinite(parse_double(cell, measures[c].key))) << measures[c].key;
    EXPECT_EQ(worst[1][1 + c], "room") << measures[c].key;
    EXPECT_EQ(worst[2][1 + c], "room") << measures[c].key;
  }
  // Shares are shares.
  for (const std::string key :
       {"memory_within_spacing", "memory_at_nearest", "navigation_reached"}) {
    const auto at = std::find(rows[0].begin(), rows[0].end(), key) - rows[0].begin();
    const double share = parse_double(room[at], key);
    EXPECT_GE(share, 0.0);
    EXPECT_LE(share, 1.0);
  }
  EXPECT_NE(printed.find("WORST"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(folder_ / "a" / "evaluation.png"));
  // The driven map's commands: the tour rendered with odometry, explored by it, navigated.
  const std::string script = read_file(folder_ / "a" / "commands.sh");
  EXPECT_NE(script.find("--trajectory tour:"), std::string::npos) << script;
  EXPECT_NE(script.find("odometry_noise="), std::string::npos) << script;
  EXPECT_NE(script.find("--odometry"), std::string::npos) << script;
  EXPECT_NE(script.find("driven.vmem --world"), std::string::npos) << script;
  EXPECT_NE(script.find("--goal-radius-m 0.3"), std::string::npos) << script;

  // Deterministic: the same suite gives the same table.
  ASSERT_EQ(run_omninav({"evaluate", "--suite", suite.string(), "--out", (folder_ / "b").string()}),
            0)
      << errors_;
  EXPECT_EQ(read_file(folder_ / "b" / "evaluation.csv"), csv);
  EXPECT_EQ(read_file(folder_ / "b" / "evaluation_worst.csv"),
            read_file(folder_ / "a" / "evaluation_worst.csv"));
}

TEST_F(EvaluateCommand, TheCommandsItWritesRemakeItsFigures) {
  const std::filesystem::path suite = write_suite(kSuite);
  const std::filesystem::path out = folder_ / "a";
  ASSERT_EQ(run_omninav({"evaluate", "--suite", suite.string(), "--out", out.string()}), 0)
      << errors_;
  const std::vector<std::vector<std::string>> table = csv_rows(read_file(out / "evaluation.csv"));
  const auto value = [&](const std::string& key) {
    const auto at = std::find(table[0].begin(), table[0].end(), key) - table[0].begin();
    return parse_double(table[1][at], key);
  };
  // Run the circle's render and compass commands from commands.sh again, into other files.
  const std::string script = read_file(out / "commands.sh");
  std::vector<std::vector<std::string>> circle;
  std::istringstream lines(script);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("/circle") == std::string::npos || line.rfind("omninav ", 0) != 0) continue;
    std::vector<std::string> args;
    std::istringstream words(line.substr(8));
    for (std::string word; words >> word;) args.push_back(word);  // the paths have no blanks
    circle.push_back(args);
  }
  ASSERT_EQ(circle.size(), 2u) << script;
  ASSERT_EQ(circle[0][2], "render");
  ASSERT_EQ(circle[1][2], "compass");
  const std::filesystem::path again = folder_ / "circle_again";
  for (std::string& arg : circle[0]) {
    if (arg == (out / "room" / "circle").string()) arg = again.string();
  }
  std::vector<std::string> compass = {
      circle[1][0],   circle[1][1], "compass", "--input",
      again.string(), "--truth",    "--stats", (folder_ / "stats.csv").string()};
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const int rendered = run(circle[0]);
  const int status = run(compass);
  ::testing::internal::GetCapturedStdout();
  ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(rendered, 0);
  ASSERT_EQ(status, 0);
  const std::vector<std::vector<std::string>> stats = csv_rows(read_file(folder_ / "stats.csv"));
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_NEAR(parse_double(stats[1][5], "max"), value("compass_circle_max_deg"), 1e-3);
  EXPECT_NEAR(parse_double(stats[1][6], "mean"), value("compass_circle_mean_deg"), 1e-3);
  EXPECT_NEAR(parse_double(stats[1][10], "final"), value("compass_circle_end_deg"), 1e-3);
}

// The quick suite, as CI runs it: one world per family, every measure for every world. The OBJ
// world needs shared/data; without it that row is empty and evaluation_worst.csv says it failed
// (and nothing else may fail).
TEST_F(EvaluateCommand, TheQuickSuiteMeasuresEveryWorld) {
  ASSERT_EQ(run_omninav({"evaluate", "--suite", "quick", "--out", (folder_ / "quick").string()}), 0)
      << errors_;
  const std::vector<std::vector<std::string>> rows =
      csv_rows(read_file(folder_ / "quick" / "evaluation.csv"));
  const std::vector<evaluation::Measure>& measures = evaluation::measures();
  const std::vector<std::vector<std::string>> worst =
      csv_rows(read_file(folder_ / "quick" / "evaluation_worst.csv"));
  ASSERT_GE(rows.size(), 2u);
  ASSERT_EQ(worst.size(), 4u);
  // Every measure's cell is a number or empty, so that a CSV reader types them as numbers.
  for (std::size_t r = 1; r < rows.size(); ++r) {
    for (std::size_t c = 2; c < rows[r].size(); ++c) {
      const std::string& cell = rows[r][c];
      if (!cell.empty()) {
        EXPECT_TRUE(std::isfinite(parse_double(cell, rows[0][c]))) << cell;
      }
    }
  }
  const bool have_obj = std::filesystem::exists(omninav::testing::shared_data_dir() / "worlds");
  std::set<std::string> families;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const std::vector<std::string>& row = rows[r];
    ASSERT_EQ(row.size(), 2 + measures.size());
    families.insert(row[1]);
    if (row[1] == "obj" && !have_obj) {
      // Its cells are empty, and as the first failed row it is every column's worst.
      EXPECT_EQ(row[2], "");
      EXPECT_EQ(worst[2][1], row[0]);
      EXPECT_EQ(worst[3][1], "failed");
      continue;
    }
    for (std::size_t c = 0; c < measures.size(); ++c) {
      const std::string& cell = row[2 + c];
      const std::string& key = measures[c].key;
      if (key == "memory_right_room") {
        // Exactly the worlds with rooms have it.
        EXPECT_EQ(cell.empty(), row[1] != "house") << row[0];
        continue;
      }
      if (cell.empty() && may_be_empty(key)) continue;
      ASSERT_FALSE(cell.empty()) << row[0] << " " << key << "\n" << output_;
      EXPECT_TRUE(std::isfinite(parse_double(cell, key))) << row[0] << " " << key;
    }
  }
  EXPECT_EQ(families, (std::set<std::string>{"room", "house", "field", "office", "obj"}));
}

TEST_F(EvaluateCommand, WorldsThatCannotBeLoadedFailTheRunAndSayWhy) {
  const std::filesystem::path fifo = folder_ / "world.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);  // read, it would block forever
  std::ofstream(folder_ / "broken.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
  const std::filesystem::path suite = write_suite(std::string(kSuite).replace(
      std::string(kSuite).find("worlds:"), std::string::npos,
      "worlds:\n  - {name: zero, world: /dev/zero.obj}\n  - {name: device, world: "
      "/dev/zero}\n  - {name: fifo, world: " +
          fifo.string() + "}\n  - {name: broken, world: " + (folder_ / "broken.obj").string() +
          "}\n"));
  EXPECT_EQ(
      run_omninav({"evaluate", "--suite", suite.string(), "--out", (folder_ / "out").string()}), 1);
  EXPECT_NE(errors_.find("4 of 4 worlds could not be evaluated"), std::string::npos) << errors_;
  EXPECT_NE(errors_.find("/dev/zero: is a device, not an OBJ file"), std::string::npos) << errors_;
  EXPECT_NE(errors_.find("world.obj: is a FIFO, not an OBJ file"), std::string::npos) << errors_;
  EXPECT_NE(errors_.find("broken.obj:3: vertex coordinate 'nan' is not a finite number"),
            std::string::npos)
      << errors_;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "out" / "evaluation.csv")) << "the table is kept";
}

TEST_F(EvaluateCommand, AnUnknownSuiteIsAUsageError) {
  EXPECT_EQ(run_omninav({"evaluate", "--suite", "no_such_suite"}), 2);
  EXPECT_NE(errors_.find("no_such_suite"), std::string::npos);
}

}  // namespace
}  // namespace omninav::cli
