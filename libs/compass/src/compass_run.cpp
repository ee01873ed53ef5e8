#include "omninav/compass/compass_run.hpp"

#include "omninav/compass/resample.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {

CompassRun::CompassRun(CompassParams params, std::optional<int> width_px)
    : params_(std::move(params)), width_px_(width_px) {
  params_.check();  // now, not at the first frame
}

CompassEstimate CompassRun::push(const cv::Mat& panorama, int frame_index,
                                 const std::string& source,
                                 std::optional<double> truth_heading_rad) {
  if (panorama.empty()) throw InputError(source + ": empty image");
  if (!input_width_px_) {
    input_width_px_ = panorama.cols;
  } else if (panorama.cols != *input_width_px_) {
    throw InputError(source + ": " + std::to_string(panorama.cols) +
                     " columns where the sequence's first image has " +
                     std::to_string(*input_width_px_));
  }
  const cv::Mat resampled =
      width_px_ && *width_px_ != panorama.cols ? resample_columns(panorama, *width_px_) : panorama;
  if (!compass_) {
    compass_ = std::make_unique<VisualCompass>(params_, truth_heading_rad.value_or(0.0));
  }
  return compass_->push(CompassFrame(resampled, frame_index, source));
}

void CompassRun::realign(double heading_rad, double sigma_rad, CompassEstimate& estimate) {
  if (!compass_) throw UsageError("the compass can only re-align a frame it has seen");
  compass_->realign(heading_rad, sigma_rad, estimate);
}

}  // namespace omninav::compass
