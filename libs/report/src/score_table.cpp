#include "omninav/report/score_table.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/measures/hershey_text.hpp"

namespace omninav::report {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTextScale = 0.4;
constexpr int kCellW = 104, kCellH = 24, kLineH = 14, kTitleH = 34, kGroupH = 22, kGap = 16;
constexpr int kKeyH = 30, kMargin = 8, kHeaderChars = 13;
const cv::Scalar kInk(0, 0, 0), kWhite(255, 255, 255);
const cv::Scalar kFailed(40, 40, 140), kNotApplicable(250, 250, 250);

// Consecutive columns of one group: [first, end) per block.
std::vector<std::pair<std::size_t, std::size_t>> blocks(const std::vector<ScoreColumn>& columns) {
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c == 0 || columns[c].group != columns[c - 1].group) spans.push_back({c, c});
    spans.back().second = c + 1;
  }
  return spans;
}

int text_width(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(measures::hershey_text(text), kFont, kTextScale, 1, &baseline).width;
}

// Words joined into lines that fit a cell (a longer word stands alone), appended to `lines`.
void wrap_into(std::vector<std::string>& lines, const std::string& text) {
  bool first = true;
  std::istringstream words(text);
  for (std::string word; words >> word; first = false) {
    if (!first && text_width(lines.back() + " " + word) <= kCellW - 8) {
      lines.back() += " " + word;
    } else {
      lines.push_back(word);
    }
  }
}

std::vector<std::string> target_lines(const ScoreColumn& column) {
  std::vector<std::string> lines;
  wrap_into(lines, column.target ? target_text(*column.target) : "no target");
  return lines;
}

// A column's header: its title, its unit and its target, each wrapped to the cell's width.
std::vector<std::string> header_lines(const ScoreColumn& column) {
  std::vector<std::string> lines;
  wrap_into(lines, column.title);
  if (!column.unit.empty()) wrap_into(lines, "(" + column.unit + ")");
  const std::vector<std::string> target = target_lines(column);
  lines.insert(lines.end(), target.begin(), target.end());
  return lines;
}

void put_text(cv::Mat& picture, const std::string& text, cv::Point at, const cv::Scalar& ink,
              double scale = kTextScale) {
  cv::putText(picture, measures::hershey_text(text), at, kFont, scale, ink, 1, cv::LINE_AA);
}

cv::Scalar cell_colour(const Cell& cell, const ScoreColumn& column) {
  switch (cell.state) {
    case Cell::State::kValue:
      return verdict_colour(verdict(column.target, cell.value));
    case Cell::State::kNotApplicable:
      return kNotApplicable;
    case Cell::State::kFailed:
      return kFailed;
  }
  return kNotApplicable;
}

// A filled box with its text right-aligned (numbers line up), the centre left clear.
void draw_cell(cv::Mat& picture, const cv::Rect& box, const Cell& cell, const ScoreColumn& column) {
  cv::rectangle(picture, box, cell_colour(cell, column), cv::FILLED);
  cv::rectangle(picture, box, kWhite, 1);
  const std::string text = cell_text(cell, column.decimals);
  const cv::Scalar ink = cell.state == Cell::State::kFailed ? kWhite : kInk;
  put_text(picture, text, {box.x + box.width - 5 - text_width(text), box.y + 16}, ink);
}

// The header's lines at the bottom of its box, over the column's cells; the target's in grey.
void draw_header(cv::Mat& picture, const cv::Rect& box, const ScoreColumn& column) {
  const std::vector<std::string> lines = header_lines(column);
  const std::size_t grey_from = lines.size() - target_lines(column).size();
  const int first = box.y + box.height - 6 - kLineH * static_cast<int>(lines.size() - 1);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    put_text(picture, lines[i], {box.x + 4, first + kLineH * static_cast<int>(i)},
             i >= grey_from ? cv::Scalar(90, 90, 90) : kInk);
  }
}

// The colours' meanings, a swatch and its text each.
std::vector<std::pair<cv::Scalar, std::string>> key_entries() {
  return {{verdict_colour(Verdict::kMeets), "meets its target"},
          {verdict_colour(Verdict::kNear), "misses it within the margin"},
          {verdict_colour(Verdict::kMisses), "misses it"},
          {verdict_colour(Verdict::kNoTarget), "no target"},
          {kFailed, "failed"},
          {kNotApplicable, "- not applicable"}};
}

int key_width() {
  int width = kMargin;
  for (const auto& entry : key_entries()) width += 24 + text_width(entry.second) + 18;
  return width;
}

