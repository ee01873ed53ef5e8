#pragma once
// The frames of an input as panoramas, for every command that reads images: any input
// open_sequence reads, or a single image file, with raw omnidirectional images unwrapped on
// the fly (omni::Unwrapper, docs/design.md's Data formats) when the input says it needs it (a BoB
// database with needsUnwrapping) or the caller asks.
// A camera too: "camera:0" (camera_sequence.hpp).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "omninav/io/frame.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/omni/unwrap.hpp"

namespace omninav::io {

struct PanoramaInputOptions {
  bool force_unwrap = false;  // unwrap every frame, whatever the input says
  // Sources that are files as absolute paths, so that a map can find its images again from
  // any working directory; else as the input names them.
  bool absolute_sources = true;
  // A bag's image topic and pose topic (bag_sequence.hpp); only for a bag.
  std::string topic = {};
  std::string pose_topic = {};
};

class PanoramaInput {
 public:
  // `unwrap_params` is asked once, at the first frame to unwrap (camera.yaml's `unwrap:`).
  // Throws InputError as open_sequence and read_image do.
  PanoramaInput(const std::filesystem::path& input,
                std::function<omni::UnwrapParams()> unwrap_params, PanoramaInputOptions options);

  // The next frame with its image a panorama, or nothing at the end. Throws InputError naming
  // the frame's source when it cannot be unwrapped.
  std::optional<Frame> next();

  std::size_t size() const;
  // What is read, e.g. "BoB database grid/ (80 images, with poses) (unwrapped with camera.yaml)".
  std::string describe() const;
  bool is_grid() const;
  // What the reading adds to the results (SequenceReader::notes); empty when nothing.
  std::string notes() const;
  std::optional<double> grid_spacing_m() const;  // SequenceReader::grid_spacing_m
  bool unwraps() const { return unwrap_; }

 private:
  std::optional<std::filesystem::path> single_;  // a single image file
  bool single_done_ = false;
  std::unique_ptr<SequenceReader> reader_;  // otherwise
  std::function<omni::UnwrapParams()> unwrap_params_;
  PanoramaInputOptions options_;
  bool unwrap_ = false;
  std::optional<omni::Unwrapper> unwrapper_;
};

}  // namespace omninav::io
