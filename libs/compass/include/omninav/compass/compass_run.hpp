#pragma once
// The visual compass over a sequence of panoramas as `omninav compass` runs it, and
// `omninav evaluate` with it: every panorama resampled to `width_px` columns first when a width
// is given (all of the sequence must share one width), the compass started at the first frame's
// true heading when it has one (Labrosse 2006, §4.1), else at 0.

#include <memory>
#include <optional>
#include <string>

#include "omninav/compass/visual_compass.hpp"

namespace omninav::compass {

class CompassRun {
 public:
  // Throws UsageError for parameters out of range (CompassParams::check).
  CompassRun(CompassParams params, std::optional<int> width_px);

  // The next frame's estimate. Throws InputError naming `source` for an empty image or one
  // whose width differs from the first frame's.
  CompassEstimate push(const cv::Mat& panorama, int frame_index, const std::string& source,
                       std::optional<double> truth_heading_rad);

  // VisualCompass::realign on the last frame pushed (its estimate, `estimate`, is updated).
  void realign(double heading_rad, double sigma_rad, CompassEstimate& estimate);

  bool started() const { return compass_ != nullptr; }
  int reference_count() const { return compass_ ? compass_->reference_count() : 0; }
  const CompassParams& params() const { return params_; }

 private:
  CompassParams params_;
  std::optional<int> width_px_;
  std::optional<int> input_width_px_;
  std::unique_ptr<VisualCompass> compass_;
};

}  // namespace omninav::compass
