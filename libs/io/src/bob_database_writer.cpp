#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "bob_format.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/io/bob_database.hpp"

namespace omninav::io {
namespace {

// Hidden, so that a folder reader never lists the staged images as part of the folder.
constexpr const char* kStagingFolder = ".omninav_staging";

std::string route_file_name(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "image_%05zu.png", index);
  return name;
}

// BoB's GridRecorder names a grid image after its position in whole mm, each coordinate with
// its sign and zero-padded to 7 characters: image_+001000_-000500_+000010.png.
std::string grid_file_name(const CameraPose& truth) {
  char name[96];
  std::snprintf(name, sizeof name, "image_%+07ld_%+07ld_%+07ld.png",
                std::lround(truth.x_m * 1000.0), std::lround(truth.y_m * 1000.0),
                std::lround(truth.z_m * 1000.0));
  return name;
}

void rename_into_place(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code error;
  std::filesystem::rename(from, to, error);
  if (error) throw Error(to.string() + ": cannot move into place (" + error.message() + ")");
}

}  // namespace

DatabaseWriter::DatabaseWriter(std::filesystem::path folder, DatabaseInfo info, bool overwrite)
    : folder_(std::move(folder)),
      staging_(folder_ / kStagingFolder),
      info_(std::move(info)),
      overwrite_(overwrite) {
  std::error_code error;
  if (!overwrite_ && (std::filesystem::exists(folder_ / kBobEntriesFile, error) ||
                      std::filesystem::exists(folder_ / kBobMetadataFile, error))) {
    throw UsageError(folder_.string() +
                     ": already holds a BoB database; ask for overwrite to replace it");
  }
  std::filesystem::create_directories(folder_, error);
  if (error) throw Error(folder_.string() + ": cannot create folder (" + error.message() + ")");
  // A staging folder can only be left over by a writer that was killed mid-way.
  std::filesystem::remove_all(staging_, error);
  std::filesystem::create_directory(staging_, error);
  if (error) throw Error(staging_.string() + ": cannot create folder (" + error.message() + ")");
}

DatabaseWriter::~DatabaseWriter() {
  if (!finished_) discard_staging();
}

void DatabaseWriter::discard_staging() noexcept {
  std::error_code ignored;
  std::filesystem::remove_all(staging_, ignored);
}

std::string DatabaseWriter::file_name_for(const CameraPose& truth,
                                          const std::optional<std::array<int, 3>>& grid,
                                          const std::string& source) const {
  if (info_.is_grid != grid.has_value()) {
    throw UsageError(source + (info_.is_grid ? ": a grid database needs the grid index"
                                             : ": a route database takes no grid index"));
  }
  if (grid && std::any_of(grid->begin(), grid->end(), [](int i) { return i < 0; })) {
    throw UsageError(source + ": grid indices must not be negative");
  }
  const std::string name = grid ? grid_file_name(truth) : route_file_name(entries_.size());
  if (file_names_.count(name) != 0) {
    throw UsageError(source + ": a second image at the same grid position (" + name + ")");
  }
  std::error_code error;
  if (!overwrite_ && std::filesystem::exists(folder_ / name, error)) {
    throw UsageError((folder_ / name).string() +
                     ": already exists; ask for overwrite to replace it");
  }
  return name;
}

