#include "csv_table.hpp"

#include <algorithm>
#include <fstream>

#include "omninav/core/errors.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::io {
namespace {

// Spreadsheets often save CSV with a UTF-8 byte-order mark, which would otherwise become part
// of the first column's name.
void drop_byte_order_mark(std::string& line) {
  constexpr std::string_view kMark = "\xEF\xBB\xBF";
  if (line.starts_with(kMark)) line.erase(0, kMark.size());
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& file) {
  std::ifstream stream(file);
  if (!stream) throw InputError(file.string() + ": cannot open");
  CsvTable table;
  table.file_ = file;

  std::string line;
  int line_number = 0;
  while (table.columns_.empty() && std::getline(stream, line)) {
    ++line_number;
    if (line_number == 1) drop_byte_order_mark(line);
    if (!trim(line).empty()) table.columns_ = split(line, ',');
  }
  if (table.columns_.empty()) throw InputError(file.string() + ": empty file, no header row");
  for (std::size_t i = 0; i < table.columns_.size(); ++i) {
    const std::string& name = table.columns_[i];
    if (std::find(table.columns_.begin() + static_cast<std::ptrdiff_t>(i) + 1, table.columns_.end(),
                  name) != table.columns_.end()) {
      throw InputError(file.string() + ": column '" + name + "' appears twice in the header");
    }
  }

  while (std::getline(stream, line)) {
    ++line_number;
    if (trim(line).empty()) continue;
    Row row{line_number, split(line, ',')};
    if (row.fields.size() != table.columns_.size()) {
      throw InputError(table.where(row) + ": " + std::to_string(row.fields.size()) +
                       " fields, but the header has " + std::to_string(table.columns_.size()));
    }
    table.rows_.push_back(std::move(row));
  }
  if (stream.bad()) throw InputError(file.string() + ": read error");
  return table;
}

std::optional<std::size_t> CsvTable::find_column(std::string_view name) const {
  const auto found = std::find(columns_.begin(), columns_.end(), name);
  if (found == columns_.end()) return std::nullopt;
  return static_cast<std::size_t>(found - columns_.begin());
}

std::size_t CsvTable::require_column(std::string_view name) const {
  if (const std::optional<std::size_t> column = find_column(name)) return *column;
  throw InputError(file_.string() + ": missing column '" + std::string(name) + "'");
}

std::string CsvTable::where(const Row& row) const {
  return file_.string() + ":" + std::to_string(row.line);
}

}  // namespace omninav::io
