#include "omninav/compass/visual_compass.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::compass {

std::string describe(const SamplingParams& sampling) {
  if (sampling.policy == SamplingPolicy::kFixedSkip) {
    return fmt::format("Fx {}", sampling.fixed_skip_frames);
  }
  std::string text = "Atm " + general(sampling.threshold_norm_amp);
  if (sampling.max_reference_rotation_rad > 0.0) {
    text += fmt::format(" cap {}°", general(rad_to_deg(sampling.max_reference_rotation_rad)));
  }
  return text;
}

namespace {

// The global minimiser for FastTurns::global_fallback, or none when the configured one is already
// global.
std::unique_ptr<PairMatcher> make_global_matcher(const CompassParams& params) {
  const MinimiserKind kind = params.matcher.minimiser.kind;
  if (!params.fast_turns.global_fallback || kind == MinimiserKind::kFft ||
      kind == MinimiserKind::kExhaustive) {
    return nullptr;
  }
  PairMatcherParams global = params.matcher;
  global.minimiser.kind = params.matcher.distance.metric == Metric::kL2
                              ? MinimiserKind::kFft
                              : MinimiserKind::kExhaustive;
  return std::make_unique<PairMatcher>(global);
}

}  // namespace

double match_variance_rad2(const PairMatch& match, int width_px) {
  constexpr double kUniform = kPi * kPi / 3.0;  // a heading uniform on the circle
  if (!std::isfinite(match.shift_sigma_px)) return kUniform;
  const double sigma_rad = match.shift_sigma_px * kTwoPi / width_px;
  double variance = sigma_rad * sigma_rad;
  if (match.competing_rotation_rad) {
    const double gap_rad = signed_difference(*match.competing_rotation_rad, match.rotation_rad);
    variance += gap_rad * gap_rad / 4.0;
  }
  return std::min(variance, kUniform);
}

void CompassParams::check() const {
  matcher.check();
  check_range("sampling.threshold_norm_amp", sampling.threshold_norm_amp, 0.0, 1.0);
  check_range("sampling.fixed_skip_frames", sampling.fixed_skip_frames, 0, 100000);
  check_range_deg("sampling.max_reference_rotation_deg", sampling.max_reference_rotation_rad, 0.0,
                  180.0);
  check_range("sampling.parallax_step_ratio", sampling.parallax_step_ratio, 0.0, 10.0);
  check_range("uncertainty.scale", uncertainty.scale, 0.0, 1000.0);
  if (joint.enabled) joint.warping.check();
}

VisualCompass::VisualCompass(const CompassParams& params, double initial_heading_rad)
    : params_(params),
      matcher_(params.matcher),
      global_matcher_(make_global_matcher(params)),
      warping_(params.joint.enabled
                   ? std::make_unique<MinWarping>(params.joint.warping, params.joint.geometry)
                   : nullptr),
      initial_heading_rad_(initial_heading_rad) {
  params.check();
}

VisualCompass::~VisualCompass() = default;

bool VisualCompass::beyond_rotation_cap(const PairMatch& match,
                                        double rotation_ref_previous_rad) const {
  const SamplingParams& sampling = params_.sampling;
  if (!(sampling.max_reference_rotation_rad > 0.0)) return false;
  // r_rc as line 15 will use it: unwrapped next to r_rp.
  const double rotation_rad =
      rotation_ref_previous_rad + signed_difference(match.rotation_rad, rotation_ref_previous_rad);
  const bool parallax = match.distance_min > sampling.parallax_step_ratio * match.self_step;
  return std::abs(rotation_rad) > sampling.max_reference_rotation_rad && parallax;
}

PairMatch VisualCompass::match_pair(const CompassFrame& first, const CompassFrame& second,
                                    int start_shift, double predicted_rotation_rad) const {
  return joint_rotation_match(
      first, second, pure_rotation_match(first, second, start_shift, predicted_rotation_rad));
}

std::shared_ptr<const MinWarpingView> VisualCompass::warping_view(const CompassFrame& frame) const {
  // Frames are told apart by their caches, which copies share (frame.hpp); the frames kept here
  // hold theirs alive, so no other frame can take their address.
  constexpr std::size_t kKept = 3;
  const auto same = [&frame](const auto& kept) { return &kept.first.caches() == &frame.caches(); };
  auto found = std::find_if(warping_views_.begin(), warping_views_.end(), same);
  if (found == warping_views_.end()) {
    if (warping_views_.size() == kKept) warping_views_.erase(warping_views_.begin());
    warping_views_.emplace_back(frame, std::make_shared<const MinWarpingView>(
                                           warping_->prepare(frame.image(), frame.source())));
  } else {
    std::rotate(found, found + 1, warping_views_.end());  // the most recent last
  }
  return warping_views_.back().second;
}

