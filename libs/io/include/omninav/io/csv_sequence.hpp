#pragma once
// A CSV of images with ground-truth poses (docs/design.md, Data formats: Input sequences): one
// header row naming the columns, in any order, extra columns ignored.
//   required: file (relative to the CSV's folder, or absolute), x_m, y_m, heading_deg
//             (counter-clockwise from +x, REP 103)
//   optional: z_m (else 0), time_s (else no capture time), and the robot's own odometry
//             odometry_x_m, odometry_y_m, odometry_heading_deg (all three, or none)

#include <filesystem>
#include <optional>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/io/sequence.hpp"

namespace omninav::io {

class CsvSequence : public SequenceReader {
 public:
  // Reads and checks the whole CSV at once, so that a bad row fails before any image is used:
  // throws InputError "<csv>: missing column 'x_m'", "<csv>:<line>: ..." for a field that is
  // not a number, or naming the image and the line for an image file that does not exist.
  explicit CsvSequence(const std::filesystem::path& csv_file);

  std::optional<Frame> next() override;
  std::size_t size() const override { return rows_.size(); }
  std::string describe() const override;

 private:
  struct Row {
    std::filesystem::path image_file;
    CameraPose truth;
    std::optional<double> time_s;
    std::optional<CameraPose> odometry;
  };

  std::filesystem::path csv_file_;
  std::vector<Row> rows_;
  std::size_t next_index_ = 0;
  ImageSizeCheck size_check_;
};

}  // namespace omninav::io
