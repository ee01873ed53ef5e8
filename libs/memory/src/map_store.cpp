#include "omninav/memory/map_store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"
#include "sqlite_db.hpp"

#ifndef OMNINAV_VERSION_STRING
#define OMNINAV_VERSION_STRING "omninav"
#endif

namespace omninav::memory {

using detail::Database;
using detail::Statement;

std::vector<std::uint8_t> floats_to_le_bytes(const std::vector<float>& values) {
  std::vector<std::uint8_t> bytes(values.size() * 4);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto bits = std::bit_cast<std::uint32_t>(values[i]);
    bytes[4 * i] = static_cast<std::uint8_t>(bits);
    bytes[4 * i + 1] = static_cast<std::uint8_t>(bits >> 8);
    bytes[4 * i + 2] = static_cast<std::uint8_t>(bits >> 16);
    bytes[4 * i + 3] = static_cast<std::uint8_t>(bits >> 24);
  }
  return bytes;
}

std::vector<float> floats_from_le_bytes(const void* data, std::size_t bytes) {
  std::vector<float> values(bytes / 4);
  const auto* p = static_cast<const std::uint8_t*>(data);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint32_t bits = static_cast<std::uint32_t>(p[4 * i]) |
                               static_cast<std::uint32_t>(p[4 * i + 1]) << 8 |
                               static_cast<std::uint32_t>(p[4 * i + 2]) << 16 |
                               static_cast<std::uint32_t>(p[4 * i + 3]) << 24;
    values[i] = std::bit_cast<float>(bits);
  }
  return values;
}

namespace {

// Schema version 3 (kMapSchemaVersion). maps/README.md documents every table and column; keep
// the two in step.
constexpr const char* kSchema = R"sql(
CREATE TABLE schema_version (
  version INTEGER NOT NULL,
  written_by TEXT NOT NULL
);
CREATE TABLE parameters (
  key TEXT PRIMARY KEY,
  value TEXT NOT NULL
);
CREATE TABLE runs (
  id INTEGER PRIMARY KEY,
  input TEXT NOT NULL,
  started_utc TEXT NOT NULL,
  frames INTEGER NOT NULL,
  places INTEGER NOT NULL,
  heading_source TEXT NOT NULL,
  description TEXT NOT NULL
);
CREATE TABLE places (
  id INTEGER PRIMARY KEY,
  run_id INTEGER NOT NULL REFERENCES runs(id),
  source TEXT NOT NULL,
  frame_index INTEGER NOT NULL,
  time_s REAL,
  heading_rad REAL,
  heading_source TEXT NOT NULL CHECK (heading_source IN ('none', 'truth', 'compass')),
  signature_rows INTEGER NOT NULL,
  signature_channels INTEGER NOT NULL CHECK (signature_channels IN (1, 3)),
  signature_components INTEGER NOT NULL,
  panorama_width_px INTEGER NOT NULL,
  magnitude BLOB NOT NULL,
  phase_rad BLOB NOT NULL,
  thumbnail_png BLOB
);
CREATE TABLE place_truth (
  place_id INTEGER PRIMARY KEY REFERENCES places(id),
  x_m REAL NOT NULL,
  y_m REAL NOT NULL,
  z_m REAL NOT NULL,
  heading_rad REAL NOT NULL,
  pitch_rad REAL NOT NULL,
  roll_rad REAL NOT NULL
);
CREATE TABLE place_odometry (
  place_id INTEGER PRIMARY KEY REFERENCES places(id),
  x_m REAL NOT NULL,
  y_m REAL NOT NULL,
  heading_rad REAL NOT NULL
);
CREATE TABLE edges (
  id INTEGER PRIMARY KEY,
  from_place INTEGER NOT NULL REFERENCES places(id),
  to_place INTEGER NOT NULL REFERENCES places(id),
  kind TEXT NOT NULL,
  dissimilarity REAL NOT NULL,
  relative_heading_rad REAL NOT NULL,
  heading_confidence REAL NOT NULL,
  motion_bearing_rad REAL,
  motion_bearing_stddev_rad REAL NOT NULL,
  parallax_rad REAL NOT NULL
);
CREATE TABLE lattice_positions (
  place_id INTEGER PRIMARY KEY REFERENCES places(id),
  x REAL NOT NULL,
  y REAL NOT NULL
);
)sql";

std::string corrupt(const std::filesystem::path& file, const std::string& what) {
  return file.string() + ": corrupt map: " + what;
}

// A stored number that is not finite (SQLite keeps infinities; NaN comes back as 0) would
// poison every later sum, comparison and drawing: it is damage.
double finite(double value, const std::filesystem::path& file, const std::string& what) {
  if (!std::isfinite(value)) {
    throw InputError(corrupt(file, what + " is " + std::to_string(value) + ", not a number"));
  }
  return value;
}

