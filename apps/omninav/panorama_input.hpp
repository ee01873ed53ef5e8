#pragma once
// Frames of an input as panoramas, for the commands that turn images into signatures
// (explore, localise): any input io::open_sequence reads, or single image files, with raw
// omnidirectional images unwrapped on the fly with camera.yaml (DESIGN.md, Data formats) when
// the input says it needs it (a BoB database with needsUnwrapping) or the user asks.

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "app_config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/omni/unwrap.hpp"

namespace omninav::cli {

class PanoramaInput {
 public:
  PanoramaInput(const std::filesystem::path& input, const std::filesystem::path& config_dir,
                bool force_unwrap)
      : input_(input), config_dir_(config_dir) {
    std::error_code error;
    if (std::filesystem::is_regular_file(input, error) && is_image_file(input)) {
      single_ = input;
    } else {
      reader_ = io::open_sequence(input);
      if (const auto* bob = dynamic_cast<const io::BobDatabaseReader*>(reader_.get())) {
        is_grid_ = bob->info().is_grid;
        unwrap_ = bob->info().needs_unwrapping.value_or(false);
      }
    }
    unwrap_ = unwrap_ || force_unwrap;
  }

  // The next frame with its image a panorama, or nothing at the end.
  std::optional<io::Frame> next() {
    std::optional<io::Frame> frame;
    if (single_) {
      if (done_) return std::nullopt;
      done_ = true;
      frame.emplace();
      frame->image = io::read_image(*single_);
      frame->source = single_->string();
    } else {
      frame = reader_->next();
      if (!frame) return std::nullopt;
    }
    // Sources that are files are kept as absolute paths, so that a map can find its images
    // again (export --what figures) from any working directory.
    std::error_code error;
    if (std::filesystem::is_regular_file(frame->source, error)) {
      frame->source = std::filesystem::absolute(frame->source).lexically_normal().string();
    }
    if (unwrap_) {
      if (!unwrapper_) {
        unwrapper_.emplace(
            omni::make_unwrapper(load_camera_config(config_dir_).unwrap, frame->image));
      }
      try {
        frame->image = unwrapper_->unwrap(frame->image);
      } catch (const InputError& unwrap_error) {
        throw InputError(frame->source + ": " + unwrap_error.what());
      }
    }
    return frame;
  }

  std::size_t size() const { return single_ ? 1 : reader_->size(); }
  std::string describe() const {
    return (single_ ? "image " + single_->string() : reader_->describe()) +
           (unwrap_ ? " (unwrapped with camera.yaml)" : "");
  }
  bool is_grid() const { return is_grid_; }

  static bool is_image_file(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" ||
           ext == ".tiff" || ext == ".ppm" || ext == ".pgm";
  }

 private:
  std::filesystem::path input_;
  std::filesystem::path config_dir_;
  std::optional<std::filesystem::path> single_;
  std::unique_ptr<io::SequenceReader> reader_;
  bool done_ = false;
  bool is_grid_ = false;
  bool unwrap_ = false;
  std::optional<omni::Unwrapper> unwrapper_;
};

}  // namespace omninav::cli
