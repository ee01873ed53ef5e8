#include "omninav/navigation/homing.hpp"

#include "omninav/signature/motion.hpp"

namespace omninav::navigation {

GoalHoming goal_homing(const cv::Mat& goal_image, const HomingScale& scale) {
  // Shared: a std::function is copyable, the extractor is not.
  auto extractor = std::make_shared<signature::SignatureExtractor>(scale.signature);
  auto goal = std::make_shared<const signature::Signature>(
      extractor->compute(goal_image, "the goal image"));
  std::shared_ptr<const compass::MinWarpingView> warping_goal;
  // Min-warping needs panoramas at least as wide as its search; narrower cameras home by the
  // phases.
  if (scale.warping && goal_image.cols >= scale.warping->params().search_width_px) {
    warping_goal = std::make_shared<const compass::MinWarpingView>(
        scale.warping->prepare(goal_image, "the goal image"));
  }
  return [extractor, goal, warping_goal, scale](const cv::Mat& panorama) {
    const signature::Signature view = extractor->compute(panorama, "the robot's view");
    const double per_value = signature::dissimilarity(view, *goal, -1, scale.weights) /
                             static_cast<double>(goal->size());
    const double distance_m = per_value * scale.metres_per_dissimilarity;
    if (warping_goal) {
      const compass::MinWarpingResult home =
          scale.warping->estimate_resized(*warping_goal, panorama, "the robot's view");
      return GoalCue{distance_m, home.home_rad, !home.featureless};
    }
    const signature::MotionEstimate motion = signature::estimate_motion(view, *goal);
    return GoalCue{distance_m, motion.bearing_rad, motion.valid};
  };
}

}  // namespace omninav::navigation