std::optional<double> finite(const std::optional<double>& value, const std::filesystem::path& file,
                             const std::string& what) {
  if (value) finite(*value, file, what);
  return value;
}

// A position (truth or lattice), finite and within ±kMaxCoordinateM.
double position(double value, const std::filesystem::path& file, const std::string& what) {
  try {
    return check_coordinate_m(value, what);
  } catch (const InputError& e) {
    throw InputError(corrupt(file, e.what()));
  }
}

// The parameters table's key for the exploration spacing (a "note" to the readers of maps
// written before it was typed, who read it under this name too).
constexpr const char* kExplorationSpacingKey = "exploration.every_m";
constexpr const char* kGridSpacingKey = "grid.separation_m";

std::map<std::string, std::string> parameter_rows(const VisualMemory& memory) {
  const MapParameters& p = memory.parameters();
  std::map<std::string, std::string> rows;
  rows["signature.components"] = std::to_string(p.signature.components);
  rows["signature.colour"] = signature::to_string(p.signature.colour);
  rows["signature.normalise_brightness"] = p.signature.normalise_brightness ? "true" : "false";
  rows["signature.weights"] = signature::to_string(p.weights);
  rows["signature.panorama_rows"] = std::to_string(p.panorama_rows);
  if (memory.exploration_spacing_m()) {
    rows[kExplorationSpacingKey] = shortest(*memory.exploration_spacing_m());
  }
  if (memory.grid_spacing_m()) rows[kGridSpacingKey] = shortest(*memory.grid_spacing_m());
  if (const std::optional<LatticeQuality>& quality = memory.lattice_quality()) {
    rows["lattice.quality.motions"] = std::to_string(quality->motions);
    rows["lattice.quality.motion_residual_steps"] = shortest(quality->motion_residual_steps);
    rows["lattice.quality.motions_off"] = shortest(quality->motions_off);
    rows["lattice.quality.pieces"] = std::to_string(quality->pieces);
    rows["lattice.quality.trustworthy"] = quality->trustworthy ? "true" : "false";
  }
  return rows;
}

// Opens an existing map and checks that it is one this build can read; returns its schema
// version.
std::int64_t check_map(Database& db) {
  const std::filesystem::path& file = db.file();
  Statement app = db.prepare("PRAGMA application_id");
  app.step();
  const std::int64_t id = app.integer(0);
  if (id != kMapApplicationId) {
    throw InputError(file.string() +
                     ": is an SQLite database but not an omninav map (no omninav "
                     "application id)");
  }
  Statement has_version =
      db.prepare("SELECT count(*) FROM sqlite_master WHERE type='table' AND name='schema_version'");
  has_version.step();
  if (has_version.integer(0) != 1) {
    throw InputError(corrupt(file, "it has no schema_version table"));
  }
  Statement version = db.prepare("SELECT version, written_by, typeof(version) FROM schema_version");
  if (!version.step()) throw InputError(corrupt(file, "its schema_version table is empty"));
  if (version.text(2) != "integer") {
    throw InputError(corrupt(file, "schema version '" + version.text(0) + "' is not a number"));
  }
  const std::int64_t v = version.integer(0);
  if (v > kMapSchemaVersion) {
    throw InputError(file.string() + ": the map has schema version " + std::to_string(v) +
                     " (written by " + version.text(1) + "); this omninav reads up to version " +
                     std::to_string(kMapSchemaVersion) + ": update omninav to read it");
  }
  if (v < 1) throw InputError(corrupt(file, "schema version " + std::to_string(v)));
  return v;
}

std::int64_t count_rows(Database& db, const std::string& table) {
  Statement count = db.prepare("SELECT count(*) FROM " + table);
  count.step();
  return count.integer(0);
}

void insert_runs(Database& db, const VisualMemory& memory, std::size_t first) {
  Statement insert = db.prepare(
      "INSERT INTO runs (id, input, started_utc, frames, places, heading_source, description) "
      "VALUES (?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = first; i < memory.runs().size(); ++i) {
    const Run& run = memory.runs()[i];
    insert.bind(1, run.id)
        .bind(2, run.input)
        .bind(3, run.started_utc)
        .bind(4, run.frames)
        .bind(5, run.places)
        .bind(6, to_string(run.heading_source))
        .bind(7, run.description)
        .run();
  }
}

