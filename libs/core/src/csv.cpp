#include "omninav/core/csv.hpp"

#include <algorithm>
#include <fstream>
#include <istream>

#include "omninav/core/errors.hpp"
#include "omninav/core/parse.hpp"

namespace omninav {
namespace {

// Spreadsheets often save CSV with a UTF-8 byte-order mark, which would otherwise become part
// of the first column's name.
void drop_byte_order_mark(std::string& line) {
  constexpr std::string_view kMark = "\xEF\xBB\xBF";
  if (line.starts_with(kMark)) line.erase(0, kMark.size());
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// Reads the record that starts on `line` (already read, line `line_number`): its fields, the
// unquoted ones trimmed. A quoted field may hold line breaks: then the record goes on over the
// next lines of `stream`, and `line_number` counts them.
std::vector<std::string> read_record(std::string line, std::istream& stream, int& line_number,
                                     const std::filesystem::path& file) {
  std::vector<std::string> fields;
  std::size_t at = 0;
  const auto where = [&] { return file.string() + ":" + std::to_string(line_number); };
  const std::string record_start = where();
  while (true) {
    while (at < line.size() && is_blank(line[at])) ++at;
    std::string field;
    if (at < line.size() && line[at] == '"') {
      ++at;
      while (true) {
        if (at == line.size()) {  // a line break inside the quotes
          std::string next;
          if (!std::getline(stream, next)) {
            throw InputError(record_start + ": a quoted field is not closed");
          }
          ++line_number;
          field += '\n';
          line = std::move(next);
          at = 0;
          continue;
        }
        if (line[at] == '"') {
          if (at + 1 < line.size() && line[at + 1] == '"') {
            field += '"';
            at += 2;
            continue;
          }
          ++at;
          break;
        }
        field += line[at++];
      }
      while (at < line.size() && is_blank(line[at])) ++at;
      if (at < line.size() && line[at] != ',') {
        throw InputError(where() + ": text after the closing quote of a field");
      }
    } else {
      const std::size_t end = std::min(line.find(',', at), line.size());
      field = std::string(trim(std::string_view(line).substr(at, end - at)));
      at = end;
    }
    fields.push_back(std::move(field));
    if (at >= line.size()) return fields;
    ++at;  // the comma
  }
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
    if (!trim(line).empty()) table.columns_ = read_record(line, stream, line_number, file);
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
    Row row{line_number, {}};
    row.fields = read_record(line, stream, line_number, file);
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

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line += csv_field(fields[i]);
  }
  return line + '\n';
}

void write_csv_line(std::ostream& out, const std::vector<std::string>& fields) {
  out << csv_line(fields);
}

}  // namespace omninav
