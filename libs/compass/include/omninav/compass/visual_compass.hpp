#pragma once
// The visual compass: Algorithm 1 of Labrosse 2006, §3.5, and its fixed-skip variant
// "Fx n" (§4.3), over a sequence of panoramas pushed one at a time.
//
// Algorithm 1, as implemented (ω: orientations, r: rotations, all counter-clockwise positive):
//   first frame:  I_r ← I_c; ω_r ← ω_c ← initial heading; r_rc ← 0
//   each frame:   I_p ← I_c; I_c ← new frame; r_rp ← r_rc
//                 r_rc ← −α_m(I_r, I_c), minimised from the shift of r_rp            (line 9)
//                 if 𝒜_n(I_r, I_c) < t:                                              (line 10)
//                     ω_r ← ω_r + r_rp           the firewall: the reference's orientation
//                                                changes only when it is replaced     (line 11)
//                     r_rc ← −α_m(I_p, I_c), minimised from 0                         (line 12)
//                     I_r ← I_p                                                       (line 13)
//                 ω_c ← ω_r + r_rc                                                    (line 15)
// with t = 0.6055 (Table 2). When I_p is I_r itself (the second frame of a sequence) there is
// nothing to fall back on: the match stands and is flagged low_amplitude.
//
// BEYOND THE PAPER: the rotation cap. Line 10's test also succeeds when |r_rc| exceeds
// max_reference_rotation_rad while the pair shows parallax: its minimum d_m is above what a pure
// rotation can leave, parallax_step_ratio·d(I_r, I_r, 1 column). Why the cap: the field of view
// moves with the second image (§3.4.3), centred on ITS front and back, but on a curved path the
// translation between the two frames points along the chord, half the rotation away; the
// bands then sit off the focus of expansion, the expansion inside them is lopsided, and the
// minimum of d is biased by an amount that grows with rotation × translation and keeps its sign
// while the robot keeps turning one way. With t alone a reference can last 61° of turn and
// 0.96 m on the rendered CIRCLE (21° max error over three turns); the cap bounds it
// (docs/compass.md). Why the parallax test: every new reference adds the sub-pixel fit's
// error, and that error is a bias (the fit is pulled towards whole columns, and a steady turn
// gives every hop the same fraction of a column), so needless references make a pure rotation
// drift (6.9° over three turns in the field at 360 columns with a reference every 5°). A pure
// rotation matches at a whole shift to within half a column, so its minimum stays below the
// reference against itself rolled by one column: that distance, measured on the reference at
// run time, is the floor (nothing fitted to a scene). max_reference_rotation_rad = 0 gives the
// paper's Algorithm 1 exactly.
//
// "Fx n" (§4.3: "skipping a fixed number of frames"): the same loop with line 10's test
// replaced by "I_c is more than n + 1 frames after I_r". The reference frames are then frames
// 0, n+1, 2(n+1), ...; each is measured against the one before it, and every frame in between
// against the latest reference. Fx 0 compares successive frames: the 2004 compass (Fig. 3 of
// Labrosse 2004) when used with the exhaustive minimiser and no sub-pixel fit.

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "omninav/compass/frame.hpp"
#include "omninav/compass/min_warping.hpp"
#include "omninav/compass/pair_matcher.hpp"

