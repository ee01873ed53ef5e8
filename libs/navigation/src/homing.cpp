#include "omninav/navigation/homing.hpp"

#include "omninav/signature/motion.hpp"

namespace omninav::navigation {

GoalHoming goal_homing(const cv::Mat& goal_image, const HomingScale& scale) {
  // Shared: a std::function is copyable, the extractor is not.
  auto extractor = std::make_shared<signature::SignatureExtractor>(scale.signature);
  auto goal = std::make_shared<const signature::Signature>(
      extractor->compute(goal_image, "the goal image"));
  return [extractor, goal, scale](const cv::Mat& panorama) {
    const signature::Signature view = extractor->compute(panorama, "the robot's view");
    const signature::MotionEstimate motion = signature::estimate_motion(view, *goal);
    const double per_value = signature::dissimilarity(view, *goal, -1, scale.weights) /
                             static_cast<double>(goal->size());
    return GoalCue{per_value * scale.metres_per_dissimilarity, motion.bearing_rad, motion.valid};
  };
}

}  // namespace omninav::navigation
