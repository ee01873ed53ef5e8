#include <algorithm>
#include <cctype>
#include <sstream>

#include "bob_format.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/video_sequence.hpp"

namespace omninav::io {
namespace {

// BoB reads an empty field as NaN ("this is how pandas encodes them") and its recorders write
// NaN when tracking drops out: both mean "no value", not a malformed file.
bool is_missing(std::string_view field) {
  std::string lowered(field);
  std::transform(lowered.begin(), lowered.end(), lowered.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lowered.empty() || lowered == "nan" || lowered == "-nan" || lowered == "+nan";
}

// Parses the rows of database_entries.csv into entries, by column name.
class EntryParser {
 public:
  EntryParser(const CsvTable& table, bool is_grid, bool has_image_files,
              std::optional<double> frame_rate_hz)
      : table_(table),
        x_(table.require_column(bob::kX)),
        y_(table.require_column(bob::kY)),
        z_(table.require_column(bob::kZ)),
        heading_(table.require_column(bob::kHeading)),
        pitch_(table.find_column(bob::kPitch)),
        roll_(table.find_column(bob::kRoll)),
        timestamp_(table.find_column(bob::kTimestamp)),
        odometry_x_(table.find_column(bob::kOdometryX)),
        odometry_y_(table.find_column(bob::kOdometryY)),
        odometry_heading_(table.find_column(bob::kOdometryHeading)),
        frame_rate_hz_(frame_rate_hz) {
    if ((odometry_x_ || odometry_y_ || odometry_heading_) &&
        !(odometry_x_ && odometry_y_ && odometry_heading_)) {
      throw InputError(table.file().string() + ": odometry needs all of the columns '" +
                       std::string(bob::kOdometryX) + "', '" + std::string(bob::kOdometryY) +
                       "' and '" + std::string(bob::kOdometryHeading) + "'");
    }
    if (has_image_files) filename_ = table.require_column(bob::kFilename);
    if (is_grid) {
      grid_ = {table.require_column(bob::kGridX), table.require_column(bob::kGridY),
               table.require_column(bob::kGridZ)};
    }
  }

  DatabaseEntry parse(const CsvTable::Row& row, std::size_t index) const {
    DatabaseEntry entry;
    entry.csv_line = row.line;
    const std::optional<double> x_mm = number(row, x_);
    const std::optional<double> y_mm = number(row, y_);
    const std::optional<double> z_mm = number(row, z_);
    const std::optional<double> heading_deg = number(row, heading_);
    // Pitch and roll: BoB's grid recorder writes NaN for "not measured", i.e. a level camera.
    const double pitch_deg = pitch_ ? number(row, *pitch_).value_or(0.0) : 0.0;
    const double roll_deg = roll_ ? number(row, *roll_).value_or(0.0) : 0.0;
    if (x_mm && y_mm && z_mm && heading_deg) {
      entry.truth = CameraPose{position_m(row, x_, *x_mm), position_m(row, y_, *y_mm),
                               position_m(row, z_, *z_mm), deg_to_rad(*heading_deg),
                               deg_to_rad(pitch_deg),      deg_to_rad(roll_deg)};
    }
    if (odometry_x_) {
      const std::optional<double> ox_mm = number(row, *odometry_x_);
      const std::optional<double> oy_mm = number(row, *odometry_y_);
      const std::optional<double> oheading_deg = number(row, *odometry_heading_);
      if (ox_mm && oy_mm && oheading_deg) {
        entry.odometry = CameraPose{position_m(row, *odometry_x_, *ox_mm),
                                    position_m(row, *odometry_y_, *oy_mm),
                                    entry.truth ? entry.truth->z_m : 0.0,
                                    deg_to_rad(*oheading_deg),
                                    0.0,
                                    0.0};
      }
    }
    if (grid_) {
      entry.grid = std::array{index_in(row, (*grid_)[0]), index_in(row, (*grid_)[1]),
                              index_in(row, (*grid_)[2])};
    }
    // A recorder's own timestamps beat a nominal frame rate; the two are never mixed.
    if (timestamp_) {
      if (const std::optional<double> time_ms = number(row, *timestamp_)) {
        entry.time_s = *time_ms / 1000.0;
      }
    } else if (frame_rate_hz_) {
      entry.time_s = static_cast<double>(index) / *frame_rate_hz_;
    }
    if (filename_) {
      const std::string& name = row.fields[*filename_];
      entry.image_file = table_.file().parent_path() / name;
      std::error_code error;
      if (!std::filesystem::is_regular_file(entry.image_file, error)) {
        throw InputError(table_.where(row) + ": image file '" + name + "' not found (" +
                         entry.image_file.string() + ")");
      }
    }
    return entry;
  }

 private:
  std::string where(const CsvTable::Row& row, std::size_t column) const {
    return table_.where(row) + ": column '" + table_.columns()[column] + "'";
  }

  std::optional<double> number(const CsvTable::Row& row, std::size_t column) const {
    const std::string& field = row.fields[column];
    if (is_missing(field)) return std::nullopt;
    return parse_double(field, where(row, column));
  }

  double position_m(const CsvTable::Row& row, std::size_t column, double value_mm) const {
    return check_coordinate_m(value_mm / 1000.0, where(row, column));
  }

  int index_in(const CsvTable::Row& row, std::size_t column) const {
    const int index = parse_int(row.fields[column], where(row, column));
    if (index < 0) {
      throw InputError(where(row, column) + ": grid index " + row.fields[column] + " is negative");
    }
    return index;
  }

  const CsvTable& table_;
  std::size_t x_, y_, z_, heading_;
  std::optional<std::size_t> pitch_, roll_, timestamp_, filename_;
  std::optional<std::size_t> odometry_x_, odometry_y_, odometry_heading_;
  std::optional<std::array<std::size_t, 3>> grid_;
  std::optional<double> frame_rate_hz_;
};

bool has_any_grid_column(const CsvTable& table) {
  return table.find_column(bob::kGridX) || table.find_column(bob::kGridY) ||
         table.find_column(bob::kGridZ);
}

}  // namespace

std::optional<double> GridGeometry::spacing_m() const {
  double smallest = 0.0;
  const auto consider = [&smallest](double mm) {
    if (mm > 0.0 && (smallest == 0.0 || mm < smallest)) smallest = mm;
  };
  consider(separation_mm[0]);
  consider(separation_mm[1]);
  if (smallest == 0.0) consider(separation_mm[2]);
  if (smallest == 0.0) return std::nullopt;
  return smallest / 1000.0;
}

BobDatabaseReader::BobDatabaseReader(const std::filesystem::path& folder) : folder_(folder) {
  const std::optional<bob::Metadata> metadata = bob::read_metadata(folder / kBobMetadataFile);
  const CsvTable table = CsvTable::read(folder / kBobEntriesFile);
  if (metadata) info_ = metadata->info;
  // As BoB does: without a `type` in the metadata, grid columns make a grid.
  info_.is_grid = metadata && metadata->is_grid ? *metadata->is_grid : has_any_grid_column(table);
  const std::string video_file = metadata ? metadata->video_file : std::string();

  const EntryParser parser(table, info_.is_grid, video_file.empty(), info_.frame_rate_hz);
  if (table.rows().empty()) throw InputError(table.file().string() + ": no entries");
  for (const CsvTable::Row& row : table.rows()) {
    entries_.push_back(parser.parse(row, entries_.size()));
  }
  if (!video_file.empty()) video_ = std::make_unique<VideoSequence>(folder / video_file);
}

std::optional<Frame> BobDatabaseReader::next() {
  if (next_index_ == entries_.size()) return std::nullopt;
  const DatabaseEntry& entry = entries_[next_index_];
  Frame frame;
  frame.index = static_cast<int>(next_index_);
  frame.time_s = entry.time_s;
  frame.truth = entry.truth;
  frame.odometry = entry.odometry;
  if (video_) {
    std::optional<Frame> video_frame = video_->next();
    if (!video_frame) {
      throw InputError(folder_.string() + ": the video ends after " + std::to_string(next_index_) +
                       " frames, but " + kBobEntriesFile + " has " +
                       std::to_string(entries_.size()) + " entries");
    }
    frame.image = std::move(video_frame->image);
    frame.source = std::move(video_frame->source);
  } else {
    frame.image = read_image(entry.image_file);
    frame.source = entry.image_file.string();
  }
  if (!info_.image_size.empty() && frame.image.size() != info_.image_size) {
    throw InputError(frame.source + ": image is " + size_text(frame.image.size()) + ", but " +
                     (folder_ / kBobMetadataFile).string() + " says camera.resolution is [" +
                     std::to_string(info_.image_size.width) + ", " +
                     std::to_string(info_.image_size.height) + "]");
  }
  size_check_.check(frame.image, frame.source);
  ++next_index_;
  return frame;
}

std::string BobDatabaseReader::describe() const {
  const auto with_truth = std::count_if(entries_.begin(), entries_.end(),
                                        [](const DatabaseEntry& e) { return e.truth.has_value(); });
  std::ostringstream text;
  text << "BoB database " << folder_.string() << " (" << (info_.is_grid ? "grid" : "route") << ", "
       << entries_.size() << (video_ ? " video frames" : " images") << ", ";
  if (static_cast<std::size_t>(with_truth) == entries_.size()) {
    text << "with poses)";
  } else {
    text << with_truth << " with poses)";
  }
  return text.str();
}

}  // namespace omninav::io