PairMatch VisualCompass::joint_rotation_match(const CompassFrame& first, const CompassFrame& second,
                                              PairMatch pure) const {
  // On the spot a turn explains the pair: its minimum stays within the reference against itself
  // rolled by one column (the rotation cap's parallax test), and min-warping is not asked.
  if (!warping_ || !(pure.distance_min > params_.sampling.parallax_step_ratio * pure.self_step)) {
    return pure;
  }
  // Panoramas narrower than the search have nothing finer to offer it: the pure rotation stands.
  if (first.width() < params_.joint.warping.search_width_px) return pure;
  const std::shared_ptr<const MinWarpingView> a = warping_view(first);
  const std::shared_ptr<const MinWarpingView> b = warping_view(second);
  const MinWarpingResult forward = warping_->estimate(*a, *b);
  // One search step: the joint estimate's own resolution, below which it cannot tell two
  // rotations apart.
  const double step_rad = kTwoPi / params_.joint.warping.search_width_px;
  const auto apart = [step_rad](double x_rad, double y_rad) {
    return std::abs(signed_difference(x_rad, y_rad)) > step_rad;
  };
  if (forward.featureless || !apart(forward.rotation_rad, pure.rotation_rad)) return pure;
  // The pair the other way round must give the opposite turn: aliased or near-blank pairs fit
  // one direction by chance, and their two searches disagree.
  if (apart(forward.rotation_rad, -warping_->estimate(*b, *a).rotation_rad)) return pure;
  const int width = first.width();
  PairMatch joint = matcher_.match_in_basin(
      first, second,
      static_cast<int>(std::lround(-shift_px_of_rotation(forward.rotation_rad, width))));
  joint.evaluations += pure.evaluations;
  // The turn alone must have a minimum where the joint estimate says: a descent that walks
  // away from it found no basin there.
  if (apart(joint.rotation_rad, forward.rotation_rad)) {
    pure.evaluations = joint.evaluations;
    return pure;
  }
  // The pure rotation's reading is kept for the uncertainty, as the fallback's other reading is.
  const double separation_rad = params_.matcher.confidence.competing_separation_rad;
  if (std::abs(signed_difference(pure.rotation_rad, joint.rotation_rad)) >= separation_rad) {
    joint.competing_rotation_rad = pure.rotation_rad;
  }
  return joint;
}

PairMatch VisualCompass::pure_rotation_match(const CompassFrame& first, const CompassFrame& second,
                                             int start_shift, double predicted_rotation_rad) const {
  PairMatch local = matcher_.match(first, second, start_shift);
  if (!global_matcher_ || !(local.amplitude_norm < params_.sampling.threshold_norm_amp)) {
    return local;
  }
  PairMatch global = global_matcher_->match(first, second, start_shift);
  const int evaluations = local.evaluations + global.evaluations;
  // The global minimum replaces the local one when it is lower and either a clear match
  // (Algorithm 1's own test 𝒜_n >= t, and no competing minimum) or nearer the prediction.
  const bool nearer = std::abs(signed_difference(global.rotation_rad, predicted_rotation_rad)) <
                      std::abs(signed_difference(local.rotation_rad, predicted_rotation_rad));
  const bool good = global.amplitude_norm >= params_.sampling.threshold_norm_amp &&
                    !global.flags.competing_minima;
  const bool take_global = global.distance_min < local.distance_min && (nearer || good);
  PairMatch& best = take_global ? global : local;
  const PairMatch& other = take_global ? local : global;
  best.evaluations = evaluations;
  // Two readings far apart: the other one is kept for the uncertainty (match_variance_rad2).
  const double separation_rad = params_.matcher.confidence.competing_separation_rad;
  if (std::abs(signed_difference(other.rotation_rad, best.rotation_rad)) >= separation_rad) {
    best.competing_rotation_rad = other.rotation_rad;
  }
  return best;
}