void insert_places(Database& db, const VisualMemory& memory, std::size_t first,
                   const SaveOptions& options) {
  Statement insert = db.prepare(
      "INSERT INTO places (id, run_id, source, frame_index, time_s, heading_rad, heading_source, "
      "signature_rows, signature_channels, signature_components, panorama_width_px, magnitude, "
      "phase_rad, thumbnail_png) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  Statement truth = db.prepare(
      "INSERT INTO place_truth (place_id, x_m, y_m, z_m, heading_rad, pitch_rad, roll_rad) "
      "VALUES (?, ?, ?, ?, ?, ?, ?)");
  Statement odometry = db.prepare(
      "INSERT INTO place_odometry (place_id, x_m, y_m, heading_rad) VALUES (?, ?, ?, ?)");
  for (std::size_t i = first; i < memory.place_count(); ++i) {
    const Place& p = memory.place(i);
    const auto magnitude = floats_to_le_bytes(p.signature.magnitude);
    const auto phase = floats_to_le_bytes(p.signature.phase_rad);
    const auto id = static_cast<std::int64_t>(i);
    insert.bind(1, id)
        .bind(2, p.run)
        .bind(3, p.source)
        .bind(4, p.frame_index)
        .bind(5, p.time_s)
        .bind(6, p.heading_rad)
        .bind(7, to_string(p.heading_source))
        .bind(8, p.signature.rows)
        .bind(9, p.signature.channels)
        .bind(10, p.signature.components)
        .bind(11, p.signature.width_px)
        .bind(12, magnitude)
        .bind(13, phase);
    if (p.thumbnail_png.empty()) {
      insert.bind_null(14);
    } else {
      insert.bind(14, p.thumbnail_png);
    }
    insert.run();
    if (p.truth) {
      // SQLite stores NaN as NULL, which the schema refuses with a message in SQL: said in
      // words here. (Finite values beyond the bound are stored: readers refuse them, and the
      // explorer never makes them, check_pose on every frame.)
      for (const double value : {p.truth->x_m, p.truth->y_m, p.truth->z_m, p.truth->heading_rad,
                                 p.truth->pitch_rad, p.truth->roll_rad}) {
        if (!std::isfinite(value)) {
          throw InputError(db.file().string() + ": cannot write the map (place " +
                           std::to_string(i) + ", " + p.source + ", has a true pose that is " +
                           "not finite)");
        }
      }
      truth.bind(1, id)
          .bind(2, p.truth->x_m)
          .bind(3, p.truth->y_m)
          .bind(4, p.truth->z_m)
          .bind(5, p.truth->heading_rad)
          .bind(6, p.truth->pitch_rad)
          .bind(7, p.truth->roll_rad)
          .run();
    }
    if (p.odometry) {
      for (const double value : {p.odometry->x_m, p.odometry->y_m, p.odometry->heading_rad}) {
        if (!std::isfinite(value)) {
          throw InputError(db.file().string() + ": cannot write the map (place " +
                           std::to_string(i) + ", " + p.source + ", has odometry that is " +
                           "not finite)");
        }
      }
      odometry.bind(1, id)
          .bind(2, p.odometry->x_m)
          .bind(3, p.odometry->y_m)
          .bind(4, p.odometry->heading_rad)
          .run();
    }
    if (options.after_place) options.after_place(i + 1 - first);
  }
}

void insert_lattice_positions(Database& db, const VisualMemory& memory, std::size_t first) {
  Statement insert = db.prepare("INSERT INTO lattice_positions (place_id, x, y) VALUES (?, ?, ?)");
  for (std::size_t i = first; i < memory.place_count(); ++i) {
    const std::optional<Eigen::Vector2d>& position = memory.place(i).lattice_position;
    if (position) {
      insert.bind(1, static_cast<std::int64_t>(i))
          .bind(2, position->x())
          .bind(3, position->y())
          .run();
    }
  }
}

