// The table of omninav evaluate: the worst row per column in each measure's direction, the CSV
// and the printed table, on constructed rows.
#include "omninav/evaluation/table.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "omninav/core/errors.hpp"

namespace omninav::evaluation {
namespace {

const std::vector<Measure> kColumns = {
    {"error_deg", "compass", "err", Worse::kHigher, 1, "deg", std::nullopt},
    {"share", "memory", "share", Worse::kLower, 3, "share", std::nullopt},
    {"mean_deg", "compass", "mean", Worse::kAbsHigher, 1, "deg", std::nullopt},
    {"room", "memory", "room", Worse::kLower, 3, "share", std::nullopt},
};

Row row(const std::string& world, const std::string& family, std::vector<Cell> cells) {
  return {world, family, std::move(cells), {}};
}

// The first two columns, the first with a target.
std::vector<Measure> measures_of_two() {
  std::vector<Measure> two(kColumns.begin(), kColumns.begin() + 2);
  two[0].target = report::Target{report::Target::Kind::kAtMost, 5.0, 2.5};
  return two;
}

std::vector<Row> constructed_rows() {
  return {
      row("a", "room", {Cell::of(2.0), Cell::of(0.9), Cell::of(-1.0), Cell::not_applicable()}),
      row("b", "field", {Cell::of(7.5), Cell::of(0.95), Cell::of(0.5), Cell::not_applicable()}),
      row("c", "house", {Cell::of(3.0), Cell::of(0.4), Cell::of(-6.0), Cell::of(0.8)}),
      row("d", "office", {Cell::of(1.0), Cell::of(0.99), Cell::of(5.0), Cell::not_applicable()}),
  };
}

TEST(EvaluationTable, TheWorstRowIsWorstInEachMeasuresDirection) {
  const std::vector<int> worst = worst_rows(constructed_rows(), kColumns);
  ASSERT_EQ(worst.size(), kColumns.size());
  EXPECT_EQ(worst[0], 1);  // the highest error: b, 7.5
  EXPECT_EQ(worst[1], 2);  // the lowest share: c, 0.4
  EXPECT_EQ(worst[2], 2);  // the farthest from 0: c, -6 (not d, +5)
  EXPECT_EQ(worst[3], 2);  // the only row with a value; not-applicable cells are never worst
}

TEST(EvaluationTable, AFailedCellIsWorseThanAnyValue) {
  std::vector<Row> rows = constructed_rows();
  rows[3].cells[0] = Cell::failed();
  rows[0].cells[1] = Cell::failed();
  const std::vector<int> worst = worst_rows(rows, kColumns);
  EXPECT_EQ(worst[0], 3);
  EXPECT_EQ(worst[1], 0);
}

TEST(EvaluationTable, AColumnWithoutValuesHasNoWorstRow) {
  std::vector<Row> rows = constructed_rows();
  rows[2].cells[3] = Cell::not_applicable();
  EXPECT_EQ(worst_rows(rows, kColumns)[3], -1);
}

TEST(EvaluationTable, RowsOfTheWrongWidthAreRejected) {
  std::vector<Row> rows = constructed_rows();
  rows[1].cells.pop_back();
  EXPECT_THROW(worst_rows(rows, kColumns), UsageError);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(EvaluationTable, TheCsvHasAColumnPerMeasureAndOnlyNumbersInThem) {
  std::vector<Row> rows = constructed_rows();
  rows[3].cells[0] = Cell::failed();
  const std::vector<std::string> lines = lines_of(table_csv(rows, kColumns));
  ASSERT_EQ(lines.size(), rows.size() + 1);  // no worst lines among the worlds
  EXPECT_EQ(lines[0], "world,family,error_deg,share,mean_deg,room");
  EXPECT_EQ(lines[1], "a,room,2.000,0.90000,-1.000,");
  EXPECT_EQ(lines[3], "c,house,3.000,0.40000,-6.000,0.80000");
  EXPECT_EQ(lines[4], "d,office,,0.99000,5.000,");  // failed: empty, the notes say why
}

TEST(EvaluationTable, TheWorstCsvNamesEachColumnsWorstRowAndItsValue) {
  std::vector<Row> rows = constructed_rows();
  rows[3].cells[0] = Cell::failed();
  rows[2].cells[3] = Cell::not_applicable();
  const std::vector<std::string> lines = lines_of(worst_csv(rows, kColumns));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "worst,error_deg,share,mean_deg,room");
  EXPECT_EQ(lines[1], "family,office,house,house,");
  EXPECT_EQ(lines[2], "world,d,c,c,");
  EXPECT_EQ(lines[3], "value,failed,0.40000,-6.000,");
}

TEST(EvaluationTable, ThePrintedTableEndsEachGroupWithTheWorstFamily) {
  const std::string text = table_text(constructed_rows(), kColumns);
  // Groups in order of first appearance, each with its header, its rows and WORST.
  const std::size_t compass = text.find("compass\n");
  const std::size_t memory = text.find("memory\n");
  ASSERT_NE(compass, std::string::npos);
  ASSERT_NE(memory, std::string::npos);
  EXPECT_LT(compass, memory);
  const std::string compass_block = text.substr(compass, memory - compass);
  EXPECT_NE(compass_block.find("err"), std::string::npos);
  EXPECT_NE(compass_block.find("mean"), std::string::npos);
  EXPECT_EQ(compass_block.find("share"), std::string::npos);
  const std::size_t worst = compass_block.find("WORST");
  ASSERT_NE(worst, std::string::npos);
  std::istringstream cells(compass_block.substr(worst));
  std::string label, error_family, mean_family;
  cells >> label >> error_family >> mean_family;
  EXPECT_EQ(error_family, "field");
  EXPECT_EQ(mean_family, "house");
}

TEST(EvaluationTable, ThePicturesTableHasTheMeasuresUnitsAndTargets) {
  std::vector<Row> rows = constructed_rows();
  for (Row& row : rows) row.cells.resize(2);
  const report::ScoreTable table = score_table(rows, measures_of_two(), "test");
  ASSERT_EQ(table.columns.size(), 2u);
  EXPECT_EQ(table.columns[0].unit, "deg");
  ASSERT_TRUE(table.columns[0].target.has_value());
  EXPECT_EQ(table.columns[0].target->limit, 5.0);
  EXPECT_FALSE(table.columns[1].target.has_value());
  ASSERT_EQ(table.rows.size(), 4u);
  EXPECT_EQ(table.rows[2].label, "c");
  EXPECT_EQ(table.rows[2].cells[0].value, 3.0);
}

TEST(EvaluationTable, EveryMeasureHasAUniqueKeyAndAKnownGroup) {
  std::set<std::string> keys;
  for (const Measure& m : measures()) {
    EXPECT_TRUE(keys.insert(m.key).second) << m.key;
    EXPECT_FALSE(m.unit.empty()) << m.key;
    EXPECT_TRUE(m.group == "compass" || m.group == "memory" || m.group == "lattice" ||
                m.group == "navigation" || m.group == "driven")
        << m.key;
    if (m.group == "driven") {
      // The driven map's block: its tour's coverage, then its lattice and navigation measures
      // named as the grid map's are.
      EXPECT_TRUE(m.key == "tour_coverage" || m.key.rfind("lattice_driven_", 0) == 0 ||
                  m.key.rfind("navigation_driven_", 0) == 0)
          << m.key;
    } else {
      EXPECT_EQ(m.key.rfind(m.group + "_", 0), 0u) << m.key;
    }
  }
  EXPECT_EQ(measures().size(),
            15u + 2u + 6u + 12u + 4u + 1u + 4u + 4u);  // memory: 4 + home vectors
}

}  // namespace
}  // namespace omninav::evaluation
