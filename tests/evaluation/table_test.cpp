// The table of omninav evaluate: the worst row per column in each measure's direction, the CSV
// and the printed table, on constructed rows.
#include "omninav/evaluation/table.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "omninav/core/errors.hpp"

namespace omninav::evaluation {
namespace {

const std::vector<Measure> kColumns = {
    {"error_deg", "compass", "err", Worse::kHigher, 1},
    {"share", "memory", "share", Worse::kLower, 3},
    {"mean_deg", "compass", "mean", Worse::kAbsHigher, 1},
    {"room", "memory", "room", Worse::kLower, 3},
};

Row row(const std::string& world, const std::string& family, std::vector<Cell> cells) {
  return {world, family, std::move(cells), {}};
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

TEST(EvaluationTable, TheCsvHasAColumnPerMeasureAndTheWorstFamilies) {
  std::vector<Row> rows = constructed_rows();
  rows[3].cells[0] = Cell::failed();
  std::istringstream csv(table_csv(rows, kColumns));
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), rows.size() + 3);
  EXPECT_EQ(lines[0], "world,family,error_deg,share,mean_deg,room");
  EXPECT_EQ(lines[1], "a,room,2.000,0.90000,-1.000,");
  EXPECT_EQ(lines[4], "d,office,failed,0.99000,5.000,");
  EXPECT_EQ(lines[5], "worst_family,,office,house,house,house");
  EXPECT_EQ(lines[6], "worst_world,,d,c,c,c");
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

TEST(EvaluationTable, ThePictureHasACellPerWorldAndMeasure) {
  const cv::Mat picture = table_picture(constructed_rows(), kColumns, "test");
  ASSERT_FALSE(picture.empty());
  EXPECT_EQ(picture.type(), CV_8UC3);
  EXPECT_GT(picture.cols, 74 * static_cast<int>(kColumns.size()));
  EXPECT_GT(picture.rows, 24 * 5);
}

TEST(EvaluationTable, EveryMeasureHasAUniqueKeyAndAKnownGroup) {
  std::set<std::string> keys;
  for (const Measure& m : measures()) {
    EXPECT_TRUE(keys.insert(m.key).second) << m.key;
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
            12u + 2u + 6u + 12u + 4u + 1u + 4u + 4u);  // memory: 4 + home vectors
}

}  // namespace
}  // namespace omninav::evaluation