void insert_edges(Database& db, const VisualMemory& memory, std::size_t first) {
  Statement insert = db.prepare(
      "INSERT INTO edges (id, from_place, to_place, kind, dissimilarity, relative_heading_rad, "
      "heading_confidence, motion_bearing_rad, motion_bearing_stddev_rad, parallax_rad) "
      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  std::size_t index = 0;
  for (const VisualMemory::EdgeRef& ref : memory.edges()) {
    const auto& [from, to, edge] = ref;
    if (index++ < first) continue;
    insert.bind(1, static_cast<std::int64_t>(index - 1))
        .bind(2, static_cast<std::int64_t>(from))
        .bind(3, static_cast<std::int64_t>(to))
        .bind(4, to_string(edge->kind))
        .bind(5, edge->dissimilarity)
        .bind(6, edge->relative_heading_rad)
        .bind(7, edge->heading_confidence)
        .bind(8, edge->motion_bearing_rad)
        .bind(9, edge->motion_bearing_stddev_rad)
        .bind(10, edge->parallax_rad)
        .run();
  }
}

void write_parameters(Database& db, const VisualMemory& memory) {
  Statement upsert = db.prepare(
      "INSERT INTO parameters (key, value) VALUES (?, ?) "
      "ON CONFLICT(key) DO UPDATE SET value = excluded.value");
  // A lattice quality belongs to the lattice it measured: none is kept for another.
  db.exec("DELETE FROM parameters WHERE key LIKE 'lattice.quality.%'");
  for (const auto& [key, value] : parameter_rows(memory)) upsert.bind(1, key).bind(2, value).run();
}

void check_replaceable(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return;
  const auto refuse = [&](const std::string& what) {
    throw UsageError(file.string() + ": " + what + "; not replacing it (only an omninav map is)");
  };
  if (!std::filesystem::is_regular_file(file, error)) refuse("is not a regular file");
  // SQLite's header: its magic, then the application id, big-endian, at byte 68.
  char header[72] = {};
  {
    std::ifstream stream(file, std::ios::binary);
    stream.read(header, sizeof header);
    if (stream.gcount() != sizeof header) refuse("is not an omninav map");
  }
  const auto byte = [&](int i) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(header[i]));
  };
  const std::uint32_t id = byte(68) << 24 | byte(69) << 16 | byte(70) << 8 | byte(71);
  if (std::memcmp(header, "SQLite format 3", 16) != 0 ||
      id != static_cast<std::uint32_t>(kMapApplicationId)) {
    refuse("is not an omninav map");
  }
  std::int64_t version = 0;
  try {
    Database db(file, Database::Mode::kReadOnly);
    Statement row = db.prepare("SELECT version FROM schema_version");
    if (row.step()) version = row.integer(0);
  } catch (const InputError&) {
    return;  // a damaged map of ours: replacing it is what the user asked for
  }
  if (version > kMapSchemaVersion) {
    refuse("was written by a newer omninav (schema version " + std::to_string(version) + ")");
  }
}

// Held while a new map is written, on "<map>.lock" beside it: a second writer of the same map
// fails at once instead of sharing the first one's work. The last holder removes the file; a
// process that locked a file removed meanwhile locks the new one.
class WriteLock {
 public:
  explicit WriteLock(const std::filesystem::path& map) : file_(map.string() + ".lock") {
    while (true) {
      fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
      if (fd_ < 0) {
        throw InputError(map.string() + ": cannot write (" + file_ + ": " + std::strerror(errno) +
                         ")");
      }
      if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd_);
        throw InputError(map.string() + ": another process is writing this map; try again later");
      }
      struct stat held {};
      struct stat named {};
      if (::fstat(fd_, &held) == 0 && ::stat(file_.c_str(), &named) == 0 &&
          held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
        return;
      }
      ::close(fd_);
    }
  }
  WriteLock(const WriteLock&) = delete;
  WriteLock& operator=(const WriteLock&) = delete;
  ~WriteLock() {
    ::unlink(file_.c_str());
    ::close(fd_);
  }

 private:
  std::string file_;
  int fd_ = -1;
};

void write_new(const VisualMemory& memory, const std::filesystem::path& file,
               const SaveOptions& options) {
  std::error_code ignored;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ignored);
  const WriteLock lock(file);
  if (!options.overwrite && std::filesystem::exists(file, ignored)) {
    throw InputError(file.string() + ": another process made this map meanwhile; not replacing it");
  }
  check_replaceable(file);
  remove_stale_temporaries(file);  // a killed writer's, under the lock no one else's
  OutputFile output(file);
  if (output.in_place()) throw InputError(file.string() + ": is not a regular file");
  {
    Database db(output.temporary(), Database::Mode::kCreate, file);
    // The temporary is thrown away if anything fails, so it needs no journal; it is synced
    // once, whole, before the rename.
    db.exec("PRAGMA journal_mode = OFF");
    db.exec("PRAGMA synchronous = OFF");
    db.exec("PRAGMA application_id = " + std::to_string(kMapApplicationId));
    db.exec("BEGIN");
    db.exec(kSchema);
    db.prepare("INSERT INTO schema_version (version, written_by) VALUES (?, ?)")
        .bind(1, kMapSchemaVersion)
        .bind(2, std::string(OMNINAV_VERSION_STRING))
        .run();
    write_parameters(db, memory);
    insert_runs(db, memory, 0);
    insert_places(db, memory, 0, options);
    insert_lattice_positions(db, memory, 0);
    insert_edges(db, memory, 0);
    db.exec("COMMIT");
  }
  // The old map's journal, left hot by a writer killed mid-transaction, would be rolled back
  // into the new map the next time it is opened: it goes before the new map arrives.
  const std::filesystem::path journal = file.string() + "-journal";
  std::filesystem::remove(journal, ignored);
  if (std::filesystem::exists(journal, ignored)) {
    throw InputError(file.string() + ": cannot remove the old map's journal " + journal.string());
  }
  output.commit();
}

// What `memory` changes of the map on disk, in step with what the store remembers of it.
struct Change {
  std::size_t places = 0, edges = 0, runs = 0;  // rows the file holds already
  bool lattice_changed = false;                 // a place it holds has moved on the lattice
};

