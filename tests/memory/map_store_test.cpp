#include "omninav/memory/map_store.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <random>

#include "omninav/core/errors.hpp"

namespace omninav::memory {
namespace {

namespace fs = std::filesystem;

// A scratch folder per test, removed afterwards.
class MapStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("omninav_map_store_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// A memory of `places` places with random signatures (45 rows, 15 components, luminance),
// thumbnails of `thumbnail_bytes` random bytes, truth for even places, and a chain of edges.
// Seeded by `seed`.
VisualMemory synthetic_memory(std::size_t places, std::size_t thumbnail_bytes = 100,
                              unsigned seed = 1, VisualMemory memory = VisualMemory{}) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> magnitude(0.f, 100.f), phase(-3.1f, 3.1f);
  Run run;
  run.id = static_cast<int>(memory.runs().size());
  run.input = "synthetic " + std::to_string(seed);
  run.started_utc = "2024-01-01T00:00:00Z";
  run.heading_source = HeadingSource::kTruth;
  run.description = "map_store_test";
  run.places = static_cast<int>(places);
  run.frames = static_cast<int>(places);
  memory.add_run(run);
  const std::size_t first = memory.place_count();
  for (std::size_t i = 0; i < places; ++i) {
    Place p;
    p.signature.rows = 45;
    p.signature.channels = 1;
    p.signature.components = 15;
    p.signature.width_px = 360;
    for (std::size_t j = 0; j < p.signature.size(); ++j) {
      p.signature.magnitude.push_back(magnitude(random));
      p.signature.phase_rad.push_back(phase(random));
    }
    p.source = "image_" + std::to_string(i) + ".png, with a comma";
    p.frame_index = static_cast<int>(i);
    p.run = run.id;
    if (i % 3 != 0) p.time_s = 0.1 * i;
    if (i % 2 == 0) {
      p.truth = CameraPose{0.3 * i, -0.1 * i, 1.0, 0.01 * i, 0.001, -0.002};
      p.heading_rad = p.truth->heading_rad;
      p.heading_source = HeadingSource::kTruth;
    }
    p.thumbnail_png.resize(thumbnail_bytes);
    for (auto& byte : p.thumbnail_png) byte = static_cast<std::uint8_t>(random());
    const PlaceIndex index = memory.add_place(std::move(p));
    if (index > first) {
      Edge e;
      e.dissimilarity = 10.0 + i;
      e.relative_heading_rad = 0.01 * i - 0.5;
      e.heading_confidence = 0.9;
      if (i % 4 != 0) e.motion_bearing_rad = 0.1 * i - 1.0;
      e.motion_bearing_stddev_rad = 0.05;
      e.parallax_rad = 0.07;
      memory.add_edge(index - 1, index, e);
    }
  }
  return memory;
}

void expect_same(const VisualMemory& a, const VisualMemory& b) {
  ASSERT_EQ(a.place_count(), b.place_count());
  ASSERT_EQ(a.edge_count(), b.edge_count());
  ASSERT_EQ(a.runs().size(), b.runs().size());
  EXPECT_EQ(a.parameters().signature.components, b.parameters().signature.components);
  EXPECT_EQ(a.parameters().signature.colour, b.parameters().signature.colour);
  EXPECT_EQ(a.parameters().weights.alpha, b.parameters().weights.alpha);
  EXPECT_EQ(a.parameters().panorama_rows, b.parameters().panorama_rows);
  EXPECT_EQ(a.exploration_spacing_m(), b.exploration_spacing_m());
  for (PlaceIndex i = 0; i < a.place_count(); ++i) {
    const Place& p = a.place(i);
    const Place& q = b.place(i);
    EXPECT_EQ(p.signature.magnitude, q.signature.magnitude) << "place " << i;  // bit-identical
    EXPECT_EQ(p.signature.phase_rad, q.signature.phase_rad) << "place " << i;
    EXPECT_EQ(p.signature.rows, q.signature.rows);
    EXPECT_EQ(p.signature.width_px, q.signature.width_px);
    EXPECT_EQ(p.heading_rad, q.heading_rad);
    EXPECT_EQ(p.heading_source, q.heading_source);
    EXPECT_EQ(p.thumbnail_png, q.thumbnail_png);
    EXPECT_EQ(p.source, q.source);
    EXPECT_EQ(p.frame_index, q.frame_index);
    EXPECT_EQ(p.run, q.run);
    EXPECT_EQ(p.time_s, q.time_s);
    ASSERT_EQ(p.truth.has_value(), q.truth.has_value());
    if (p.truth) {
      EXPECT_EQ(p.truth->x_m, q.truth->x_m);
      EXPECT_EQ(p.truth->y_m, q.truth->y_m);
      EXPECT_EQ(p.truth->heading_rad, q.truth->heading_rad);
      EXPECT_EQ(p.truth->roll_rad, q.truth->roll_rad);
    }
    EXPECT_EQ(p.lattice_position, q.lattice_position);
  }
  const auto ea = a.edges();
  const auto eb = b.edges();
  for (std::size_t i = 0; i < ea.size(); ++i) {
    EXPECT_EQ(ea[i].from, eb[i].from);
    EXPECT_EQ(ea[i].to, eb[i].to);
    EXPECT_EQ(ea[i].edge->kind, eb[i].edge->kind);
    EXPECT_EQ(ea[i].edge->dissimilarity, eb[i].edge->dissimilarity);
    EXPECT_EQ(ea[i].edge->relative_heading_rad, eb[i].edge->relative_heading_rad);
    EXPECT_EQ(ea[i].edge->motion_bearing_rad, eb[i].edge->motion_bearing_rad);
    EXPECT_EQ(ea[i].edge->parallax_rad, eb[i].edge->parallax_rad);
  }
  for (std::size_t i = 0; i < a.runs().size(); ++i) {
    EXPECT_EQ(a.runs()[i].id, b.runs()[i].id);
    EXPECT_EQ(a.runs()[i].input, b.runs()[i].input);
    EXPECT_EQ(a.runs()[i].places, b.runs()[i].places);
    EXPECT_EQ(a.runs()[i].heading_source, b.runs()[i].heading_source);
  }
}

void sql(const fs::path& file, const std::string& statement) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int code = sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &error);
  EXPECT_EQ(code, SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

// The InputError message load_map throws, or "" if it throws nothing.
std::string load_error(const fs::path& file) {
  try {
    load_map(file);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

// The names in `folder`, sorted: what a writer left there.
std::vector<std::string> folder_entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(LittleEndianFloats, ExplicitByteOrder) {
  const std::vector<float> values{1.0f, -2.5f, 0.0f, 3.0e-20f};
  const std::vector<std::uint8_t> bytes = floats_to_le_bytes(values);
  ASSERT_EQ(bytes.size(), 16u);
  // 1.0f is 0x3F800000: least significant byte first.
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[1], 0x00);
  EXPECT_EQ(bytes[2], 0x80);
  EXPECT_EQ(bytes[3], 0x3F);
  EXPECT_EQ(floats_from_le_bytes(bytes.data(), bytes.size()), values);
}

// The lattice positions (i, -i / 3) of `memory`'s places.
std::vector<Eigen::Vector2d> diagonal_lattice(const VisualMemory& memory) {
  std::vector<Eigen::Vector2d> positions;
  for (std::size_t i = 0; i < memory.place_count(); ++i) positions.emplace_back(i, -1.0 * i / 3);
  return positions;
}

TEST_F(MapStoreTest, RoundTripKeepsSignaturesAndGraphIdentical) {
  VisualMemory memory = synthetic_memory(30);
  memory.set_exploration_spacing_m(0.3);
  memory.set_lattice_positions(diagonal_lattice(memory));
  const fs::path file = dir_ / "round.vmem";
  MapStore(file).save(memory);
  EXPECT_EQ(folder_entries(dir_), std::vector<std::string>{"round.vmem"});
  const VisualMemory loaded = load_map(file);
  expect_same(memory, loaded);
  EXPECT_EQ(*loaded.place(4).lattice_position, Eigen::Vector2d(4.0, -4.0 / 3));
  EXPECT_EQ(loaded.exploration_spacing_m(), 0.3);
}

TEST_F(MapStoreTest, RoundTripKeepsTheGridSpacingAndTheLatticeQuality) {
  VisualMemory memory = synthetic_memory(5);
  memory.set_grid_spacing_m(0.3);
  memory.set_lattice_positions(diagonal_lattice(memory));
  memory.set_lattice_quality({.motions = 40,
                              .motion_residual_steps = 0.25,
                              .motions_off = 0.125,
                              .pieces = 2,
                              .trustworthy = false});
  const fs::path file = dir_ / "quality.vmem";
  MapStore store(file);
  store.save(memory);
  VisualMemory loaded = store.load();
  EXPECT_EQ(loaded.grid_spacing_m(), 0.3);
  EXPECT_FALSE(loaded.exploration_spacing_m());
  ASSERT_TRUE(loaded.lattice_quality());
  EXPECT_EQ(loaded.lattice_quality()->motions, 40);
  EXPECT_EQ(loaded.lattice_quality()->motion_residual_steps, 0.25);
  EXPECT_EQ(loaded.lattice_quality()->motions_off, 0.125);
  EXPECT_EQ(loaded.lattice_quality()->pieces, 2);
  EXPECT_FALSE(loaded.lattice_quality()->trustworthy);
  // A lattice cleared takes its quality with it, on disk too.
  loaded.clear_lattice_positions();
  EXPECT_FALSE(loaded.lattice_quality());
  store.save(loaded);
  EXPECT_FALSE(load_map(file).lattice_quality());
  EXPECT_THROW(memory.set_grid_spacing_m(0.0), UsageError);
}

// The spacing was a free-form note once; readers of the schema's parameters table (older
// omninav, sqlite3) still find it under the note's name, and a map that has it as the note
// reads it as the spacing.
TEST_F(MapStoreTest, TheExplorationSpacingIsTheParameterOlderReadersKnow) {
  const fs::path file = dir_ / "spacing.vmem";
  VisualMemory memory = synthetic_memory(3);
  memory.set_exploration_spacing_m(0.25);
  MapStore(file).save(memory);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* row = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT value FROM parameters WHERE key = 'exploration.every_m'",
                               -1, &row, nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(row), SQLITE_ROW);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(sqlite3_column_text(row, 0))), "0.25");
  sqlite3_finalize(row);
  sqlite3_close(db);