namespace omninav::compass {

enum class SamplingPolicy {
  kThreshold,  // Algorithm 1: switch the reference when 𝒜_n < t ("Atm t" in Tables 3-4)
  kFixedSkip,  // "Fx n": a new reference every n + 1 frames
};

struct SamplingParams {
  SamplingPolicy policy = SamplingPolicy::kThreshold;
  // t, Algorithm 1 line 1 and Table 2: the median normalised amplitude at the best skip + 1 on
  // CIRCLE1 (Table 1 of Labrosse 2006).
  double threshold_norm_amp = 0.6055;
  // n of "Fx n": frames skipped between references.
  int fixed_skip_frames = 3;
  // Ours (the rotation cap above): also replace the reference when the rotation from it exceeds
  // this, radians, once the pair shows parallax; 0: off (the paper's Algorithm 1). 4° keeps the
  // bands within 2° of the direction of travel; chosen across the zoo leaving one family out
  // (docs/evaluation.md "Compass: Thresholds"; it was 6°, chosen in the built-in room).
  double max_reference_rotation_rad = 4.0 * 3.14159265358979323846 / 180.0;
  // Parallax shown: the pair's minimum d_m above this multiple of d(I_r, I_r, 1 column)
  // (PairMatch::self_step), the most a pure rotation leaves (above). 1: the bound itself, not a
  // value fitted to a scene.
  double parallax_step_ratio = 1.0;
};

// Fast turns (ours; docs/compass.md "Fast turns"). The zoo's wanders turn 15-30° between
// frames at 10 frames/s: the amplitude of every pair falls below t, Algorithm 1 takes a new
// reference at every frame, and line 12 starts the local scan at 0, whose descent and ±10° scan
// end in a wrong local minimum, 10-40° on the other side of 0. The global fallback: when a
// local minimiser's (local_scan, phase) match has 𝒜_n below t, the whole d(α) is searched (fft,
// exhaustive under l1), and its global minimum replaces the local one when it is lower and
// either a clear match (𝒜_n >= t, Algorithm 1's own test, and no competing minimum) or nearer
// the rotation the last frame's turn predicts (a constant turn rate). Without that second
// condition the aliased grass at 10 cm, whose pairs 1° apart have global minima 60-180° away,
// and the ofstad arena's near-blank views close to its wall are lost. No threshold of its own: t is
// Table 2's; frames whose local match passes t pay nothing.
struct FastTurns {
  // Measured on the zoo: docs/compass.md "Fast turns". A turn of 105° in one frame next to a wall
  // (house-s1's wander), whose global minimum the fallback's tests reject, is min-warping's joint
  // rotation's to catch (min_warping.in_compass); without it (in_compass false, panoramas
  // narrower than its search) such a turn is lost.
  bool global_fallback = true;
};

// The heading's standard deviation (ours; docs/compass.md "Uncertainty"). Each match's variance
// is (PairMatch::shift_sigma_px in radians)² plus (half the gap to its other reading)² when it has
// one (a two-point distribution's variance), at most π²/3 (uniform on the circle). The heading is
// ω_r + r_rc, and ω_r a sum of the r_rp of every reference change, so the variances of those add up
// along the chain of references. `scale` multiplies the standard deviation: it is the one number
// calibrated against ground truth (compass.yaml says how).
struct UncertaintyParams {
  double scale = 0.472;  // compass.yaml's uncertainty.scale
};

// The joint rotation (ours; issue 30; docs/compass.md "The compass while travelling"). Under
// translation the pure-rotation distance's lowest minimum can be a parallax-shifted one, 10-40°
// off (room-s1's wander: 32° max error). Where a pair shows parallax (the rotation cap's test:
// d_m above the reference against itself rolled one column), min-warping (min_warping.hpp)
// estimates the rotation and the direction of travel together, and the pair's minimum becomes
// the pure-rotation distance's minimum in min-warping's basin when the pair's own evidence
// agrees: (1) min-warping's rotation is more than one search step (its resolution) from the
// pure-rotation minimum; (2) the pair matched the other way round gives the opposite rotation
// within one search step (aliased or near-blank pairs fit a direction by chance and their two
// searches disagree); (3) the descent of the pure-rotation distance from min-warping's rotation
// ends within one search step of it (the turn alone has a minimum there). No threshold fitted to
// a world: the one tolerance is the search step. The pure rotation's reading is kept as the
// match's other reading for the uncertainty. Algorithm 1's reference switching acts on the
// resulting match as on any other.
struct JointRotationParams {
  bool enabled = true;        // compass.yaml's min_warping.in_compass
  MinWarpingParams warping;   // compass.yaml's min_warping section
  PanoramaGeometry geometry;  // the rows' elevations (camera.yaml's panorama section)
};

struct CompassParams {
  PairMatcherParams matcher;
  SamplingParams sampling;
  FastTurns fast_turns;
  UncertaintyParams uncertainty;
  JointRotationParams joint;