// A connection that fails mid-transaction on a full disk leaves SQLite's pager in its error
// state, which closes without rolling back: the journal stays hot and the file grown until the
// next opener rolls them back. The failing writer is that opener, before it reports the failure.
void roll_back_hot_journal(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::exists(file.string() + "-journal", error)) return;
  try {
    Database db(file, Database::Mode::kReadWrite);
    db.exec("SELECT count(*) FROM sqlite_master", "cannot roll back the failed write");
  } catch (const InputError&) {
    // Left to the next opener, as SQLite intends; the first failure is the one reported.
  }
}

void append(const VisualMemory& memory, const std::filesystem::path& file,
            const SaveOptions& options, const Change& change) {
  Database db(file, Database::Mode::kReadWrite);
  const std::int64_t version = check_map(db);
  db.exec("PRAGMA journal_mode = DELETE");
  db.exec("PRAGMA synchronous = FULL");
  db.exec("PRAGMA foreign_keys = ON");
  db.exec("BEGIN IMMEDIATE");
  try {
    if (count_rows(db, "places") != static_cast<std::int64_t>(change.places) ||
        count_rows(db, "edges") != static_cast<std::int64_t>(change.edges) ||
        count_rows(db, "runs") != static_cast<std::int64_t>(change.runs)) {
      // Another writer's append won the race: a failure of this run, not of its arguments.
      throw InputError(file.string() +
                       ": the map on disk is not the one this memory was read from (another "
                       "process changed it meanwhile); not writing");
    }
    // The signature parameters must match, or the new places could not be compared.
    const auto mine = parameter_rows(memory);
    Statement read = db.prepare("SELECT key, value FROM parameters WHERE key LIKE 'signature.%'");
    while (read.step()) {
      const std::string key = read.text(0);
      const auto found = mine.find(key);
      if (key != "signature.panorama_rows" && found != mine.end() &&
          found->second != read.text(1)) {
        throw UsageError(file.string() + ": the map was made with " + key + " = " + read.text(1) +
                         ", not " + found->second);
      }
    }
    write_parameters(db, memory);
    // Version 1 to 2: the old edges become what load_map reads them as, and the new edges may
    // be of a kind a version-1 reader does not know.
    if (version < 2) db.exec("UPDATE edges SET kind = 'listed'");
    // Version 2 to 3: the places' odometry, none for the places already there.
    if (version < 3) {
      db.exec(
          "CREATE TABLE IF NOT EXISTS place_odometry (place_id INTEGER PRIMARY KEY REFERENCES "
          "places(id), "
          "x_m REAL NOT NULL, y_m REAL NOT NULL, heading_rad REAL NOT NULL)");
      db.prepare("UPDATE schema_version SET version = ?, written_by = ?")
          .bind(1, kMapSchemaVersion)
          .bind(2, std::string(OMNINAV_VERSION_STRING))
          .run();
    }
    insert_runs(db, memory, change.runs);
    insert_places(db, memory, change.places, options);
    if (change.lattice_changed) db.exec("DELETE FROM lattice_positions");
    insert_lattice_positions(db, memory, change.lattice_changed ? 0 : change.places);
    insert_edges(db, memory, change.edges);
    db.exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
    db.close();
    roll_back_hot_journal(file);
    throw;
  }
}

Place read_place(const Statement& row, const std::filesystem::path& file, std::size_t expected) {
  const std::int64_t id = row.integer(0);
  if (id != static_cast<std::int64_t>(expected)) {
    throw InputError(corrupt(file, "place ids are not 0, 1, 2, ... (found " + std::to_string(id) +
                                       " where " + std::to_string(expected) + " belongs)"));
  }
  Place p;
  p.run = static_cast<int>(row.integer(1));
  p.source = row.text(2);
  p.frame_index = static_cast<int>(row.integer(3));
  const std::string place = "place " + std::to_string(id);
  p.time_s = finite(row.optional_real(4), file, place + " time_s");
  p.heading_rad = finite(row.optional_real(5), file, place + " heading_rad");
  try {
    p.heading_source = heading_source_from_string(row.text(6));
  } catch (const InputError& error) {
    throw InputError(corrupt(file, "place " + std::to_string(id) + ": " + error.what()));
  }
  signature::Signature& s = p.signature;
  s.rows = static_cast<int>(row.integer(7));
  s.channels = static_cast<int>(row.integer(8));
  s.components = static_cast<int>(row.integer(9));
  s.width_px = static_cast<int>(row.integer(10));
  if (s.rows < 1 || s.rows > 100000 || (s.channels != 1 && s.channels != 3) || s.components < 1 ||
      s.components > 100000 || s.width_px < 1) {
    throw InputError(corrupt(file, "place " + std::to_string(id) + " has signature dimensions " +
                                       std::to_string(s.rows) + " x " + std::to_string(s.channels) +
                                       " x " + std::to_string(s.components)));
  }
  const std::size_t expected_bytes = s.size() * 4;
  const auto [magnitude, magnitude_bytes] = row.blob_view(11);
  const auto [phase, phase_bytes] = row.blob_view(12);
  if (magnitude_bytes != expected_bytes || phase_bytes != expected_bytes) {
    throw InputError(corrupt(file, "place " + std::to_string(id) + ": signature blobs of " +
                                       std::to_string(magnitude_bytes) + " and " +
                                       std::to_string(phase_bytes) + " bytes, expected " +
                                       std::to_string(expected_bytes)));
  }
  s.magnitude = floats_from_le_bytes(magnitude, magnitude_bytes);
  s.phase_rad = floats_from_le_bytes(phase, phase_bytes);
  for (const std::vector<float>* values : {&s.magnitude, &s.phase_rad}) {
    if (!std::all_of(values->begin(), values->end(), [](float v) { return std::isfinite(v); })) {
      throw InputError(corrupt(file, place + ": its signature holds a value that is not finite"));
    }
  }
  p.thumbnail_png = row.blob(13);
  return p;
}