CompassEstimate VisualCompass::push(const CompassFrame& frame) {
  CompassEstimate estimate;
  estimate.frame_index = frame.index();
  if (!current_) {
    // Lines 2-4: the first image is the reference; ω_r = ω_c = the initial heading.
    reference_ = frame;
    current_ = frame;
    reference_position_ = 0;
    frame_count_ = 1;
    reference_count_ = 1;
    reference_heading_rad_ = initial_heading_rad_;
    current_heading_rad_ = initial_heading_rad_;
    previous_heading_rad_ = initial_heading_rad_;
    reference_variance_rad2_ = 0.0;
    current_variance_rad2_ = 0.0;
    rotation_ref_current_rad_ = 0.0;
    estimate.heading_rad = current_heading_rad_;
    estimate.amplitude_norm = 1.0;
    estimate.reference_index = frame.index();
    estimate.new_reference = true;
    return estimate;
  }
  require_same_shape(*reference_, frame);

  const CompassFrame previous = *current_;  // line 6
  current_ = frame;                         // line 7
  ++frame_count_;
  const double rotation_ref_previous_rad = rotation_ref_current_rad_;  // line 8
  const double previous_heading_rad = current_heading_rad_;
  const int width = frame.width();
  // The turn expected between the previous frame and this one, for the global fallback's
  // choice (FastTurns): the last frame's.
  const double predicted_turn_rad = last_rotation_rad_;

  const bool previous_is_reference = frame_count_ - 2 == reference_position_;
  const bool fixed_skip = params_.sampling.policy == SamplingPolicy::kFixedSkip;
  PairMatch match;
  bool switch_reference = false;
  if (fixed_skip) {
    // "Fx n" decides from positions alone, so line 9's match is skipped when it switches.
    switch_reference =
        frame_count_ - 1 - reference_position_ > params_.sampling.fixed_skip_frames + 1;
  }
  if (!switch_reference) {
    // Line 9, started from the shift of r_rp (§3.5, "In the actual implementation").
    const int start_shift =
        static_cast<int>(std::lround(-shift_px_of_rotation(rotation_ref_previous_rad, width)));
    match =
        match_pair(*reference_, frame, start_shift, rotation_ref_previous_rad + predicted_turn_rad);
    estimate.evaluations = match.evaluations;
    // Line 10, and the rotation cap (visual_compass.hpp: ours, not the paper's).
    switch_reference = !fixed_skip && (match.amplitude_norm < params_.sampling.threshold_norm_amp ||
                                       beyond_rotation_cap(match, rotation_ref_previous_rad));
  }
  if (switch_reference) {
    if (!previous_is_reference) {
      reference_variance_rad2_ += current_variance_rad2_;   // var(r_rp) joins var(ω_r)
      reference_heading_rad_ += rotation_ref_previous_rad;  // line 11, the firewall
      const int evaluations = estimate.evaluations;
      match = match_pair(previous, frame, 0, predicted_turn_rad);  // line 12, started from 0
      estimate.evaluations = evaluations + match.evaluations;
      reference_ = previous;  // line 13
      reference_position_ = frame_count_ - 2;
      ++reference_count_;
      estimate.new_reference = true;
    }
    // Even the frame just before is too different (or there is none to fall back on).
    if (!fixed_skip && match.amplitude_norm < params_.sampling.threshold_norm_amp) {
      match.flags.low_amplitude = true;
    }
  }
  // r_rc moves little from frame to frame, so it is unwrapped next to r_rp: a reference that is
  // never replaced (a pure rotation on the spot matches perfectly at any angle) still
  // accumulates whole turns. After a switch r_rc is the small rotation between two frames.
  rotation_ref_current_rad_ =
      estimate.new_reference ? match.rotation_rad
                             : rotation_ref_previous_rad +
                                   signed_difference(match.rotation_rad, rotation_ref_previous_rad);
  current_heading_rad_ = reference_heading_rad_ + rotation_ref_current_rad_;  // line 15
  current_variance_rad2_ = match_variance_rad2(match, width);
  estimate.heading_sigma_rad =
      params_.uncertainty.scale * std::sqrt(reference_variance_rad2_ + current_variance_rad2_);

  estimate.heading_rad = current_heading_rad_;
  previous_heading_rad_ = previous_heading_rad;
  estimate.rotation_rad = current_heading_rad_ - previous_heading_rad;
  last_rotation_rad_ = estimate.rotation_rad;
  estimate.amplitude_norm = match.amplitude_norm;
  estimate.reference_index = reference_->index();
  estimate.shift_px = match.subpixel_shift_px;
  estimate.flags = match.flags;
  return estimate;
}

void VisualCompass::realign(double heading_rad, double sigma_rad, CompassEstimate& estimate) {
  if (!current_) throw UsageError("the compass can only re-align a frame it has seen");
  if (!(sigma_rad >= 0.0)) throw UsageError("a re-alignment needs a standard deviation >= 0");
  // Unwrapped next to ω_c, so that whole turns stay accumulated.
  current_heading_rad_ += signed_difference(heading_rad, current_heading_rad_);
  reference_heading_rad_ = current_heading_rad_ - rotation_ref_current_rad_;
  // var(ω_c) = var(ω_r) + var(r_rc) before the scale: the re-alignment's variance is all ω_c's.
  const double scale = params_.uncertainty.scale;
  const double variance_rad2 = scale > 0.0 ? (sigma_rad / scale) * (sigma_rad / scale) : 0.0;
  reference_variance_rad2_ = variance_rad2;
  current_variance_rad2_ = 0.0;
  estimate.heading_rad = current_heading_rad_;
  // The jump is the output's rotation; the fast-turn prediction keeps the compass's own turn.
  estimate.rotation_rad = current_heading_rad_ - previous_heading_rad_;
  estimate.heading_sigma_rad = sigma_rad;
  estimate.realigned = true;
}

}  // namespace omninav::compass