  // The ranges of compass.yaml's keys for these (the matcher's too). Throws UsageError naming
  // the key (core/param_check.hpp); the loader and VisualCompass's constructor call it.
  void check() const;
};

// What the compass says about one frame.
struct CompassEstimate {
  int frame_index = 0;          // CompassFrame::index()
  double heading_rad = 0.0;     // ω_c, unwrapped (turns accumulate; wrap it for display)
  double rotation_rad = 0.0;    // ω_c − ω of the previous frame
  double amplitude_norm = 0.0;  // 𝒜_n of the pair that gave r_rc (1 for the first frame)
  int reference_index = 0;      // CompassFrame::index() of the reference I_r used
  bool new_reference = false;   // the reference changed at this frame (lines 11-13)
  double shift_px = 0.0;        // α_m of that pair (sub-pixel)
  ConfidenceFlags flags;
  int evaluations = 0;  // distance evaluations spent on this frame
  // The heading's standard deviation, radians (UncertaintyParams): 0 for the first frame, then
  // growing with every reference change.
  double heading_sigma_rad = 0.0;
  // The heading was set from outside after the match (VisualCompass::realign: a recognised
  // place of a map).
  bool realigned = false;
};

class VisualCompass {
 public:
  // Throws UsageError for parameters out of range (CompassParams::check).
  explicit VisualCompass(const CompassParams& params, double initial_heading_rad = 0.0);
  ~VisualCompass();
  VisualCompass(const VisualCompass&) = delete;
  VisualCompass& operator=(const VisualCompass&) = delete;

  // Feeds the next frame and returns its estimate. Throws InputError naming the frame when it
  // differs in shape from the first one.
  CompassEstimate push(const CompassFrame& frame);

  // Re-aligns the last frame pushed on a heading measured otherwise (a place of a map recognised
  // in it, Labrosse 2006's abstract: "only requiring infrequent re-alignment, for
  // example when re-localising in a topological map"), with that measure's standard deviation.
  // ω_r moves so that ω_c = heading_rad (unwrapped next to ω_c); the chain's variance restarts
  // from sigma_rad, so later frames grow from it. `estimate`, the last push's, is updated: its
  // heading, rotation and sigma, and `realigned`. Throws UsageError before the first frame.
  void realign(double heading_rad, double sigma_rad, CompassEstimate& estimate);

  // Frames pushed so far, and how many of them served as a reference (the "Nb" of Tables 3-4).
  int frame_count() const { return frame_count_; }
  int reference_count() const { return reference_count_; }

  const CompassParams& params() const { return params_; }
  const PairMatcher& matcher() const { return matcher_; }

 private:
  // Whether the match of line 9 passes the rotation cap (ours, see above).
  bool beyond_rotation_cap(const PairMatch& match, double rotation_ref_previous_rad) const;
  // The match of the local minimiser, or the global search's where it is poor (FastTurns),
  // then in the joint rotation's basin where it applies (JointRotationParams).
  PairMatch match_pair(const CompassFrame& first, const CompassFrame& second, int start_shift,
                       double predicted_rotation_rad) const;
  PairMatch pure_rotation_match(const CompassFrame& first, const CompassFrame& second,
                                int start_shift, double predicted_rotation_rad) const;
  PairMatch joint_rotation_match(const CompassFrame& first, const CompassFrame& second,
                                 PairMatch pure) const;

  CompassParams params_;
  PairMatcher matcher_;
  std::unique_ptr<PairMatcher> global_matcher_;  // FastTurns, when the minimiser is local
  // Min-warping's view of a frame, prepared once for the frames in use: the reference meets
  // every frame that follows it, and a frame is the second of one pair and the first of the next.
  std::shared_ptr<const MinWarpingView> warping_view(const CompassFrame& frame) const;

  std::unique_ptr<MinWarping> warping_;  // JointRotationParams, when enabled
  // The views of the frames used last, most recent last (a few: the reference and the newest).
  mutable std::vector<std::pair<CompassFrame, std::shared_ptr<const MinWarpingView>>>
      warping_views_;
  double initial_heading_rad_;
  std::optional<CompassFrame> reference_;
  std::optional<CompassFrame> current_;
  int reference_position_ = 0;  // position in the sequence of I_r
  int frame_count_ = 0;
  int reference_count_ = 0;
  double reference_heading_rad_ = 0.0;     // ω_r
  double rotation_ref_current_rad_ = 0.0;  // r_rc
  double current_heading_rad_ = 0.0;       // ω_c
  double last_rotation_rad_ = 0.0;         // ω_c − ω_p of the last frame (FastTurns)
  double previous_heading_rad_ = 0.0;      // ω_p, the frame before the last (realign)
  double reference_variance_rad2_ = 0.0;   // var(ω_r): the r_rp of every reference change
  double current_variance_rad2_ = 0.0;     // var(r_rc)
};

// A match's variance, radians² (UncertaintyParams), before the scale.
double match_variance_rad2(const PairMatch& match, int width_px);

// How Tables 3-4 name the method: "Atm 0.6055", "Fx 3"; Algorithm 1 with the rotation cap on
// says so: "Atm 0.6055 cap 4°".
std::string describe(const SamplingParams& sampling);

}  // namespace omninav::compass