// A copy of a map and of the hot journal a killed writer left beside it, in a private temporary
// folder (removed with this object), for a reader that may not write where the map is (read-only
// storage): SQLite rolls the journal back into the copy, which then holds the previous map.
class RolledBackCopy {
 public:
  explicit RolledBackCopy(const std::filesystem::path& map) {
    std::string pattern = (std::filesystem::temp_directory_path() / "omninav-map-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw InputError(map.string() + ": cannot read (it has a journal to roll back, and no " +
                       "temporary folder to do it in: " + std::strerror(errno) + ")");
    }
    folder_ = pattern;
    file_ = folder_ / "map.vmem";
    std::error_code error;
    std::filesystem::copy_file(map, file_, error);
    if (!error) {
      std::filesystem::copy_file(map.string() + "-journal", file_.string() + "-journal", error);
    }
    if (error) {
      std::filesystem::remove_all(folder_, error);
      throw InputError(map.string() + ": cannot read (it has a journal to roll back, and " +
                       "copying them failed: " + error.message() + ")");
    }
  }
  ~RolledBackCopy() {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
  RolledBackCopy(const RolledBackCopy&) = delete;
  RolledBackCopy& operator=(const RolledBackCopy&) = delete;

  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path folder_, file_;
};

// Whether a reader of `file` must roll back a hot journal it may not write: the map or its
// folder read-only (storage mounted read-only, or permissions), and a journal beside it.
bool needs_rolled_back_copy(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::path journal = file.string() + "-journal";
  if (!std::filesystem::exists(journal, error) || std::filesystem::file_size(journal, error) == 0) {
    return false;
  }
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : ".";
  return ::access(file.c_str(), W_OK) != 0 || ::access(folder.c_str(), W_OK) != 0;
}

// Opens a map for reading. Read-write when possible: a map left with a hot journal by a killed
// writer is rolled back to its previous state when opened, which a read-only connection cannot
// do (then `copy` holds the map rolled back, and is what is read). Messages name `file`.
Database open_for_reading(const std::filesystem::path& file, std::optional<RolledBackCopy>& copy) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) {
    throw InputError(file.string() + ": no such map file");
  }
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(file.string() + ": is not a map file (not a regular file)");
  }
  if (needs_rolled_back_copy(file)) {
    copy.emplace(file);
    return Database(copy->file(), Database::Mode::kReadWrite, file);
  }
  const bool writable = ::access(file.c_str(), W_OK) == 0;
  return Database(file, writable ? Database::Mode::kReadWrite : Database::Mode::kReadOnly);
}

