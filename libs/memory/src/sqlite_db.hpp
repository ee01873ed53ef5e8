#pragma once
// A thin RAII layer over SQLite's C API for the map file: a connection, prepared statements,
// and errors turned into omninav's InputError naming the map and saying in words what is wrong
// (never the SQL, never the hidden temporary a new map is written in).

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace omninav::memory::detail {

class Statement;

class Database {
 public:
  enum class Mode { kReadOnly, kReadWrite, kCreate };
  // `name`: the map messages name, when `file` is a temporary or a copy of it (default: `file`).
  Database(const std::filesystem::path& file, Mode mode, std::filesystem::path name = {});
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs `sql`; a failure is "<name>: <doing> (<SQLite's reason>)".
  void exec(const std::string& sql, const std::string& doing = "cannot write the map");
  Statement prepare(const std::string& sql);
  // Throws InputError for `code` (an SQLite result code) with `doing` as context.
  [[noreturn]] void fail(int code, const std::string& doing) const;
  void close();

  sqlite3* handle() { return db_; }
  // The map's name in messages.
  const std::filesystem::path& file() const { return name_; }

 private:
  std::filesystem::path name_;
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(Database& db, const std::string& sql);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);
  Statement& bind(int index, const std::string& value);
  Statement& bind(int index, const std::vector<std::uint8_t>& blob);  // must outlive step()
  Statement& bind_null(int index);
  Statement& bind(int index, const std::optional<double>& value) {
    return value ? bind(index, *value) : bind_null(index);
  }

  // Steps once: true when a row is available.
  bool step();
  // Steps a statement that returns no rows, then resets it for the next binding.
  void run();
  void reset();

  bool is_null(int column) const;
  std::int64_t integer(int column) const;
  double real(int column) const;
  std::optional<double> optional_real(int column) const;
  std::string text(int column) const;
  std::vector<std::uint8_t> blob(int column) const;
  // The raw bytes of a blob column, valid until the next step.
  std::pair<const void*, std::size_t> blob_view(int column) const;

 private:
  Database* db_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string sql_;
};

}  // namespace omninav::memory::detail
