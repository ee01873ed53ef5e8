#include "omninav/io/csv_sequence.hpp"

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::io {

CsvSequence::CsvSequence(const std::filesystem::path& csv_file) : csv_file_(csv_file) {
  const CsvTable table = CsvTable::read(csv_file);
  const std::size_t file_column = table.require_column("file");
  const std::size_t x_column = table.require_column("x_m");
  const std::size_t y_column = table.require_column("y_m");
  const std::size_t heading_column = table.require_column("heading_deg");
  const std::optional<std::size_t> z_column = table.find_column("z_m");
  const std::optional<std::size_t> time_column = table.find_column("time_s");
  // The robot's own odometry beside the truth (explore --odometry): all three columns or none.
  const std::optional<std::size_t> odometry_x = table.find_column("odometry_x_m");
  const std::optional<std::size_t> odometry_y = table.find_column("odometry_y_m");
  const std::optional<std::size_t> odometry_heading = table.find_column("odometry_heading_deg");
  if ((odometry_x || odometry_y || odometry_heading) &&
      !(odometry_x && odometry_y && odometry_heading)) {
    throw InputError(csv_file.string() +
                     ": odometry needs all of odometry_x_m, odometry_y_m, odometry_heading_deg");
  }
  if (table.rows().empty()) throw InputError(csv_file.string() + ": no rows after the header");

  const std::filesystem::path folder = csv_file.parent_path();
  for (const CsvTable::Row& row : table.rows()) {
    const std::string where = table.where(row);
    const auto in_column = [&](std::size_t column) {
      return where + ": column '" + table.columns()[column] + "'";
    };
    const auto number = [&](std::size_t column) {
      return parse_double(row.fields[column], in_column(column));
    };
    Row parsed;
    parsed.image_file = folder / row.fields[file_column];
    const auto position_m = [&](std::size_t column) {
      return check_coordinate_m(number(column), in_column(column));
    };
    parsed.truth.x_m = position_m(x_column);
    parsed.truth.y_m = position_m(y_column);
    if (z_column) parsed.truth.z_m = position_m(*z_column);
    parsed.truth.heading_rad = deg_to_rad(number(heading_column));
    if (time_column) parsed.time_s = number(*time_column);
    if (odometry_x) {
      parsed.odometry = CameraPose{position_m(*odometry_x),
                                   position_m(*odometry_y),
                                   parsed.truth.z_m,
                                   deg_to_rad(number(*odometry_heading)),
                                   0.0,
                                   0.0};
    }
    std::error_code error;
    if (!std::filesystem::is_regular_file(parsed.image_file, error)) {
      throw InputError(where + ": image file '" + row.fields[file_column] + "' not found (" +
                       parsed.image_file.string() + ")");
    }
    rows_.push_back(std::move(parsed));
  }
}

std::optional<Frame> CsvSequence::next() {
  if (next_index_ == rows_.size()) return std::nullopt;
  const Row& row = rows_[next_index_];
  Frame frame;
  frame.index = static_cast<int>(next_index_);
  frame.time_s = row.time_s;
  frame.image = read_image(row.image_file);
  frame.truth = row.truth;
  frame.odometry = row.odometry;
  frame.source = row.image_file.string();
  size_check_.check(frame.image, frame.source);
  ++next_index_;
  return frame;
}

std::string CsvSequence::describe() const {
  return "CSV " + csv_file_.string() + " (" + std::to_string(rows_.size()) + " images, with poses)";
}

}  // namespace omninav::io
