#include "omninav/evaluation/table.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/measures/hershey_text.hpp"

namespace omninav::evaluation {
namespace {

// How bad a value is, larger = worse, whatever the measure's direction.
double badness(const Measure& measure, double value) {
  switch (measure.worse) {
    case Worse::kHigher:
      return value;
    case Worse::kLower:
      return -value;
    case Worse::kAbsHigher:
      return std::abs(value);
  }
  return value;
}

std::string cell_text(const Cell& cell, int decimals) {
  switch (cell.state) {
    case Cell::State::kValue:
      return fixed(cell.value, decimals);
    case Cell::State::kNotApplicable:
      return "-";
    case Cell::State::kFailed:
      return "failed";
  }
  return "";
}

void check_rows(const std::vector<Row>& rows, const std::vector<Measure>& columns) {
  for (const Row& row : rows) {
    if (row.cells.size() != columns.size()) {
      throw UsageError("evaluation table: row " + row.world + " has " +
                       std::to_string(row.cells.size()) + " cells for " +
                       std::to_string(columns.size()) + " measures");
    }
  }
}

}  // namespace

const std::vector<Measure>& measures() {
  static const std::vector<Measure> all = [] {
    std::vector<Measure> m;
    for (const auto& [route, title] : std::vector<std::pair<std::string, std::string>>{
             {"rotate", "rot"}, {"circle", "circ"}, {"wander", "wand"}, {"bumpy", "bumpy"}}) {
      m.push_back({"compass_" + route + "_max_deg", "compass", title + " max", Worse::kHigher, 1});
      m.push_back(
          {"compass_" + route + "_mean_deg", "compass", title + " mean", Worse::kAbsHigher, 1});
      m.push_back(
          {"compass_" + route + "_end_deg", "compass", title + " end", Worse::kAbsHigher, 1});
    }
    // The heading's standard deviation: the share of frames of the four routes within 1 and 2 of
    // it (ideally 0.68 and 0.95; lower means overconfident).
    m.push_back({"compass_within_1_sigma", "compass", "in 1 sd", Worse::kLower, 2});
    m.push_back({"compass_within_2_sigma", "compass", "in 2 sd", Worse::kLower, 2});
    m.push_back({"memory_within_spacing", "memory", "within 1 sp", Worse::kLower, 3});
    m.push_back({"memory_at_nearest", "memory", "at nearest", Worse::kLower, 3});
    m.push_back({"memory_heading_error_deg", "memory", "heading err", Worse::kHigher, 1});
    m.push_back({"memory_right_room", "memory", "right room", Worse::kLower, 3});
    // Min-warping's home vectors between grid places 1-3 spacings apart: |error| in degrees.
    m.push_back({"memory_home_median_deg", "memory", "home med", Worse::kHigher, 1});
    m.push_back({"memory_home_p90_deg", "memory", "home p90", Worse::kHigher, 1});
    for (const auto& [map, title] : std::vector<std::pair<std::string, std::string>>{
             {"grid", "grid"}, {"zigzag30", "zz30"}, {"zigzag60", "zz60"}}) {
      m.push_back({"lattice_" + map + "_rmse", "lattice", title + " all", Worse::kHigher, 2});
      m.push_back(
          {"lattice_" + map + "_rmse_interior", "lattice", title + " int", Worse::kHigher, 2});
      m.push_back(
          {"lattice_" + map + "_rmse_boundary", "lattice", title + " bnd", Worse::kHigher, 2});
      m.push_back({"lattice_" + map + "_folds", "lattice", title + " folds", Worse::kHigher, 0});
    }
    m.push_back({"navigation_reached", "navigation", "reached", Worse::kLower, 3});
    m.push_back({"navigation_path_ratio", "navigation", "path/line", Worse::kHigher, 2});
    m.push_back({"navigation_outside_m", "navigation", "out (m)", Worse::kHigher, 2});
    m.push_back({"navigation_outside_spacings", "navigation", "out (sp)", Worse::kHigher, 1});
    // The driven map: a tour of the grid's rectangle, explored by odometry.
    m.push_back({"tour_coverage", "driven", "coverage", Worse::kLower, 3});
    m.push_back({"lattice_driven_rmse", "driven", "lat all", Worse::kHigher, 2});
    m.push_back({"lattice_driven_rmse_interior", "driven", "lat int", Worse::kHigher, 2});
    m.push_back({"lattice_driven_rmse_boundary", "driven", "lat bnd", Worse::kHigher, 2});
    m.push_back({"lattice_driven_folds", "driven", "lat folds", Worse::kHigher, 0});
    m.push_back({"navigation_driven_reached", "driven", "reached", Worse::kLower, 3});
    m.push_back({"navigation_driven_path_ratio", "driven", "path/line", Worse::kHigher, 2});
    m.push_back({"navigation_driven_outside_m", "driven", "out (m)", Worse::kHigher, 2});
    m.push_back({"navigation_driven_outside_spacings", "driven", "out (sp)", Worse::kHigher, 1});
    return m;
  }();
  return all;
}

std::vector<int> worst_rows(const std::vector<Row>& rows, const std::vector<Measure>& columns) {
  check_rows(rows, columns);
  std::vector<int> worst(columns.size(), -1);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const Cell& cell = rows[r].cells[c];
      if (cell.state == Cell::State::kNotApplicable) continue;
      if (worst[c] < 0) {
        worst[c] = static_cast<int>(r);
        continue;
      }
      const Cell& current = rows[worst[c]].cells[c];
      if (current.state == Cell::State::kFailed) continue;
      if (cell.state == Cell::State::kFailed ||
          badness(columns[c], cell.value) > badness(columns[c], current.value)) {
        worst[c] = static_cast<int>(r);
      }
    }
  }
  return worst;
}