// The parameters table: what every place shares, and the exploration spacing. Keys this build
// does not know are left in the file and not read.
VisualMemory read_parameters(Database& db) {
  std::map<std::string, std::string> rows;
  {
    Statement read = db.prepare("SELECT key, value FROM parameters");
    while (read.step()) rows[read.text(0)] = read.text(1);
  }
  const auto get = [&](const std::string& key) {
    const auto found = rows.find(key);
    if (found == rows.end()) throw InputError("the parameter " + key + " is missing");
    return found->second;
  };
  try {
    MapParameters parameters;
    parameters.signature.components =
        parse_int(get("signature.components"), "signature.components");
    parameters.signature.colour = signature::colour_mode_from_string(get("signature.colour"));
    const std::string normalise = get("signature.normalise_brightness");
    if (normalise != "true" && normalise != "false") {
      throw InputError("signature.normalise_brightness is '" + normalise + "'");
    }
    parameters.signature.normalise_brightness = normalise == "true";
    parameters.weights =
        signature::parse_component_weights(get("signature.weights"), "signature.weights");
    parameters.panorama_rows = parse_int(get("signature.panorama_rows"), "signature.panorama_rows");
    VisualMemory memory(parameters);
    const auto spacing = rows.find(kExplorationSpacingKey);
    if (spacing != rows.end()) {
      const double every_m = parse_double(spacing->second, kExplorationSpacingKey);
      if (!std::isfinite(every_m)) {
        throw InputError(std::string(kExplorationSpacingKey) + " is " + spacing->second);
      }
      // A spacing of 0 (none) was once possible to store: it says nothing.
      if (every_m > 0.0) memory.set_exploration_spacing_m(every_m);
    }
    if (rows.contains(kGridSpacingKey)) {
      memory.set_grid_spacing_m(parse_double(get(kGridSpacingKey), kGridSpacingKey));
    }
    if (rows.contains("lattice.quality.motions")) {
      LatticeQuality quality;
      const auto number = [&](const std::string& key) {
        const double value = parse_double(get("lattice.quality." + key), key);
        if (!std::isfinite(value)) throw InputError("lattice.quality." + key + " is not finite");
        return value;
      };
      quality.motions = static_cast<int>(number("motions"));
      quality.motion_residual_steps = number("motion_residual_steps");
      quality.motions_off = number("motions_off");
      quality.pieces = static_cast<int>(number("pieces"));
      quality.trustworthy = get("lattice.quality.trustworthy") == "true";
      memory.set_lattice_quality(quality);
    }
    return memory;
  } catch (const std::exception& e) {
    throw InputError(corrupt(db.file(), e.what()));
  }
}

std::vector<Run> read_runs(Database& db) {
  Statement rows = db.prepare(
      "SELECT id, input, started_utc, frames, places, heading_source, description FROM runs "
      "ORDER BY id");
  std::vector<Run> runs;
  while (rows.step()) {
    Run run;
    run.id = static_cast<int>(rows.integer(0));
    run.input = rows.text(1);
    run.started_utc = rows.text(2);
    run.frames = static_cast<int>(rows.integer(3));
    run.places = static_cast<int>(rows.integer(4));
    try {
      run.heading_source = heading_source_from_string(rows.text(5));
    } catch (const InputError& error) {
      throw InputError(corrupt(db.file(), "run " + std::to_string(run.id) + ": " + error.what()));
    }
    run.description = rows.text(6);
    runs.push_back(run);
  }
  return runs;
}

std::vector<Place> read_places(Database& db) {
  Statement rows = db.prepare(
      "SELECT id, run_id, source, frame_index, time_s, heading_rad, heading_source, "
      "signature_rows, signature_channels, signature_components, panorama_width_px, magnitude, "
      "phase_rad, thumbnail_png FROM places ORDER BY id");
  std::vector<Place> places;
  while (rows.step()) places.push_back(read_place(rows, db.file(), places.size()));
  return places;
}

// The place a row of `table` names, which must be one of `places`.
PlaceIndex place_of(std::int64_t id, std::size_t places, const std::filesystem::path& file,
                    const std::string& table) {
  if (id < 0 || id >= static_cast<std::int64_t>(places)) {
    throw InputError(
        corrupt(file, table + " names place " + std::to_string(id) + ", which does not exist"));
  }
  return static_cast<PlaceIndex>(id);
}

void read_truth(Database& db, std::vector<Place>& places) {
  const std::filesystem::path& file = db.file();
  Statement rows = db.prepare(
      "SELECT place_id, x_m, y_m, z_m, heading_rad, pitch_rad, roll_rad FROM place_truth");
  while (rows.step()) {
    const PlaceIndex place = place_of(rows.integer(0), places.size(), file, "place_truth");
    const std::string what = "place_truth of place " + std::to_string(place);
    places[place].truth = CameraPose{position(rows.real(1), file, what + ": x_m"),
                                     position(rows.real(2), file, what + ": y_m"),
                                     position(rows.real(3), file, what + ": z_m"),
                                     finite(rows.real(4), file, what + ": heading_rad"),
                                     finite(rows.real(5), file, what + ": pitch_rad"),
                                     finite(rows.real(6), file, what + ": roll_rad")};
  }
}

void read_odometry(Database& db, std::vector<Place>& places) {
  const std::filesystem::path& file = db.file();
  Statement rows = db.prepare("SELECT place_id, x_m, y_m, heading_rad FROM place_odometry");
  while (rows.step()) {
    const PlaceIndex place = place_of(rows.integer(0), places.size(), file, "place_odometry");
    const std::string what = "place_odometry of place " + std::to_string(place);
    places[place].odometry = CameraPose{position(rows.real(1), file, what + ": x_m"),
                                        position(rows.real(2), file, what + ": y_m"),
                                        0.0,
                                        finite(rows.real(3), file, what + ": heading_rad"),
                                        0.0,
                                        0.0};
  }
}

