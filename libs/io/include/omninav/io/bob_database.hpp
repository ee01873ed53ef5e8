#pragma once
// BoB robotics image databases (BrainsOnBoard/bob_robotics, include/navigation/image_database.h
// and src/navigation/image_database.cc): a folder holding
//   - database_entries.csv: a header row, then one row per image. Columns are found by name:
//     "X [mm]", "Y [mm]", "Z [mm]", "Heading [degrees]" (always), "Filename" (image databases),
//     "Grid X", "Grid Y", "Grid Z" (grids), "Pitch [degrees]", "Roll [degrees]" (newer BoB),
//     and any extra columns a recorder adds, such as "Timestamp [ms]";
//   - database_metadata.yaml (optional): an OpenCV FileStorage YAML file whose `metadata` map
//     holds `type` (route or grid), `camera` {name, resolution [w, h], isPanoramic},
//     `needsUnwrapping`, `isGreyscale`, for video databases `videoFile` and `frameRate`, and
//     for grids (BoB's GridRecorder) `grid` {beginAtMM, separationMM, size}, each [x, y, z]
//     (read with yaml-cpp, at most 64 KiB and 32 levels deep; the images must have the stated
//     resolution). A folder with this file but no database_entries.csv is an error;
//   - the images, named by the recorder: routes "image_00000.png"... (BoB's ant-world example
//     databases; newer BoB recorders write "image00001.png"...), grids
//     "image_+001000_+000000_+000010.png" (the position in whole mm, sign and 6 digits each).
//     Readers use the Filename column, so any naming reads.
// Video databases (a `videoFile` in the metadata and no Filename column) take their images from
// the video, one frame per row.
//
// Heading: BoB's robots use REP 103's yaw, counter-clockwise from +x (their SimulatedTank moves
// by (cos yaw, sin yaw) and turns left when yaw grows; Vicon's yaw is right-handed about +z), so
// "Heading [degrees]" maps to heading_rad unchanged. One exception: databases rendered in BoB's
// ant world (its RouteContinuous sets yaw = 90° − atan2(dy, dx), and its renderer turns the
// view clockwise as yaw grows) measure heading clockwise from +y; such a database needs
// heading_ours = 90° − heading_bob, which the file cannot tell us, so it is left to the caller.
// Pitch and roll are converted to radians as they are; their sign convention is not documented
// by BoB.

#include <array>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::io {

inline constexpr const char* kBobEntriesFile = "database_entries.csv";
inline constexpr const char* kBobMetadataFile = "database_metadata.yaml";

// What database_metadata.yaml says (or, for a writer, will say) about a database.
// Where a grid database's points lie (metadata `grid`, as BoB's GridRecorder writes it): point
// (i, j, k) of the grid is at begin_mm + (i, j, k) * separation_mm, componentwise.
struct GridGeometry {
  std::array<double, 3> begin_mm{};       // `beginAtMM`
  std::array<double, 3> separation_mm{};  // `separationMM`: between neighbouring points, >= 0
  std::array<int, 3> size{};              // `size`: points along x, y and z
  // The distance between neighbouring points of the grid, metres: the smallest positive
  // separation along x and y (along z when the grid is a column); nothing when none is > 0.
  std::optional<double> spacing_m() const;
};

struct DatabaseInfo {
  bool is_grid = false;                  // metadata `type`: grid, else route
  cv::Size image_size;                   // `camera.resolution`; 0x0 when unknown (writer: the
                                         // size of the first image added)
  std::optional<double> frame_rate_hz;   // `frameRate`, when the recording had a fixed rate
  std::string camera_name;               // `camera.name`, e.g. "pixpro_usb"
  std::string description;               // `description`, free text (omninav's own key)
  std::optional<bool> needs_unwrapping;  // `needsUnwrapping` (else `camera.isPanoramic`):
                                         // raw omnidirectional images; unknown when absent
  std::optional<GridGeometry> grid;      // `grid`, when the metadata has it (grids only)
};

// One row of database_entries.csv, parsed.
struct DatabaseEntry {
  int csv_line = 0;                        // where the row is, for messages
  std::filesystem::path image_file;        // empty for video databases
  std::optional<CameraPose> truth;         // none when the row's position or heading is empty or
                                           // NaN (how BoB's recorders write a tracking dropout)
  std::optional<std::array<int, 3>> grid;  // grid databases: the x, y, z grid indices
  std::optional<double> time_s;            // from "Timestamp [ms]", else row index / frameRate
  // From omninav's "Odometry X [mm]", "Odometry Y [mm]", "Odometry Heading [degrees]" (the
  // robot's wheel odometry beside the truth), when the database has them.
  std::optional<CameraPose> odometry;
};