void DatabaseWriter::add(const Frame& frame, std::optional<std::array<int, 3>> grid) {
  if (finished_) throw UsageError(folder_.string() + ": add() after finish()");
  if (!frame.truth) {
    throw UsageError(frame.source + ": no ground-truth pose, which every BoB database entry needs");
  }
  if (!entries_.empty() && entries_.front().time_s.has_value() != frame.time_s.has_value()) {
    throw UsageError(frame.source + ": every frame of a database needs a time, or none");
  }
  if (!entries_.empty() && entries_.front().odometry.has_value() != frame.odometry.has_value()) {
    throw UsageError(frame.source + ": every frame of a database needs odometry, or none");
  }
  require_panorama(frame.image, frame.source);
  const cv::Size size = info_.image_size.empty() ? frame.image.size() : info_.image_size;
  if (frame.image.size() != size) {
    throw InputError(frame.source + ": image is " + size_text(frame.image.size()) +
                     ", but the database's images are " + size_text(size));
  }

  Entry entry{file_name_for(*frame.truth, grid, frame.source), *frame.truth, grid, frame.time_s,
              frame.odometry};
  const std::filesystem::path staged = staging_ / entry.file_name;
  bool written = false;
  try {
    written = cv::imwrite(staged.string(), frame.image);
  } catch (const cv::Exception& e) {
    throw Error(staged.string() + ": cannot write image (" + e.err + ")");
  }
  if (!written) throw Error(staged.string() + ": cannot write image");
  if (entries_.empty()) {
    info_.image_size = size;
    greyscale_ = frame.image.channels() == 1;
  }
  file_names_.insert(entry.file_name);
  entries_.push_back(std::move(entry));
}

void DatabaseWriter::finish() {
  if (finished_) throw UsageError(folder_.string() + ": finish() called twice");
  if (entries_.empty()) throw UsageError(folder_.string() + ": no frames added, nothing to write");

  const bool has_times = entries_.front().time_s.has_value();
  std::string csv =
      "X [mm], Y [mm], Z [mm], Heading [degrees], Pitch [degrees], Roll [degrees], "
      "Filename";
  if (info_.is_grid) csv += ", Grid X, Grid Y, Grid Z";
  if (has_times) csv += ", " + std::string(bob::kTimestamp);
  const bool has_odometry = entries_.front().odometry.has_value();
  if (has_odometry) {
    csv += ", " + std::string(bob::kOdometryX) + ", " + std::string(bob::kOdometryY) + ", " +
           std::string(bob::kOdometryHeading);
  }
  csv += '\n';
  for (const Entry& entry : entries_) {
    const CameraPose& pose = entry.truth;
    csv += shortest(pose.x_m * 1000.0) + ", " + shortest(pose.y_m * 1000.0) + ", " +
           shortest(pose.z_m * 1000.0) + ", " + shortest(rad_to_deg(pose.heading_rad)) + ", " +
           shortest(rad_to_deg(pose.pitch_rad)) + ", " + shortest(rad_to_deg(pose.roll_rad)) +
           ", " + entry.file_name;
    if (entry.grid) {
      csv += ", " + std::to_string((*entry.grid)[0]) + ", " + std::to_string((*entry.grid)[1]) +
             ", " + std::to_string((*entry.grid)[2]);
    }
    if (has_times) csv += ", " + shortest(*entry.time_s * 1000.0);
    if (has_odometry) {
      const CameraPose& odometry = *entry.odometry;
      csv += ", " + shortest(odometry.x_m * 1000.0) + ", " + shortest(odometry.y_m * 1000.0) +
             ", " + shortest(rad_to_deg(odometry.heading_rad));
    }
    csv += '\n';
  }
  write_output_file(staging_ / kBobEntriesFile, csv);
  write_output_file(staging_ / kBobMetadataFile, bob::metadata_yaml(info_, greyscale_));

  // From here on the folder changes. The old entries go first, so that an interruption leaves
  // no database rather than old entries that name new images; the new entries come last, so
  // that the database appears only once everything it names is in place.
  std::error_code error;
  std::filesystem::remove(folder_ / kBobEntriesFile, error);
  if (error) throw Error((folder_ / kBobEntriesFile).string() + ": cannot remove the old entries");
  for (const Entry& entry : entries_) {
    rename_into_place(staging_ / entry.file_name, folder_ / entry.file_name);
  }
  rename_into_place(staging_ / kBobMetadataFile, folder_ / kBobMetadataFile);
  rename_into_place(staging_ / kBobEntriesFile, folder_ / kBobEntriesFile);
  finished_ = true;
  discard_staging();
}

}  // namespace omninav::io