void read_lattice_positions(Database& db, std::vector<Place>& places) {
  const std::filesystem::path& file = db.file();
  Statement rows = db.prepare("SELECT place_id, x, y FROM lattice_positions");
  while (rows.step()) {
    const PlaceIndex place = place_of(rows.integer(0), places.size(), file, "lattice_positions");
    const std::string what = "lattice position of place " + std::to_string(place);
    places[place].lattice_position = Eigen::Vector2d(position(rows.real(1), file, what + ": x"),
                                                     position(rows.real(2), file, what + ": y"));
  }
}

void read_edges(Database& db, std::int64_t version, VisualMemory& memory) {
  const std::filesystem::path& file = db.file();
  Statement rows = db.prepare(
      "SELECT from_place, to_place, kind, dissimilarity, relative_heading_rad, "
      "heading_confidence, motion_bearing_rad, motion_bearing_stddev_rad, parallax_rad "
      "FROM edges ORDER BY id");
  for (std::size_t index = 0; rows.step(); ++index) {
    Edge edge;
    try {
      edge.kind = edge_kind_from_string(rows.text(2));
      // Version 1 called every edge a sequence, also between a grid database's images; read
      // as listed, such an edge is one step only where the two images look it.
      if (version < 2) edge.kind = EdgeKind::kListed;
    } catch (const InputError& e) {
      throw InputError(corrupt(file, e.what()));
    }
    const std::string what = "edge " + std::to_string(index);
    edge.dissimilarity = finite(rows.real(3), file, what + " dissimilarity");
    edge.relative_heading_rad = finite(rows.real(4), file, what + " relative_heading_rad");
    edge.heading_confidence = finite(rows.real(5), file, what + " heading_confidence");
    edge.motion_bearing_rad = finite(rows.optional_real(6), file, what + " motion_bearing_rad");
    edge.motion_bearing_stddev_rad =
        finite(rows.real(7), file, what + " motion_bearing_stddev_rad");
    edge.parallax_rad = finite(rows.real(8), file, what + " parallax_rad");
    const std::size_t places = memory.place_count();
    memory.add_edge(place_of(rows.integer(0), places, file, "edges"),
                    place_of(rows.integer(1), places, file, "edges"), edge);
  }
}

std::vector<std::optional<Eigen::Vector2d>> lattice_positions_of(const VisualMemory& memory) {
  std::vector<std::optional<Eigen::Vector2d>> positions;
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
    positions.push_back(memory.place(i).lattice_position);
  }
  return positions;
}

}  // namespace

MapStore::MapStore(std::filesystem::path file) : file_(std::move(file)) {}

void MapStore::check_replaceable() const {
  memory::check_replaceable(file_);
}

VisualMemory MapStore::load() {
  std::optional<RolledBackCopy> copy;  // outlives db, declared before it
  Database db = open_for_reading(file_, copy);
  const std::int64_t version = check_map(db);
  db.exec("BEGIN", "cannot read the map");  // one consistent snapshot
  VisualMemory memory = read_parameters(db);
  for (Run& run : read_runs(db)) memory.add_run(std::move(run));
  std::vector<Place> places = read_places(db);
  read_truth(db, places);
  if (version >= 3) read_odometry(db, places);
  read_lattice_positions(db, places);
  for (Place& place : places) {
    try {
      memory.add_place(std::move(place));
    } catch (const UsageError& e) {
      throw InputError(
          corrupt(file_, "place " + std::to_string(memory.place_count()) + ": " + e.what()));
    }
  }
  read_edges(db, version, memory);
  db.exec("COMMIT");
  on_disk_ = {memory.place_count(), memory.edge_count(), memory.runs().size(),
              lattice_positions_of(memory)};
  return memory;
}

void MapStore::save(const VisualMemory& memory, const SaveOptions& options) {
  std::error_code error;
  if (options.overwrite || !std::filesystem::exists(file_, error)) {
    write_new(memory, file_, options);
  } else {
    if (memory.place_count() < on_disk_.places || memory.edge_count() < on_disk_.edges ||
        memory.runs().size() < on_disk_.runs) {
      throw UsageError(file_.string() +
                       ": this memory holds less than the map it was read from; not writing");
    }
    const std::vector<std::optional<Eigen::Vector2d>> lattice = lattice_positions_of(memory);
    const bool lattice_changed = !std::equal(on_disk_.lattice_positions.begin(),
                                             on_disk_.lattice_positions.end(), lattice.begin());
    append(memory, file_, options,
           {on_disk_.places, on_disk_.edges, on_disk_.runs, lattice_changed});
  }
  on_disk_ = {memory.place_count(), memory.edge_count(), memory.runs().size(),
              lattice_positions_of(memory)};
}

VisualMemory load_map(const std::filesystem::path& file) {
  return MapStore(file).load();
}

}  // namespace omninav::memory
