#include "sqlite_db.hpp"

#include "omninav/core/errors.hpp"

namespace omninav::memory::detail {

Database::Database(const std::filesystem::path& file, Mode mode, std::filesystem::path name)
    : name_(name.empty() ? file : std::move(name)) {
  int flags = SQLITE_OPEN_NOMUTEX;
  switch (mode) {
    case Mode::kReadOnly:
      flags |= SQLITE_OPEN_READONLY;
      break;
    case Mode::kReadWrite:
      flags |= SQLITE_OPEN_READWRITE;
      break;
    case Mode::kCreate:
      flags |= SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
      break;
  }
  const int code = sqlite3_open_v2(file.string().c_str(), &db_, flags, nullptr);
  if (code != SQLITE_OK) fail(code, "cannot open");
  sqlite3_extended_result_codes(db_, 1);
  sqlite3_busy_timeout(db_, 5000);  // another omninav writing the same map: wait, then fail
}

Database::~Database() {
  close();
}

void Database::close() {
  if (db_ != nullptr) {
    sqlite3_close_v2(db_);
    db_ = nullptr;
  }
}

void Database::fail(int code, const std::string& doing) const {
  const int primary = code & 0xff;
  const std::string reason =
      db_ != nullptr && sqlite3_errcode(db_) == code ? sqlite3_errmsg(db_) : sqlite3_errstr(code);
  std::string what;
  if (primary == SQLITE_NOTADB) {
    what = "is not an omninav map (not an SQLite database)";
  } else if (primary == SQLITE_CORRUPT) {
    what = "is corrupt (SQLite: " + reason + ")";
  } else if (primary == SQLITE_FULL) {
    what = doing + " (the disk is full)";
  } else if (primary == SQLITE_BUSY || primary == SQLITE_LOCKED) {
    what = doing + " (another process is writing this map; try again later)";
  } else if (primary == SQLITE_READONLY) {
    what = doing + " (the map or its folder is read-only)";
  } else {
    what = doing + " (" + reason + ")";
  }
  throw InputError(name_.string() + ": " + what);
}

void Database::exec(const std::string& sql, const std::string& doing) {
  char* message = nullptr;
  const int code = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message);
  if (message != nullptr) sqlite3_free(message);
  if (code != SQLITE_OK) fail(code, doing);
}

Statement Database::prepare(const std::string& sql) {
  return Statement(*this, sql);
}

Statement::Statement(Database& db, const std::string& sql) : db_(&db), sql_(sql) {
  const int code = sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr);
  if (code != SQLITE_OK) db.fail(code, "cannot read the map");
}

Statement::~Statement() {
  if (stmt_ != nullptr) sqlite3_finalize(stmt_);
}

Statement::Statement(Statement&& other) noexcept
    : db_(other.db_), stmt_(other.stmt_), sql_(std::move(other.sql_)) {
  other.stmt_ = nullptr;
}

Statement& Statement::bind(int index, std::int64_t value) {
  sqlite3_bind_int64(stmt_, index, value);
  return *this;
}

Statement& Statement::bind(int index, double value) {
  sqlite3_bind_double(stmt_, index, value);
  return *this;
}

Statement& Statement::bind(int index, const std::string& value) {
  sqlite3_bind_text(stmt_, index, value.c_str(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
  return *this;
}

Statement& Statement::bind(int index, const std::vector<std::uint8_t>& blob) {
  // An empty vector's data() may be null, which SQLite would store as NULL: bind a zero-length
  // blob explicitly.
  if (blob.empty()) {
    sqlite3_bind_zeroblob(stmt_, index, 0);
  } else {
    sqlite3_bind_blob(stmt_, index, blob.data(), static_cast<int>(blob.size()), SQLITE_STATIC);
  }
  return *this;
}

Statement& Statement::bind_null(int index) {
  sqlite3_bind_null(stmt_, index);
  return *this;
}

bool Statement::step() {
  const int code = sqlite3_step(stmt_);
  if (code == SQLITE_ROW) return true;
  if (code == SQLITE_DONE) return false;
  db_->fail(code,
            sqlite3_stmt_readonly(stmt_) != 0 ? "cannot read the map" : "cannot write the map");
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

bool Statement::is_null(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}

std::int64_t Statement::integer(int column) const {
  return sqlite3_column_int64(stmt_, column);
}

double Statement::real(int column) const {
  return sqlite3_column_double(stmt_, column);
}

std::optional<double> Statement::optional_real(int column) const {
  if (is_null(column)) return std::nullopt;
  return real(column);
}

std::string Statement::text(int column) const {
  const unsigned char* text = sqlite3_column_text(stmt_, column);
  if (text == nullptr) return {};
  return std::string(reinterpret_cast<const char*>(text),
                     static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)));
}

std::pair<const void*, std::size_t> Statement::blob_view(int column) const {
  const void* data = sqlite3_column_blob(stmt_, column);
  const int bytes = sqlite3_column_bytes(stmt_, column);
  return {data, static_cast<std::size_t>(bytes)};
}

std::vector<std::uint8_t> Statement::blob(int column) const {
  const auto [data, bytes] = blob_view(column);
  if (data == nullptr || bytes == 0) return {};
  const auto* begin = static_cast<const std::uint8_t*>(data);
  return std::vector<std::uint8_t>(begin, begin + bytes);
}

}  // namespace omninav::memory::detail
