#pragma once
// Readers of image sequences (docs/design.md, Data formats: Input sequences). Every reader checks
// its input and throws InputError naming the file (and line, for text files) on bad input:
// unreadable or corrupt image, mixed image sizes, empty folder, missing CSV column,
// non-numeric field, database entries whose image files are missing.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "omninav/io/frame.hpp"

namespace omninav::io {

class SequenceReader {
 public:
  virtual ~SequenceReader() = default;

  // The next frame in order, or nothing at the end. Throws InputError on a bad frame.
  virtual std::optional<Frame> next() = 0;

  // How many frames the sequence holds (for a video, what its container says).
  virtual std::size_t size() const = 0;

  // One line saying what is being read, e.g. "BoB database grid/ (80 images, with poses)".
  virtual std::string describe() const = 0;

  // Whether the frames are raw omnidirectional images to unwrap (a BoB database marked
  // needsUnwrapping), and whether they lie on a grid (a BoB grid database).
  virtual bool needs_unwrapping() const { return false; }
  virtual bool is_grid() const { return false; }
  // The distance between neighbouring points of a grid, metres, when the input states it (a
  // BoB grid database's metadata `grid.separationMM`); nothing otherwise.
  virtual std::optional<double> grid_spacing_m() const { return std::nullopt; }
  // Whether the frames come from a video file (they have no file names of their own).
  virtual bool is_video() const { return false; }
  // What the reading itself adds to the results, for a command's log and a map's run: e.g. a
  // camera's frames dropped when the processing fell behind, or its stop by Ctrl-C. Empty when
  // nothing.
  virtual std::string notes() const { return {}; }
};

// Opens `path` as whichever kind it is:
//   - a folder holding database_entries.csv: a BoB robotics image database;
//   - any other folder: its images (is_image_file_name), natural sort;
//   - a bag (bag_sequence.hpp: .bag, .mcap, .db3, a folder holding metadata.yaml), its only
//     image topic, no poses (open_bag chooses topics);
//   - a .csv file: rows of `file, x_m, y_m, heading_deg` (files relative to the CSV);
//   - any other file: a video, read with cv::VideoCapture.
// (A camera, "camera:0", opens through PanoramaInput: camera_sequence.hpp.)
std::unique_ptr<SequenceReader> open_sequence(const std::filesystem::path& path);

// Reads every frame (convenience for small sequences and tests).
std::vector<Frame> read_all(SequenceReader& reader);

}  // namespace omninav::io
