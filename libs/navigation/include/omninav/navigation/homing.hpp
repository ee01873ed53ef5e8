#pragma once
// Homing on the goal image itself, once the navigator has recognised the goal's place: beyond
// Menegatti et al. 2004, §3.5, whose robot stops on recognising that place. The place's
// image was taken up to half a cell's diagonal from the goal and the robot recognises it from
// anywhere in its cell, so stopping there can leave the robot a whole spacing from the goal
// (docs/navigation.md). The view and the goal image are compared directly: the magnitudes'
// dissimilarity (Eq. 2) falls as the robot nears the goal, and min-warping's home vector gives
// the direction of the goal (compass/min_warping.hpp; without min-warping, the phases' motion
// estimate of §3.4, signature/motion.hpp).

#include <functional>
#include <memory>
#include <opencv2/core.hpp>

#include "omninav/compass/min_warping.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::navigation {

// What the robot's view says about the goal image.
struct GoalCue {
  // How far the goal seems: Eq. 2 between the view's and the goal image's signatures, per
  // compared value, times the map's metres per unit of it (homing_scale). §2.3: the
  // dissimilarity grows about linearly with distance over short distances.
  double distance_m = 0.0;
  double bearing_rad = 0.0;  // where the goal lies, counter-clockwise from the robot's front
  // The bearing is an estimate: false when either image is featureless (min-warping), or the
  // phases show no displacement (at the goal, or lost).
  bool valid = false;
};

using GoalHoming = std::function<GoalCue(const cv::Mat& panorama)>;

// What homing needs to know of the map: how its signatures are made and compared (Eq. 6's
// weights), and how many metres one unit of dissimilarity per value stands for (0: homing never
// moves).
struct HomingScale {
  signature::SignatureParams signature;
  signature::ComponentWeights weights;
  double metres_per_dissimilarity = 0.0;
  // The goal's bearing by min-warping's home vector; none, or a goal image narrower than its
  // search: by the phases.
  std::shared_ptr<const compass::MinWarping> warping;
};

// Compares views with `goal_image` (signatures made as `scale.signature` says). Throws
// InputError when the goal image is not a panorama.
GoalHoming goal_homing(const cv::Mat& goal_image, const HomingScale& scale);

}  // namespace omninav::navigation
