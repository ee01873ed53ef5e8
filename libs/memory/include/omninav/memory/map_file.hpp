#pragma once
// The map file (DESIGN.md, Data formats: Maps; maps/README.md describes the schema): one
// SQLite database holding the places, edges, lattice positions, runs, the parameters used and
// a schema version.
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
//   - adding to an existing map (exploring again) appends the new rows in one SQLite
//     transaction: killed midway, SQLite's rollback journal restores the previous map the next
//     time the file is opened.
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
inline constexpr int kMapSchemaVersion = 2;
// SQLite's application_id of every omninav map: "OMNV" in ASCII.
inline constexpr int kMapApplicationId = 0x4F4D4E56;

struct SaveOptions {
  // Replace an existing file with this memory instead of appending to it.
  bool overwrite = false;
  // Called after each place row is written (for progress, and for the test that kills a
  // writer midway).
  std::function<void(std::size_t places_written)> after_place;
};

// UsageError unless `file` is absent or an omninav map this build may replace (see above).
// Explore calls it before the work when asked to overwrite.
void check_map_replaceable(const std::filesystem::path& file);

// Reads a whole map. Throws InputError as described above.
VisualMemory load_map(const std::filesystem::path& file);

// Writes `memory` to `file`: a new file when there is none (or options.overwrite), else the
// places, edges and runs `memory` holds beyond memory.persisted() are appended in one
// transaction, after checking that the file still holds exactly what was loaded (UsageError
// otherwise: another program changed it) and that its parameters match. Marks `memory` as
// persisted on success.
void save_map(VisualMemory& memory, const std::filesystem::path& file,
              const SaveOptions& options = {});

// Replaces the lattice positions of the map in one transaction (issue 5 writes them): one per
// place, in place order, or an empty vector to clear them. Throws UsageError on a wrong count.
void save_lattice_positions(const std::filesystem::path& file,
                            const std::vector<LatticePosition>& positions);

// Serialises floats as little-endian IEEE 754 float32, whatever the host's byte order: the
// layout of the signature blobs.
std::vector<std::uint8_t> floats_to_le_bytes(const std::vector<float>& values);
std::vector<float> floats_from_le_bytes(const void* data, std::size_t bytes);

}  // namespace omninav::memory
