#pragma once
// A table of scores as a picture that reads at a glance (`omninav evaluate`'s evaluation.png):
// a row per world, the columns grouped under their stage's name, each header written
// horizontally with its unit and target, each cell coloured against its measure's target
// (green meets it, amber misses it within a margin, red misses it, grey when the measure has
// none), and a key of the colours under the table.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace omninav::report {

// One cell: a value, or not applicable (a world without rooms has no "right room"), or failed
// (the stage that measures it threw).
struct Cell {
  enum class State { kValue, kNotApplicable, kFailed };
  State state = State::kNotApplicable;
  double value = 0.0;

  static Cell of(double v) { return {State::kValue, v}; }
  static Cell not_applicable() { return {State::kNotApplicable, 0.0}; }
  static Cell failed() { return {State::kFailed, 0.0}; }
  bool has_value() const { return state == State::kValue; }
};

// A cell as written in a table: the value with `decimals`, "-" when not applicable, "failed".
std::string cell_text(const Cell& cell, int decimals);

// What a measure should reach: a value at most, at least, or of magnitude at most `limit`;
// up to `margin` past the limit is "near".
struct Target {
  enum class Kind { kAtMost, kAtLeast, kAbsAtMost };
  Kind kind = Kind::kAtMost;
  double limit = 0.0;
  double margin = 0.0;
};

enum class Verdict { kMeets, kNear, kMisses, kNoTarget };

// How `value` stands against `target` (kNoTarget without one).
Verdict verdict(const std::optional<Target>& target, double value);

// The fill of a cell with a value of that verdict (BGR).
cv::Scalar verdict_colour(Verdict verdict);

// The target as a header line, e.g. "<= 5", ">= 0.95", "|x| <= 0.5".
std::string target_text(const Target& target);

struct ScoreColumn {
  std::string group;  // the stage: consecutive columns of a group form one block
  std::string title;  // the header, wrapped at blanks
  std::string unit;   // written under the title
  int decimals = 2;
  std::optional<Target> target;
};

struct ScoreRow {
  std::string label;
  std::vector<Cell> cells;  // one per column
};

struct ScoreTable {
  std::string title;
  std::vector<ScoreColumn> columns;
  std::vector<ScoreRow> rows;
};

// Where everything goes: one block per group, stacked, each with the group's name, the headers
// and a line per row; the key under the last block.
struct ScoreTableLayout {
  cv::Size size;
  int label_width = 0;                      // the rows' labels, left of every block
  int header_lines = 0;                     // text lines of the tallest header
  std::vector<int> block_top;               // per group block, its name's top
  std::vector<std::vector<cv::Rect>> cell;  // [row][column]
  std::vector<cv::Rect> header;             // per column
  int key_top = 0;
};

// Throws UsageError when a row's cell count differs from the columns'.
ScoreTableLayout score_table_layout(const ScoreTable& table);

cv::Mat score_table_picture(const ScoreTable& table);

}  // namespace omninav::report