// The key in one line under the table.
void draw_key(cv::Mat& picture, int top) {
  int x = kMargin;
  for (const auto& [colour, text] : key_entries()) {
    const cv::Rect swatch(x, top + 8, 18, 14);
    cv::rectangle(picture, swatch, colour, cv::FILLED);
    cv::rectangle(picture, swatch, cv::Scalar(160, 160, 160), 1);
    put_text(picture, text, {x + 24, top + 19}, kInk);
    x += 24 + text_width(text) + 18;
  }
}

}  // namespace

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

Verdict verdict(const std::optional<Target>& target, double value) {
  if (!target) return Verdict::kNoTarget;
  // How far past the limit, in the bad direction (<= 0 meets).
  double past = value - target->limit;
  if (target->kind == Target::Kind::kAtLeast) past = target->limit - value;
  if (target->kind == Target::Kind::kAbsAtMost) past = std::abs(value) - target->limit;
  if (past <= 0.0) return Verdict::kMeets;
  return past <= target->margin ? Verdict::kNear : Verdict::kMisses;
}

cv::Scalar verdict_colour(Verdict verdict) {
  switch (verdict) {
    case Verdict::kMeets:
      return {110, 205, 110};
    case Verdict::kNear:
      return {60, 190, 250};
    case Verdict::kMisses:
      return {95, 95, 235};
    case Verdict::kNoTarget:
      return {200, 200, 200};
  }
  return {200, 200, 200};
}

std::string target_text(const Target& target) {
  std::ostringstream limit_text;
  limit_text << target.limit;  // the shortest form: 5, 0.5, 0.95
  const std::string limit = limit_text.str();
  switch (target.kind) {
    case Target::Kind::kAtMost:
      return "target <= " + limit;
    case Target::Kind::kAtLeast:
      return "target >= " + limit;
    case Target::Kind::kAbsAtMost:
      return "target |x| <= " + limit;
  }
  return "";
}

ScoreTableLayout score_table_layout(const ScoreTable& table) {
  for (const ScoreRow& row : table.rows) {
    if (row.cells.size() != table.columns.size()) {
      throw UsageError("score table: row " + row.label + " has " +
                       std::to_string(row.cells.size()) + " cells for " +
                       std::to_string(table.columns.size()) + " columns");
    }
  }
  ScoreTableLayout layout;
  layout.label_width = 60;
  for (const ScoreRow& row : table.rows) {
    layout.label_width = std::max(layout.label_width, text_width(row.label) + 2 * kMargin);
  }
  for (const ScoreColumn& column : table.columns) {
    layout.header_lines =
        std::max(layout.header_lines, static_cast<int>(header_lines(column).size()));
  }
  const int header_h = kLineH * layout.header_lines + 6;
  const int rows = static_cast<int>(table.rows.size());
  layout.cell.assign(table.rows.size(), std::vector<cv::Rect>(table.columns.size()));
  layout.header.resize(table.columns.size());
  int top = kTitleH, widest = 0;
  for (const auto& [first, end] : blocks(table.columns)) {
    layout.block_top.push_back(top);
    for (std::size_t c = first; c < end; ++c) {
      const int x = layout.label_width + kCellW * static_cast<int>(c - first);
      layout.header[c] = cv::Rect(x, top + kGroupH, kCellW, header_h);
      for (int r = 0; r < rows; ++r) {
        layout.cell[r][c] = cv::Rect(x, top + kGroupH + header_h + kCellH * r, kCellW, kCellH);
      }
    }
    widest = std::max(widest, static_cast<int>(end - first));
    top += kGroupH + header_h + kCellH * rows + kGap;
  }
  layout.key_top = top;
  layout.size =
      cv::Size(std::max(layout.label_width + kCellW * widest + kMargin, key_width()), top + kKeyH);
  return layout;
}

cv::Mat score_table_picture(const ScoreTable& table) {
  const ScoreTableLayout layout = score_table_layout(table);
  cv::Mat picture(layout.size, CV_8UC3, kWhite);
  put_text(picture, table.title, {kMargin, 24}, kInk, 0.6);
  const auto spans = blocks(table.columns);
  for (std::size_t b = 0; b < spans.size(); ++b) {
    const auto [first, end] = spans[b];
    put_text(picture, table.columns[first].group, {kMargin, layout.block_top[b] + 16}, kInk, 0.5);
    for (std::size_t c = first; c < end; ++c) {
      draw_header(picture, layout.header[c], table.columns[c]);
      for (std::size_t r = 0; r < table.rows.size(); ++r) {
        draw_cell(picture, layout.cell[r][c], table.rows[r].cells[c], table.columns[c]);
      }
    }
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
      put_text(picture, table.rows[r].label, {kMargin, layout.cell[r][first].y + 16}, kInk);
    }
  }
  draw_key(picture, layout.key_top);
  return picture;
}

}  // namespace omninav::report