  sql(file, "UPDATE parameters SET value = '0.5' WHERE key = 'exploration.every_m'");
  EXPECT_EQ(load_map(file).exploration_spacing_m(), 0.5);
  sql(file, "DELETE FROM parameters WHERE key = 'exploration.every_m'");
  EXPECT_FALSE(load_map(file).exploration_spacing_m());
  sql(file, "INSERT INTO parameters VALUES ('exploration.every_m', 'far')");
  EXPECT_NE(load_error(file).find("corrupt map"), std::string::npos) << load_error(file);
}

TEST_F(MapStoreTest, ExploringAgainAppendsToTheMap) {
  const fs::path file = dir_ / "grow.vmem";
  VisualMemory memory = synthetic_memory(10);
  MapStore(file).save(memory);
  MapStore store(file);
  VisualMemory grown = synthetic_memory(7, 50, 2, store.load());
  store.save(grown);
  const VisualMemory again = load_map(file);
  EXPECT_EQ(again.place_count(), 17u);
  EXPECT_EQ(again.runs().size(), 2u);
  EXPECT_EQ(again.edge_count(), 9u + 6u);  // each run's chain; runs are not joined
  expect_same(grown, again);
}

TEST_F(MapStoreTest, EdgeKindsRoundTripAndVersionOneMapsStillRead) {
  const fs::path file = dir_ / "kinds.vmem";
  VisualMemory memory = synthetic_memory(4);
  Edge listed;
  listed.kind = EdgeKind::kListed;
  memory.add_edge(3, 0, listed);
  MapStore(file).save(memory);
  const VisualMemory loaded = load_map(file);
  const auto edges = loaded.edges();
  ASSERT_EQ(edges.size(), 4u);
  EXPECT_EQ(edges[0].edge->kind, EdgeKind::kSequence);
  EXPECT_EQ(edges[3].edge->kind, EdgeKind::kListed);

  // A map written by schema 1 (every edge `sequence`, even a grid database's) reads its edges
  // as listed; exploring into it marks it with this schema, whose edge kinds a version-1 reader
  // would not know.
  const fs::path old = dir_ / "old.vmem";
  VisualMemory version_one = synthetic_memory(5);
  MapStore(old).save(version_one);
  sql(old, "UPDATE schema_version SET version = 1, written_by = 'omninav 0.1.0'");
  MapStore old_store(old);
  VisualMemory read_old = old_store.load();
  for (const VisualMemory::EdgeRef& edge : read_old.edges())
    EXPECT_EQ(edge.edge->kind, EdgeKind::kListed);
  VisualMemory grown = synthetic_memory(3, 50, 2, std::move(read_old));
  old_store.save(grown);
  const VisualMemory grown_read = load_map(old);
  EXPECT_EQ(grown_read.edges().front().edge->kind, EdgeKind::kListed);   // from version 1
  EXPECT_EQ(grown_read.edges().back().edge->kind, EdgeKind::kSequence);  // new, version 2
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(old.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* version = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT version FROM schema_version", -1, &version, nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(version), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(version, 0), kMapSchemaVersion);
  sqlite3_finalize(version);
  sqlite3_close(db);
}

TEST_F(MapStoreTest, AppendingRefusesAMapChangedOnDiskOrMadeDifferently) {
  const fs::path file = dir_ / "changed.vmem";
  VisualMemory memory = synthetic_memory(5);
  MapStore(file).save(memory);
  MapStore stale_store(file);
  VisualMemory stale = stale_store.load();
  MapStore other_store(file);
  VisualMemory other = synthetic_memory(3, 10, 3, other_store.load());
  other_store.save(other);
  VisualMemory more = synthetic_memory(2, 10, 4, std::move(stale));
  // The losing writer of a race failed at run time (exit status 1), not by its arguments (2).
  EXPECT_THROW(stale_store.save(more), InputError);
  EXPECT_EQ(load_map(file).place_count(), 8u);
  // Nor does a lattice organised from the stale map go into the changed one.
  MapStore organising_store(file);
  VisualMemory organised = organising_store.load();
  organised.set_lattice_positions(diagonal_lattice(organised));
  other_store.save(synthetic_memory(1, 10, 5, other_store.load()));
  EXPECT_THROW(organising_store.save(organised), InputError);
  EXPECT_FALSE(load_map(file).all_have_lattice());
  // A memory that lost rows the map has is not written either.
  EXPECT_THROW(other_store.save(synthetic_memory(2)), UsageError);

  MapParameters colour;
  colour.signature.colour = signature::ColourMode::kPerChannel;
  colour.signature.components = 15;
  VisualMemory different(colour);
  const fs::path empty_map = dir_ / "empty.vmem";
  MapStore empty_store(empty_map);
  empty_store.save(VisualMemory{});
  EXPECT_THROW(empty_store.save(different), UsageError);
}

TEST_F(MapStoreTest, OverwriteReplacesTheMap) {
  const fs::path file = dir_ / "over.vmem";
  VisualMemory first = synthetic_memory(5);
  MapStore(file).save(first);
  VisualMemory second = synthetic_memory(3, 10, 9);
  MapStore(file).save(second, {.overwrite = true, .after_place = {}});
  expect_same(second, load_map(file));
}

TEST_F(MapStoreTest, SavingAnOrganisedMapReplacesItsLattice) {
  const fs::path file = dir_ / "lattice.vmem";
  MapStore(file).save(synthetic_memory(4));
  MapStore store(file);
  VisualMemory memory = store.load();
  memory.set_lattice_positions({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  store.save(memory);
  VisualMemory loaded = load_map(file);
  EXPECT_TRUE(loaded.all_have_lattice());
  EXPECT_EQ(loaded.place(2).lattice_position->y(), 1.0);
  EXPECT_THROW(memory.set_lattice_positions({{0, 0}}), UsageError);
  EXPECT_TRUE(memory.all_have_lattice());  // the refused change changed nothing
  // Organised again, and explored further: the new lattice and the new places in one save.
  memory.set_lattice_positions({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  memory = synthetic_memory(2, 10, 3, std::move(memory));
  store.save(memory);
  loaded = load_map(file);
  expect_same(memory, loaded);
  EXPECT_EQ(loaded.place(2).lattice_position->y(), 2.0);
  EXPECT_FALSE(loaded.place(4).lattice_position);
  memory.clear_lattice_positions();
  store.save(memory);
  EXPECT_FALSE(load_map(file).place(0).lattice_position.has_value());
}

// Forks a child that writes `memory` to `file` and blocks after `places_before_kill` places,
// then kills it with SIGKILL: a writer killed in the middle of its transaction.
void kill_writer_midway(MapStore store, VisualMemory memory, std::size_t places_before_kill,
                        bool overwrite) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fds[0]);
    SaveOptions options;
    options.overwrite = overwrite;
    options.after_place = [&](std::size_t written) {
      if (written == places_before_kill) {
        const char byte = 'k';
        (void)!::write(pipe_fds[1], &byte, 1);
        for (;;) ::pause();  // wait here, mid-transaction, for SIGKILL
      }
    };
    try {
      store.save(memory, options);
    } catch (...) {
    }
    ::_exit(3);  // never reached when the kill lands
  }
  ::close(pipe_fds[1]);
  char byte = 0;
  ASSERT_EQ(::read(pipe_fds[0], &byte, 1), 1) << "the writer died before its signal";
  ::close(pipe_fds[0]);
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
}

TEST_F(MapStoreTest, AWriterKilledWhileAppendingLeavesThePreviousMap) {
  const fs::path file = dir_ / "killed.vmem";
  VisualMemory before = synthetic_memory(20, 100);
  MapStore(file).save(before);
  // 1500 places with 8 KB thumbnails: ~20 MB, far more than SQLite's page cache, so pages of
  // the unfinished transaction reach the file and only the journal can undo them.
  MapStore store(file);
  VisualMemory bigger = synthetic_memory(1500, 8000, 2, store.load());
  kill_writer_midway(store, std::move(bigger), 1000, false);
  fs::path journal = file;
  journal += "-journal";
  EXPECT_TRUE(fs::exists(journal)) << "the kill should leave a hot journal";
  const VisualMemory after = load_map(file);
  expect_same(before, after);
  EXPECT_FALSE(fs::exists(journal)) << "opening rolls the journal back";
}

// Runs `write` in a child process whose files may not grow beyond `limit_bytes` (RLIMIT_FSIZE,
// its SIGXFSZ ignored: writes fail with EFBIG, as on a full disk). Returns the message of the
// InputError it threw ("" when it threw none, "other" for any other exception).
std::string message_of_write_with_file_limit(std::uintmax_t limit_bytes,
                                             const std::function<void()>& write) {
  int pipe_fds[2];
  EXPECT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(pipe_fds[0]);
    ::signal(SIGXFSZ, SIG_IGN);
    const struct rlimit limit {
      static_cast<rlim_t>(limit_bytes), static_cast<rlim_t>(limit_bytes)
    };
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message;
    try {
      write();
    } catch (const InputError& error) {
      message = error.what();
    } catch (...) {
      message = "other";
    }
    (void)!::write(pipe_fds[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(pipe_fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, n);
  ::close(pipe_fds[0]);
  int status = 0;
  EXPECT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  return message;
}

TEST_F(MapStoreTest, AnAppendThatCannotGrowTheFileRollsItselfBackBeforeItFails) {
  const fs::path file = dir_ / "full.vmem";
  fs::path journal = file;
  journal += "-journal";
  VisualMemory before = synthetic_memory(20, 100);
  MapStore(file).save(before);
  const std::uintmax_t size = fs::file_size(file);
  MapStore store(file);
  VisualMemory bigger = synthetic_memory(1500, 8000, 2, store.load());
  const std::string message =
      message_of_write_with_file_limit(size + 200'000, [&] { store.save(bigger); });
  EXPECT_EQ(message.rfind(file.string() + ": cannot write the map (", 0), 0u) << message;
  EXPECT_FALSE(fs::exists(journal)) << "no hot journal left for the next reader";
  EXPECT_EQ(fs::file_size(file), size) << "the file did not keep the failed append's pages";
  expect_same(before, load_map(file));
}

TEST_F(MapStoreTest, ANewMapThatCannotBeWrittenIsNamedNotItsTemporary) {
  const fs::path file = dir_ / "new.vmem";
  const std::string message = message_of_write_with_file_limit(
      100'000, [&] { MapStore(file).save(synthetic_memory(600, 8000)); });
  EXPECT_EQ(message.rfind(file.string() + ": cannot write", 0), 0u) << message;
  EXPECT_EQ(message.find(".new."), std::string::npos) << message;
  EXPECT_TRUE(folder_entries(dir_).empty()) << "no map, no temporary";
}

TEST_F(MapStoreTest, AReaderOnReadOnlyStorageReadsAMapAnotherWriterLeftAJournalIn) {
  const fs::path folder = dir_ / "storage";
  fs::create_directories(folder);
  const bool mounted =
      ::geteuid() == 0 && ::mount("tmpfs", folder.c_str(), "tmpfs", 0, "size=64m") == 0;
  if (::geteuid() == 0 && !mounted)
    GTEST_SKIP() << "root without a mount: cannot make storage read-only";
  // Unmounted (or writable again) however the test ends, so that TearDown can remove it.
  const std::unique_ptr<const fs::path, std::function<void(const fs::path*)>> restore(
      &folder, [mounted](const fs::path* storage) {
        if (mounted) {
          ::umount2(storage->c_str(), MNT_DETACH);
        } else {
          std::error_code ignored;
          fs::permissions(*storage, fs::perms::owner_all, ignored);
        }
      });
  const fs::path file = folder / "killed.vmem";
  fs::path journal = file;
  journal += "-journal";
  VisualMemory before = synthetic_memory(20, 100);
  MapStore(file).save(before);
  MapStore store(file);
  // Loaded before `store` is copied into the call (argument order is unspecified: clang copies
  // first, and the copy would not know what the file holds).
  VisualMemory bigger = synthetic_memory(1500, 8000, 2, store.load());
  kill_writer_midway(store, std::move(bigger), 1000, false);
  ASSERT_TRUE(fs::exists(journal)) << "the kill should leave a hot journal";
  if (mounted) {
    ASSERT_EQ(::mount(nullptr, folder.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr), 0);
  } else {
    fs::permissions(file, fs::perms::owner_read | fs::perms::group_read);
    fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
  }
  VisualMemory after;
  EXPECT_NO_THROW(after = load_map(file));
  expect_same(before, after);
  EXPECT_TRUE(fs::exists(journal)) << "the reader changed nothing where it may not write";
}

TEST_F(MapStoreTest, APlaceWithATruePoseThatIsNotFiniteIsRefusedInWords) {
  // The explorer refuses such a frame (check_pose); a memory built by hand is refused on saving,
  // naming the map and the place, where SQLite said "NOT NULL constraint failed".
  const fs::path file = dir_ / "nan.vmem";
  VisualMemory memory = synthetic_memory(3);
  VisualMemory copy(memory.parameters());
  copy.add_run(memory.runs()[0]);
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
    Place place = memory.place(i);
    place.source = "run.bag#/camera frame " + std::to_string(i);
    if (i == 2) place.truth = CameraPose{std::nan(""), 0.0, 0.0, 0.0, 0.0, 0.0};
    copy.add_place(std::move(place));
  }
  try {
    MapStore(file).save(copy);
    ADD_FAILURE() << "a NaN position was written";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              file.string() +
                  ": cannot write the map (place 2, run.bag#/camera frame 2, has a "
                  "true pose that is not finite)");
  }
  EXPECT_TRUE(folder_entries(dir_).empty());
}

TEST_F(MapStoreTest, AWriterKilledWhileCreatingLeavesNoMapOrTheOldOne) {
  const fs::path file = dir_ / "new.vmem";
  kill_writer_midway(MapStore(file), synthetic_memory(600, 8000), 300, false);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_NE(load_error(file).find("no such map file"), std::string::npos);

  VisualMemory old = synthetic_memory(5);
  MapStore(file).save(old);
  kill_writer_midway(MapStore(file), synthetic_memory(600, 8000, 4), 300, true);
  expect_same(old, load_map(file));
  // The next write cleans up the killed writer's leftovers.
  VisualMemory next = synthetic_memory(2, 10, 5);
  MapStore(file).save(next, {.overwrite = true, .after_place = {}});
  EXPECT_EQ(folder_entries(dir_), std::vector<std::string>{"new.vmem"});
  expect_same(next, load_map(file));
}

TEST_F(MapStoreTest, ANewMapIsNeverRolledBackByTheOldMapsJournal) {
  const fs::path file = dir_ / "stale.vmem";
  fs::path journal = file;
  journal += "-journal";
  for (const bool deleted_first : {false, true}) {
    VisualMemory before = synthetic_memory(20, 100);
    MapStore(file).save(before, {.overwrite = true, .after_place = {}});
    MapStore store(file);
    // Loaded before `store` is copied into the call (argument order is unspecified: clang copies
    // first, and the copy would not know what the file holds).
    VisualMemory bigger = synthetic_memory(1500, 8000, 2, store.load());
    kill_writer_midway(store, std::move(bigger), 1000, false);
    ASSERT_TRUE(fs::exists(journal)) << "the kill should leave a hot journal";
    if (deleted_first) fs::remove(file);  // the user deletes the map, not its journal
    VisualMemory fresh = synthetic_memory(7, 10, 11);
    MapStore(file).save(fresh, {.overwrite = !deleted_first, .after_place = {}});
    EXPECT_FALSE(fs::exists(journal));
    expect_same(fresh, load_map(file));
  }
}

TEST_F(MapStoreTest, ASecondWriterOfTheSameNewMapFailsAtOnce) {
  const fs::path file = dir_ / "shared.vmem";
  // Another process writing the map holds the lock beside it.
  const int held = ::open((file.string() + ".lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);
  VisualMemory memory = synthetic_memory(4);
  try {
    MapStore(file).save(memory);
    ADD_FAILURE() << "the second writer wrote";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("shared.vmem: another process is writing this map"),
              std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(fs::exists(file));
  ::close(held);
  fs::remove(file.string() + ".lock");
  MapStore(file).save(memory);
  expect_same(memory, load_map(file));
  EXPECT_EQ(folder_entries(dir_), std::vector<std::string>{"shared.vmem"});

  // A map that appeared while this memory was made is not replaced by a new one.
  VisualMemory other = synthetic_memory(3, 10, 7);
  try {
    MapStore(file).save(other, {.overwrite = false, .after_place = {}});
    ADD_FAILURE() << "the map made meanwhile was replaced";
  } catch (const Error&) {
  }
  expect_same(memory, load_map(file));
}

TEST_F(MapStoreTest, OverwriteReplacesOnlyAnOmninavMapItKnows) {
  const fs::path picture = dir_ / "picture.png";
  std::ofstream(picture, std::ios::binary) << "\x89PNG\r\n\x1a\n" << std::string(200, 'p');
  const auto before = fs::file_size(picture);
  VisualMemory memory = synthetic_memory(3);
  EXPECT_THROW(MapStore(picture).save(memory, {.overwrite = true, .after_place = {}}), UsageError);
  EXPECT_EQ(fs::file_size(picture), before);

  const fs::path newer = dir_ / "newer.vmem";
  VisualMemory old = synthetic_memory(5);
  MapStore(newer).save(old);
  sql(newer, "UPDATE schema_version SET version = 7");
  try {
    MapStore(newer).check_replaceable();
    ADD_FAILURE() << "a newer map would be replaced";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("newer omninav (schema version 7)"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(MapStore(newer).save(memory, {.overwrite = true, .after_place = {}}), UsageError);

  // A damaged map of ours is what --overwrite is for.
  const fs::path damaged = dir_ / "damaged.vmem";
  VisualMemory big = synthetic_memory(300, 2000);
  MapStore(damaged).save(big);
  fs::resize_file(damaged, fs::file_size(damaged) / 2);
  MapStore(damaged).save(memory, {.overwrite = true, .after_place = {}});
  expect_same(memory, load_map(damaged));
}

TEST_F(MapStoreTest, AFailedNewMapLeavesNothingBehind) {
  const fs::path file = dir_ / "failed.vmem";
  VisualMemory memory = synthetic_memory(10);
  SaveOptions failing;
  failing.after_place = [](std::size_t written) {
    if (written == 5) throw std::runtime_error("the disk is full");
  };
  EXPECT_THROW(MapStore(file).save(memory, failing), std::runtime_error);
  EXPECT_TRUE(folder_entries(dir_).empty()) << "no map, no temporary, no lock file";
}

TEST_F(MapStoreTest, AMapCannotBeWrittenOntoADevice) {
  VisualMemory memory = synthetic_memory(3);
  EXPECT_THROW(MapStore("/dev/full").save(memory, {.overwrite = true, .after_place = {}}), Error);
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST_F(MapStoreTest, EachBadFileGivesItsError) {
  EXPECT_NE(load_error(dir_ / "missing.vmem").find("no such map file"), std::string::npos);

  const fs::path text = dir_ / "text.vmem";
  std::ofstream(text, std::ios::binary) << "these are not the droids you are looking for\n"
                                        << std::string(5000, 'x');
  EXPECT_NE(load_error(text).find("not an SQLite database"), std::string::npos) << load_error(text);

  const fs::path other = dir_ / "other.sqlite";
  sql(other, "CREATE TABLE things (a INTEGER); INSERT INTO things VALUES (1);");
  EXPECT_NE(load_error(other).find("not an omninav map"), std::string::npos) << load_error(other);

  const fs::path empty = dir_ / "empty.vmem";
  std::ofstream(empty, std::ios::binary).flush();
  EXPECT_NE(load_error(empty).find("not an omninav map"), std::string::npos) << load_error(empty);

  const fs::path newer = dir_ / "newer.vmem";
  VisualMemory memory = synthetic_memory(5);
  MapStore(newer).save(memory);
  sql(newer, "UPDATE schema_version SET version = 7, written_by = 'omninav 9.0'");
  const std::string newer_error = load_error(newer);
  EXPECT_NE(newer_error.find("schema version 7"), std::string::npos) << newer_error;
  EXPECT_NE(newer_error.find("reads up to version " + std::to_string(kMapSchemaVersion)),
            std::string::npos)
      << newer_error;

  const fs::path short_blob = dir_ / "blob.vmem";
  VisualMemory memory2 = synthetic_memory(5);
  MapStore(short_blob).save(memory2);
  sql(short_blob, "UPDATE places SET magnitude = x'0000803F' WHERE id = 3");
  EXPECT_NE(load_error(short_blob).find("corrupt map: place 3: signature blobs"), std::string::npos)
      << load_error(short_blob);

  const fs::path dangling = dir_ / "dangling.vmem";
  VisualMemory memory3 = synthetic_memory(5);
  MapStore(dangling).save(memory3);
  sql(dangling, "INSERT INTO edges VALUES (99, 1, 42, 'sequence', 1.0, 0.0, 1.0, NULL, 0.0, 0.0)");
  EXPECT_NE(load_error(dangling).find("names place 42"), std::string::npos) << load_error(dangling);

  const fs::path truncated = dir_ / "truncated.vmem";
  VisualMemory big = synthetic_memory(300, 2000);
  MapStore(truncated).save(big);
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  const std::string truncated_error = load_error(truncated);
  EXPECT_NE(truncated_error.find("corrupt"), std::string::npos) << truncated_error;

  const fs::path scribbled = dir_ / "scribbled.vmem";
  MapStore(scribbled).save(big);
  {
    std::fstream file(scribbled, std::ios::binary | std::ios::in | std::ios::out);
    file.seekp(4096 * 3);
    file << std::string(4096 * 20, '\xA5');
  }
  const std::string scribbled_error = load_error(scribbled);
  EXPECT_NE(scribbled_error.find("corrupt"), std::string::npos) << scribbled_error;

  const fs::path wordy = dir_ / "wordy.vmem";
  VisualMemory memory4 = synthetic_memory(5);
  MapStore(wordy).save(memory4);
  sql(wordy, "UPDATE schema_version SET version = 'two'");
  EXPECT_NE(load_error(wordy).find("schema version 'two'"), std::string::npos) << load_error(wordy);
  sql(wordy, "UPDATE schema_version SET version = 2");
  sql(wordy, "UPDATE parameters SET value = 'many' WHERE key = 'signature.components'");
  EXPECT_NE(load_error(wordy).find("signature.components: 'many' is not a whole number"),
            std::string::npos)
      << load_error(wordy);

  const fs::path folder = dir_ / "folder.vmem";
  fs::create_directories(folder);
  EXPECT_NE(load_error(folder).find("not a regular file"), std::string::npos);
}

// A map whose numbers are not finite (NaN, infinite) or absurd (a truth 1e160 mm away) is
// damaged: such values overflow the arithmetic of figures and lattices later.
TEST_F(MapStoreTest, NonFiniteAndAbsurdValuesAreCorrupt) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"UPDATE places SET magnitude = x'0000C07F' || substr(magnitude, 5) WHERE id = 2",
       "place 2: its signature holds a value that is not finite"},
      {"UPDATE places SET phase_rad = substr(phase_rad, 1, 8) || x'0000807F' || "
       "substr(phase_rad, 13) WHERE id = 1",
       "place 1: its signature holds a value that is not finite"},
      {"UPDATE place_truth SET x_m = 1e999 WHERE place_id = 2", "place_truth of place 2: x_m"},
      {"UPDATE place_truth SET y_m = 1e157 WHERE place_id = 4", "place_truth of place 4: y_m"},
      {"UPDATE place_truth SET heading_rad = -1e999 WHERE place_id = 0",
       "place_truth of place 0: heading_rad"},
      {"INSERT INTO lattice_positions VALUES (1, -1e999, 0)", "lattice position of place 1: x"},
      {"UPDATE edges SET dissimilarity = 1e999 WHERE id = 2", "edge 2 dissimilarity"},
      {"UPDATE places SET time_s = 1e999 WHERE id = 1", "place 1 time_s"},
  };
  for (const auto& [statement, expected] : cases) {
    const fs::path map = dir_ / "damaged.vmem";
    VisualMemory memory = synthetic_memory(5);
    SaveOptions replace;
    replace.overwrite = true;
    MapStore(map).save(memory, replace);
    sql(map, statement);
    const std::string error = load_error(map);
    EXPECT_NE(error.find("corrupt map: " + expected), std::string::npos)
        << statement << " gave: " << error;
  }
}

}  // namespace
}  // namespace omninav::memory