std::string table_csv(const std::vector<Row>& rows, const std::vector<Measure>& columns) {
  const std::vector<int> worst = worst_rows(rows, columns);
  std::ostringstream csv;
  std::vector<std::string> header{"world", "family"};
  for (const Measure& m : columns) header.push_back(m.key);
  write_csv_line(csv, header);
  for (const Row& row : rows) {
    std::vector<std::string> fields{row.world, row.family};
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const Cell& cell = row.cells[c];
      fields.push_back(cell.state == Cell::State::kValue
                           ? fixed(cell.value, columns[c].decimals + 2)
                       : cell.state == Cell::State::kFailed ? "failed"
                                                            : "");
    }
    write_csv_line(csv, fields);
  }
  // The worst row of each column: its family, then its world.
  for (const bool family : {true, false}) {
    std::vector<std::string> fields{family ? "worst_family" : "worst_world", ""};
    for (const int w : worst) {
      fields.push_back(w < 0 ? "" : family ? rows[w].family : rows[w].world);
    }
    write_csv_line(csv, fields);
  }
  return csv.str();
}

std::string table_text(const std::vector<Row>& rows, const std::vector<Measure>& columns) {
  const std::vector<int> worst = worst_rows(rows, columns);
  std::size_t label_width = 5;  // "WORST"
  for (const Row& row : rows) label_width = std::max(label_width, row.world.size());
  std::ostringstream out;
  std::vector<std::string> groups;
  for (const Measure& m : columns) {
    if (std::find(groups.begin(), groups.end(), m.group) == groups.end()) groups.push_back(m.group);
  }
  for (const std::string& group : groups) {
    std::vector<std::size_t> in_group;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c].group == group) in_group.push_back(c);
    }
    std::vector<std::size_t> width(columns.size(), 0);
    for (const std::size_t c : in_group) {
      width[c] = columns[c].title.size();
      for (const Row& row : rows) {
        width[c] = std::max(width[c], cell_text(row.cells[c], columns[c].decimals).size());
      }
      if (worst[c] >= 0) width[c] = std::max(width[c], rows[worst[c]].family.size());
    }
    out << group << '\n' << std::left << std::setw(static_cast<int>(label_width)) << "world";
    for (const std::size_t c : in_group) {
      out << "  " << std::right << std::setw(static_cast<int>(width[c])) << columns[c].title;
    }
    out << '\n';
    for (const Row& row : rows) {
      out << std::left << std::setw(static_cast<int>(label_width)) << row.world;
      for (const std::size_t c : in_group) {
        out << "  " << std::right << std::setw(static_cast<int>(width[c]))
            << cell_text(row.cells[c], columns[c].decimals);
      }
      out << '\n';
    }
    out << std::left << std::setw(static_cast<int>(label_width)) << "WORST";
    for (const std::size_t c : in_group) {
      out << "  " << std::right << std::setw(static_cast<int>(width[c]))
          << (worst[c] < 0 ? "-" : rows[worst[c]].family);
    }
    out << "\n\n";
  }
  return out.str();
}

