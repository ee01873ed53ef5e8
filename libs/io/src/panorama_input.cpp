#include "omninav/io/panorama_input.hpp"

#include "omninav/core/errors.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/camera_sequence.hpp"
#include "omninav/io/image_file.hpp"

namespace omninav::io {

PanoramaInput::PanoramaInput(const std::filesystem::path& input,
                             std::function<omni::UnwrapParams()> unwrap_params,
                             PanoramaInputOptions options)
    : unwrap_params_(std::move(unwrap_params)), options_(options) {
  std::error_code error;
  const BagOptions bag{.topic = options.topic, .pose_topic = options.pose_topic};
  // With a topic, every input but a bag is open_sequence's UsageError.
  const bool has_topics = !bag.topic.empty() || !bag.pose_topic.empty();
  const std::optional<std::string> device = camera_device(input.string());
  if (device && !has_topics) {
    reader_ = std::make_unique<CameraSequence>(*device);
  } else if (std::filesystem::is_regular_file(input, error) && is_image_file_name(input) &&
             !has_topics) {
    single_ = input;
  } else {
    reader_ = open_sequence(input, bag);
  }
  unwrap_ = options.force_unwrap || (reader_ && reader_->needs_unwrapping());
}

std::optional<Frame> PanoramaInput::next() {
  std::optional<Frame> frame;
  if (single_) {
    if (single_done_) return std::nullopt;
    single_done_ = true;
    frame.emplace();
    frame->image = read_image(*single_);
    frame->source = single_->string();
  } else {
    frame = reader_->next();
    if (!frame) return std::nullopt;
  }
  std::error_code error;
  if (options_.absolute_sources && std::filesystem::is_regular_file(frame->source, error)) {
    frame->source = std::filesystem::absolute(frame->source).lexically_normal().string();
  }
  if (unwrap_) {
    if (!unwrapper_) unwrapper_.emplace(omni::make_unwrapper(unwrap_params_(), frame->image));
    try {
      frame->image = unwrapper_->unwrap(frame->image);
    } catch (const InputError& unwrap_error) {
      throw InputError(frame->source + ": " + unwrap_error.what());
    }
  }
  return frame;
}

std::size_t PanoramaInput::size() const {
  return single_ ? 1 : reader_->size();
}

std::string PanoramaInput::describe() const {
  return (single_ ? "image " + single_->string() : reader_->describe()) +
         (unwrap_ ? " (unwrapped with camera.yaml)" : "");
}

std::string PanoramaInput::notes() const {
  return reader_ ? reader_->notes() : std::string();
}

bool PanoramaInput::is_grid() const {
  return reader_ && reader_->is_grid();
}

std::optional<double> PanoramaInput::grid_spacing_m() const {
  return reader_ ? reader_->grid_spacing_m() : std::nullopt;
}

}  // namespace omninav::io
