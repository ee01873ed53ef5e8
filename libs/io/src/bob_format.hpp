#pragma once
// What BoB's reader and writer share about the on-disk format (see bob_database.hpp for where
// it comes from): the column names of database_entries.csv and database_metadata.yaml.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "omninav/io/bob_database.hpp"

namespace omninav::io::bob {

inline constexpr std::string_view kX = "X [mm]";
inline constexpr std::string_view kY = "Y [mm]";
inline constexpr std::string_view kZ = "Z [mm]";
inline constexpr std::string_view kHeading = "Heading [degrees]";
inline constexpr std::string_view kPitch = "Pitch [degrees]";
inline constexpr std::string_view kRoll = "Roll [degrees]";
inline constexpr std::string_view kFilename = "Filename";
inline constexpr std::string_view kGridX = "Grid X";
inline constexpr std::string_view kGridY = "Grid Y";
inline constexpr std::string_view kGridZ = "Grid Z";
// Not a BoB column but the extra field its data-collection programs add for capture times.
inline constexpr std::string_view kTimestamp = "Timestamp [ms]";
// omninav's own columns: what the robot's wheel odometry measured (dead reckoning), beside the
// truth; other readers ignore them.
inline constexpr std::string_view kOdometryX = "Odometry X [mm]";
inline constexpr std::string_view kOdometryY = "Odometry Y [mm]";
inline constexpr std::string_view kOdometryHeading = "Odometry Heading [degrees]";

struct Metadata {
  DatabaseInfo info;
  std::optional<bool> is_grid;  // `type`, when given; BoB otherwise looks for grid columns
  std::string video_file;       // `videoFile`, relative to the database folder; empty for images
};

// Reads database_metadata.yaml, or nothing when the file does not exist. Throws InputError
// naming the file when it cannot be parsed or a known key has the wrong type.
std::optional<Metadata> read_metadata(const std::filesystem::path& yaml_file);

// The text of database_metadata.yaml for `info`, laid out as BoB's Recorder writes it (through
// cv::FileStorage). No creation time, so that the same input gives the same files.
std::string metadata_yaml(const DatabaseInfo& info, bool greyscale);

}  // namespace omninav::io::bob
