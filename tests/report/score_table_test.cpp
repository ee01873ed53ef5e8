// The picture of a score table (evaluation.png): its shape, and each cell coloured against its
// column's target rather than by rank.
#include "omninav/report/score_table.hpp"

#include <gtest/gtest.h>

#include "omninav/core/errors.hpp"

namespace omninav::report {
namespace {

const Target kAtMost5{Target::Kind::kAtMost, 5.0, 2.5};
const Target kAtLeast95{Target::Kind::kAtLeast, 0.95, 0.1};

// Two worlds, two stages of two measures each; b misses both targets, a meets them.
ScoreTable two_worlds() {
  ScoreTable table;
  table.title = "test";
  table.columns = {{"compass", "circle max |e|", "deg", 1, kAtMost5},
                   {"compass", "in 1 sd", "share", 2, std::nullopt},
                   {"navigation", "goals reached", "share", 3, kAtLeast95},
                   {"navigation", "outside map", "m", 2, std::nullopt}};
  table.rows = {{"a", {Cell::of(2.0), Cell::of(0.6), Cell::of(1.0), Cell::not_applicable()}},
                {"b", {Cell::of(32.1), Cell::of(0.4), Cell::of(0.17), Cell::failed()}}};
  return table;
}

cv::Scalar centre_colour(const cv::Mat& picture, const cv::Rect& cell) {
  const cv::Vec3b bgr = picture.at<cv::Vec3b>(cell.y + cell.height / 2, cell.x + cell.width / 2);
  return {double(bgr[0]), double(bgr[1]), double(bgr[2])};
}

TEST(ScoreTable, AValueStandsAgainstItsTargetInTheTargetsDirection) {
  EXPECT_EQ(verdict(kAtMost5, 5.0), Verdict::kMeets);
  EXPECT_EQ(verdict(kAtMost5, 7.0), Verdict::kNear);
  EXPECT_EQ(verdict(kAtMost5, 8.0), Verdict::kMisses);
  EXPECT_EQ(verdict(kAtLeast95, 0.97), Verdict::kMeets);
  EXPECT_EQ(verdict(kAtLeast95, 0.90), Verdict::kNear);
  EXPECT_EQ(verdict(kAtLeast95, 0.17), Verdict::kMisses);
  const Target abs{Target::Kind::kAbsAtMost, 0.5, 0.25};
  EXPECT_EQ(verdict(abs, -0.4), Verdict::kMeets);
  EXPECT_EQ(verdict(abs, -0.9), Verdict::kMisses);
  EXPECT_EQ(verdict(std::nullopt, 1e9), Verdict::kNoTarget);
  EXPECT_EQ(target_text(kAtLeast95), "target >= 0.95");
  EXPECT_EQ(target_text(kAtMost5), "target <= 5");
}

TEST(ScoreTable, TheStagesAreStackedSoThePictureIsNoStrip) {
  const ScoreTable table = two_worlds();
  const ScoreTableLayout layout = score_table_layout(table);
  const cv::Mat picture = score_table_picture(table);
  ASSERT_EQ(picture.type(), CV_8UC3);
  EXPECT_EQ(picture.size(), layout.size);
  EXPECT_LT(picture.cols, 3 * picture.rows) << picture.size();
  EXPECT_GT(picture.rows, 100);
  // The navigation block is under the compass block, its headers horizontal over the cells.
  ASSERT_EQ(layout.block_top.size(), 2u);
  EXPECT_GT(layout.cell[0][2].y, layout.cell[1][0].y);
  EXPECT_EQ(layout.cell[0][2].x, layout.cell[0][0].x);
  EXPECT_GT(layout.header[0].width, layout.header[0].height / 2);
  EXPECT_GE(layout.header_lines, 3);  // title, unit, target
}

TEST(ScoreTable, EachCellIsColouredAgainstItsTargetNotByRank) {
  const ScoreTable table = two_worlds();
  const ScoreTableLayout layout = score_table_layout(table);
  const cv::Mat picture = score_table_picture(table);
  const cv::Scalar meets = verdict_colour(Verdict::kMeets);
  const cv::Scalar misses = verdict_colour(Verdict::kMisses);
  const cv::Scalar none = verdict_colour(Verdict::kNoTarget);
  EXPECT_EQ(centre_colour(picture, layout.cell[0][0]), meets);   // 2 deg <= 5
  EXPECT_EQ(centre_colour(picture, layout.cell[1][0]), misses);  // 32.1 deg
  EXPECT_EQ(centre_colour(picture, layout.cell[0][2]), meets);   // every goal reached
  EXPECT_EQ(centre_colour(picture, layout.cell[1][2]), misses);  // 0.17 of them
  EXPECT_EQ(centre_colour(picture, layout.cell[0][1]), none);    // no target
  EXPECT_EQ(centre_colour(picture, layout.cell[1][1]), none);
  EXPECT_NE(centre_colour(picture, layout.cell[1][3]), none);  // failed
  EXPECT_NE(centre_colour(picture, layout.cell[1][3]), centre_colour(picture, layout.cell[0][3]));

  // One world alone that misses is still red: nothing is ranked.
  ScoreTable alone = table;
  alone.rows.erase(alone.rows.begin());
  const ScoreTableLayout alone_layout = score_table_layout(alone);
  EXPECT_EQ(centre_colour(score_table_picture(alone), alone_layout.cell[0][2]), misses);
}

TEST(ScoreTable, RowsOfTheWrongWidthAreRejected) {
  ScoreTable table = two_worlds();
  table.rows[1].cells.pop_back();
  EXPECT_THROW(score_table_layout(table), UsageError);
}

}  // namespace
}  // namespace omninav::report
