#pragma once
// Comma-separated text, read and written by one rule (RFC 4180's quoting): a field holding a
// comma, a double quote or a line break is written between double quotes, its quotes doubled;
// the reader takes such a field back whole. Unquoted fields are trimmed; blank lines are
// skipped. Every CSV file omninav reads (BoB's databases, image lists, trajectories) and writes
// (commands' tables, map exports) goes through here.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace omninav {

// A comma-separated text file with one header row, read whole, columns found by name.
class CsvTable {
 public:
  struct Row {
    int line = 0;  // 1-based line in the file where the row starts (the header is line 1)
    std::vector<std::string> fields;
  };

  // Throws InputError naming the file when it cannot be read, has no header row, repeats a
  // column name, has a row whose number of fields differs from the header's, or ends inside a
  // quoted field.
  static CsvTable read(const std::filesystem::path& file);

  const std::filesystem::path& file() const { return file_; }
  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<Row>& rows() const { return rows_; }

  std::optional<std::size_t> find_column(std::string_view name) const;
  // Throws InputError "<file>: missing column '<name>'".
  std::size_t require_column(std::string_view name) const;

  // "<file>:<line>", the prefix of every message about one row.
  std::string where(const Row& row) const;

 private:
  std::filesystem::path file_;
  std::vector<std::string> columns_;
  std::vector<Row> rows_;
};

// `text` as one CSV field: as it is, or quoted when it holds a comma, a double quote or a line
// break.
std::string csv_field(std::string_view text);

// One line of CSV: the fields through csv_field, joined by commas, ending in '\n'.
std::string csv_line(const std::vector<std::string>& fields);

// Writes csv_line(fields) to `out`.
void write_csv_line(std::ostream& out, const std::vector<std::string>& fields);

}  // namespace omninav
