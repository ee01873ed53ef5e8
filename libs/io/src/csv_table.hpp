#pragma once
// A comma-separated text file with one header row, read whole, columns found by name. Fields
// are trimmed; blank lines are skipped. No quoting: neither BoB's files nor ours need it.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace omninav::io {

class CsvTable {
 public:
  struct Row {
    int line = 0;  // 1-based line in the file (the header is line 1)
    std::vector<std::string> fields;
  };

  // Throws InputError naming the file when it cannot be read, has no header row, repeats a
  // column name, or has a row whose number of fields differs from the header's.
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

}  // namespace omninav::io