class BobDatabaseReader : public SequenceReader {
 public:
  // Reads and checks the metadata and every row at once, so that bad input fails before any
  // image is used. Throws InputError: "<csv>: missing column 'X [mm]'", "<csv>:<line>: ..." for
  // a field that is not a number, naming the image and the line for a missing image file, or
  // naming database_metadata.yaml when it cannot be parsed.
  explicit BobDatabaseReader(const std::filesystem::path& folder);

  std::optional<Frame> next() override;
  std::size_t size() const override { return entries_.size(); }
  std::string describe() const override;
  bool needs_unwrapping() const override { return info_.needs_unwrapping.value_or(false); }
  bool is_grid() const override { return info_.is_grid; }
  std::optional<double> grid_spacing_m() const override {
    return info_.grid ? info_.grid->spacing_m() : std::nullopt;
  }

  const DatabaseInfo& info() const { return info_; }
  const std::vector<DatabaseEntry>& entries() const { return entries_; }

 private:
  std::filesystem::path folder_;
  DatabaseInfo info_;
  std::vector<DatabaseEntry> entries_;
  std::unique_ptr<SequenceReader> video_;  // video databases only
  std::size_t next_index_ = 0;
  ImageSizeCheck size_check_;
};

// Writes a BoB database that BoB's ImageDatabase and BobDatabaseReader both read: PNG images,
// database_entries.csv with "X [mm], Y [mm], Z [mm], Heading [degrees], Pitch [degrees],
// Roll [degrees], Filename" (then "Grid X, Grid Y, Grid Z" for grids, "Timestamp [ms]" when
// the frames have times, and "Odometry X [mm], Odometry Y [mm], Odometry Heading [degrees]" when
// they have odometry), and database_metadata.yaml. Numbers are written in the shortest form
// that reads back to the same double, so poses survive the trip up to the mm/m conversion.
//
// Nothing is half-written: images go to a staging folder inside `folder`; finish() moves them
// in and renames the CSV into place last. A writer destroyed without finish() removes what it
// staged and leaves the folder as it was. The writer deletes nothing it did not write: images of
// an overwritten database that the new one does not name stay in the folder, unreferenced.
class DatabaseWriter {
 public:
  // Creates `folder` if needed. Throws UsageError when it already holds a database
  // (database_entries.csv or database_metadata.yaml) unless `overwrite` is set; the old database
  // stays readable until finish() replaces it. Every method throws omninav::Error when the
  // folder cannot be written.
  DatabaseWriter(std::filesystem::path folder, DatabaseInfo info, bool overwrite = false);
  ~DatabaseWriter();
  DatabaseWriter(const DatabaseWriter&) = delete;
  DatabaseWriter& operator=(const DatabaseWriter&) = delete;

  // Stages the image as image_%05d.png (route, counting from 0) or BoB's grid name, and
  // remembers the entry. Throws UsageError when the frame has no ground-truth pose, when `grid`
  // is missing for a grid database (or given for a route), when two grid entries share a file
  // name, when some frames have times and others not, or after finish(); InputError naming
  // frame.source when its image is empty, not 8-bit grey or BGR, or differs in size from the
  // database's.
  void add(const Frame& frame, std::optional<std::array<int, 3>> grid = {});

  // Writes the CSV and the metadata and moves everything into place. Throws UsageError when no
  // frame was added.
  void finish();

  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::string file_name;
    CameraPose truth;
    std::optional<std::array<int, 3>> grid;
    std::optional<double> time_s;
    std::optional<CameraPose> odometry;
  };

  std::string file_name_for(const CameraPose& truth, const std::optional<std::array<int, 3>>& grid,
                            const std::string& source) const;
  void discard_staging() noexcept;

  std::filesystem::path folder_;
  std::filesystem::path staging_;
  DatabaseInfo info_;
  bool overwrite_;
  bool greyscale_ = false;
  bool finished_ = false;
  std::vector<Entry> entries_;
  std::set<std::string> file_names_;
};

}  // namespace omninav::io
