#pragma once
// The map store (docs/design.md, Data formats: Maps; maps/README.md describes the schema): a visual
// memory kept in one SQLite file holding the places, edges, lattice positions, runs, the
// parameters used and a schema version. The memory (visual_memory.hpp) is the data; the store
// reads and writes it, and remembers what of it the file already holds.
//
// Writes never leave a half-written map:
//   - a new map is written whole into a temporary of a unique name next to it (a hidden
//     ".<name>.XXXXXX.vmem", core/output_file.hpp), committed, synced and renamed over <file>
//     (rename is atomic on POSIX file systems): killed or failing before the rename, there is
//     no map at <file> (or the old one, when overwriting), and no temporary once it failed;
//     the old map's rollback journal, if a killed writer left one, is removed first, so that
//     it is never rolled back into the new map; a second process writing the same new map at
//     the same time fails at once ("another process is writing this map": a lock on
//     "<file>.lock", removed after);
//   - replacing (overwrite) takes only an omninav map of a schema this build knows: anything
//     else at <file> is a UsageError;
//   - changing an existing map (exploring again, organising) writes what changed (the new rows,
//     the lattice, the parameters) in one SQLite transaction: killed midway, SQLite's rollback
//     journal restores the previous map the next time the file is opened.
// Reading refuses, each with a one-line InputError naming the file: a file that is missing,
// not an SQLite database or damaged ("corrupt"), an SQLite database that is not an omninav map,
// a map from a newer schema, and rows that break the schema (a signature blob of the wrong
// length, an edge to a missing place, ...).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "omninav/memory/visual_memory.hpp"

namespace omninav::memory {

// The schema this build writes and the newest it reads (maps/README.md). Version 2 added the edge
// kind `listed`; a version 1 map's edges, all called `sequence` then, read as `listed`, and
// exploring into one rewrites them so and marks it version 2.
inline constexpr int kMapSchemaVersion = 3;
// SQLite's application_id of every omninav map: "OMNV" in ASCII.
inline constexpr int kMapApplicationId = 0x4F4D4E56;

struct SaveOptions {
  // Replace an existing file with this memory instead of changing it.
  bool overwrite = false;
  // Called after each place row is written (for progress, and for the test that kills a
  // writer midway).
  std::function<void(std::size_t places_written)> after_place;
};

class MapStore {
 public:
  explicit MapStore(std::filesystem::path file);

  const std::filesystem::path& file() const { return file_; }

  // UsageError unless the file is absent or an omninav map this build may replace (see
  // above). Explore calls it before the work when asked to overwrite.
  void check_replaceable() const;

  // Reads the whole map, and remembers what the file holds. Throws InputError as described
  // above.
  VisualMemory load();

  // Writes `memory` in one transaction, and remembers what the file then holds:
  //   - the whole memory, as a new file, when there is none or options.overwrite;
  //   - else what `memory` changed since this store's last load or save (nothing of it yet: an
  //     empty map): its new runs, places and edges are appended, the lattice positions replaced
  //     when they changed, the parameters written. InputError when the file no longer holds
  //     what the store remembers (another process changed it meanwhile); UsageError when
  //     `memory` lacks places, edges or runs the file has, or when its signature parameters
  //     differ from the file's. A failed append (a full disk) is rolled back before it throws:
  //     the file keeps its size and no hot journal is left.
  void save(const VisualMemory& memory, const SaveOptions& options = {});

 private:
  // What the file holds, as of the last load or save.
  struct OnDisk {
    std::size_t places = 0, edges = 0, runs = 0;
    std::vector<std::optional<Eigen::Vector2d>> lattice_positions;  // one per place
  };

  std::filesystem::path file_;
  OnDisk on_disk_;
};

// MapStore(file).load(), for the readers of a map.
VisualMemory load_map(const std::filesystem::path& file);

// Serialises floats as little-endian IEEE 754 float32, whatever the host's byte order: the
// layout of the signature blobs.
std::vector<std::uint8_t> floats_to_le_bytes(const std::vector<float>& values);
std::vector<float> floats_from_le_bytes(const void* data, std::size_t bytes);

}  // namespace omninav::memory
