#pragma once
// The table of `omninav evaluate`: a row per world, a column per measure, and the worst world
// of each column, worst meaning the direction that is bad for that measure.

#include <optional>
#include <string>
#include <vector>

#include "omninav/report/score_table.hpp"

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
  std::string unit;                      // deg, share, spacings, m, ...
  std::optional<report::Target> target;  // from docs/evaluation.md's targets; none: grey
};

// The measures of evaluate, in column order (docs/evaluation.md defines each).
const std::vector<Measure>& measures();

// One cell: a value, or not applicable (a world without rooms has no "right room"; a path ratio
// needs a trial that reached its goal), or failed (the stage threw; the reason is in the row's
// notes). A failed cell is worse than any value.
using Cell = report::Cell;

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

// evaluation.csv: header "world,family,<keys>", a line per row, every measure's cell a number
// (with the measure's decimals + 2) or empty (not applicable, or failed: the row's notes say
// why), so that a CSV reader types each measure's column as numbers.
std::string table_csv(const std::vector<Row>& rows, const std::vector<Measure>& columns);

// evaluation_worst.csv: header "worst,<keys>", then the lines "family" and "world" (the family
// and the world of each column's worst row) and "value" (its cell as in table_csv, or "failed");
// empty where the column has no worst row.
std::string worst_csv(const std::vector<Row>& rows, const std::vector<Measure>& columns);

// The printed table, one block per group (compass, memory, lattice, navigation) so that it
// fits a terminal: rows as worlds, a column per measure, and a last line WORST with the worst
// family per column.
std::string table_text(const std::vector<Row>& rows, const std::vector<Measure>& columns);

// The table for evaluation.png (report::score_table_picture): a row per world, the measures
// with their units and targets.
report::ScoreTable score_table(const std::vector<Row>& rows, const std::vector<Measure>& columns,
                               const std::string& title);

}  // namespace omninav::evaluation
