#pragma once
// The table of `omninav evaluate`: a row per world, a column per measure, and the worst world
// of each column, worst meaning the direction that is bad for that measure.

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace omninav::evaluation {

// Which way a measure gets worse.
enum class Worse {
  kHigher,     // errors, folds, distances outside the map
  kLower,      // shares of successes
  kAbsHigher,  // signed errors: farther from 0 is worse
};

struct Measure {
  std::string key;    // CSV column, e.g. "compass_rotate_max_deg"
  std::string group;  // compass, memory, lattice, navigation, driven (the driven map's block)
  std::string title;  // short header of the printed table
  Worse worse = Worse::kHigher;
  int decimals = 2;
};

// The measures of evaluate, in column order (docs/evaluation.md defines each).
const std::vector<Measure>& measures();

// One cell: a value, or not applicable (a world without rooms has no "right room"; a path ratio
// needs a trial that reached its goal), or failed (the stage threw; the reason is in the row's
// notes). A failed cell is worse than any value.
struct Cell {
  enum class State { kValue, kNotApplicable, kFailed };
  State state = State::kNotApplicable;
  double value = 0.0;

  static Cell of(double v) { return {State::kValue, v}; }
  static Cell not_applicable() { return {State::kNotApplicable, 0.0}; }
  static Cell failed() { return {State::kFailed, 0.0}; }
  bool has_value() const { return state == State::kValue; }
};

struct Row {
  std::string world;               // the row's label
  std::string family;              // its family
  std::vector<Cell> cells;         // one per measure, in measures() order
  std::vector<std::string> notes;  // why a cell failed, and other warnings
};

// The worst row of each column: its index into `rows`, or -1 when no row has a value or fails
// there. Failed cells are worst; among values, the worst in the measure's direction (ties: the
// first row). Throws UsageError when a row's cell count differs from the measures'.
std::vector<int> worst_rows(const std::vector<Row>& rows, const std::vector<Measure>& columns);

// The CSV: header "world,family,<keys>", a line per row (values with the measure's decimals
// + 2, empty when not applicable, "failed"), then "worst_family" (the family of each column's
// worst row) and "worst_world" lines.
std::string table_csv(const std::vector<Row>& rows, const std::vector<Measure>& columns);

// The printed table, one block per group (compass, memory, lattice, navigation) so that it
// fits a terminal: rows as worlds, a column per measure, and a last line WORST with the worst
// family per column.
std::string table_text(const std::vector<Row>& rows, const std::vector<Measure>& columns);

// A heat-table picture: each cell coloured from good (green) to bad (red) by its rank within
// the column in the measure's direction, with its value written in it; failed cells dark red,
// not applicable grey; the worst family per column in the last line.
cv::Mat table_picture(const std::vector<Row>& rows, const std::vector<Measure>& columns,
                      const std::string& title);

}  // namespace omninav::evaluation