cv::Mat table_picture(const std::vector<Row>& rows, const std::vector<Measure>& columns,
                      const std::string& title) {
  const std::vector<int> worst = worst_rows(rows, columns);
  constexpr int kCellW = 74, kCellH = 24, kLabelW = 150, kHeaderH = 150, kTitleH = 34;
  const int width = kLabelW + kCellW * static_cast<int>(columns.size()) + 10;
  const int height = kTitleH + kHeaderH + kCellH * (static_cast<int>(rows.size()) + 1) + 10;
  cv::Mat picture(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  cv::putText(picture, measures::hershey_text(title), {8, 24}, font, 0.6, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  // Headers written upwards, one per column.
  for (std::size_t c = 0; c < columns.size(); ++c) {
    cv::Mat header(kCellW, kHeaderH, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(header, measures::hershey_text(columns[c].group + " " + columns[c].title),
                {4, kCellW / 2 + 5}, font, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    cv::Mat rotated;
    cv::rotate(header, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    rotated.copyTo(
        picture(cv::Rect(kLabelW + kCellW * static_cast<int>(c), kTitleH, kCellW, kHeaderH)));
  }
  const auto row_top = [&](std::size_t r) { return kTitleH + kHeaderH + kCellH * int(r); };
  for (std::size_t r = 0; r <= rows.size(); ++r) {
    const std::string label = r < rows.size() ? rows[r].world : "WORST";
    cv::putText(picture, measures::hershey_text(label), {6, row_top(r) + 16}, font, 0.42,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  for (std::size_t c = 0; c < columns.size(); ++c) {
    // Rank of each value in the column, 0 best .. 1 worst.
    std::vector<double> values;
    for (const Row& row : rows) {
      if (row.cells[c].has_value()) values.push_back(badness(columns[c], row.cells[c].value));
    }
    std::sort(values.begin(), values.end());
    const int x = kLabelW + kCellW * static_cast<int>(c);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const Cell& cell = rows[r].cells[c];
      cv::Scalar colour(200, 200, 200);
      if (cell.state == Cell::State::kFailed) colour = cv::Scalar(40, 40, 140);
      if (cell.has_value()) {
        const double b = badness(columns[c], cell.value);
        const auto rank = std::lower_bound(values.begin(), values.end(), b) - values.begin();
        const double share = values.size() > 1 ? double(rank) / double(values.size() - 1) : 0.0;
        // Green (good) through yellow to red (bad), BGR.
        colour = share < 0.5 ? cv::Scalar(120, 220, 120 + 260 * share)
                             : cv::Scalar(120, 220 - 200 * (share - 0.5), 250);
      }
      const cv::Rect box(x, row_top(r), kCellW, kCellH);
      cv::rectangle(picture, box, colour, cv::FILLED);
      cv::rectangle(picture, box, cv::Scalar(255, 255, 255), 1);
      const cv::Scalar ink =
          cell.state == Cell::State::kFailed ? cv::Scalar(255, 255, 255) : cv::Scalar(0, 0, 0);
      cv::putText(picture, cell_text(cell, columns[c].decimals), {x + 4, row_top(r) + 16}, font,
                  0.4, ink, 1, cv::LINE_AA);
    }
    if (worst[c] >= 0) {
      cv::putText(picture, measures::hershey_text(rows[worst[c]].family),
                  {x + 4, row_top(rows.size()) + 16}, font, 0.4, cv::Scalar(0, 0, 160), 1,
                  cv::LINE_AA);
    }
  }
  return picture;
}

}  // namespace omninav::evaluation
