#pragma once
// The rotation between two panoramas, with the sub-pixel minimum, the amplitudes and a
// confidence: everything Algorithm 1 (visual_compass.hpp) needs from one pair I_i, I_j.
//
// Amplitudes (Labrosse 2006, §3.4.2):
//   A(I_i, I_j)  = d(a_m + W/2) − d(a_m)                 pixel resolution, Eq. 9
//   𝒜(I_i, I_j)  = d(α_m + W/2) − d_m                    sub-pixel, Eq. 12; d at the fractional
//                                                        shift α_m + W/2 is interpolated linearly
//                                                        between its two integer neighbours (the
//                                                        function is smooth there, Fig. 11)
//   normalised by A(I_i, I_i) = d(I_i, I_i, W/2)          Eq. 8 (the first image against itself:
//                                                        its minimum is 0 at shift 0, so the
//                                                        pixel and sub-pixel versions agree)
// Algorithm 1 tests the sub-pixel normalised amplitude 𝒜_n against its threshold (line 10); the
// mixture of Eqs. 10-11 is driven by the pixel-resolution A_n, which exists before the fit.
//
// Confidence, so that a user can tell a measurement from a guess:
//   featureless (§3.3.5): the distance function is flat. The amplitude of the pair, or of the
//       first image against itself, is below a mean difference of `flat_below_grey` grey levels
//       per compared component (RMS for L2): a uniform image, a horizontally uniform band, fog.
//   competing_minima (§4.3, GRASS2, Fig. 21): another local minimum at least
//       `competing_separation` away from the best one is less than `competing_depth_ratio`·A
//       above it: a moving object can be "pushed" out of the field of view either way, and the
//       two readings disagree. With the whole d(α) (exhaustive, fft) every local minimum is
//       examined; local_scan knows only the shifts it evaluated and descends from each scan
//       value that comes that close, flagging it when that descent ends far from the best.

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "omninav/compass/distance.hpp"
#include "omninav/compass/minimiser.hpp"
#include "omninav/compass/subpixel.hpp"

namespace omninav::compass {

struct ConfidenceParams {
  // Below this mean difference per compared component (grey levels, RMS for L2, mean absolute
  // for L1) the distance function counts as flat: featureless (§3.3.5). A label only (no heading
  // changes with it on the zoo); chosen across the zoo, leaving one family out, by how well it
  // flags frames whose turn is more than 5° off (docs/evaluation.md "Compass: Thresholds").
  double flat_below_grey = 8.0;
  // A second local minimum at least this far from the best one ...
  double competing_separation_rad = 10.0 * 3.14159265358979323846 / 180.0;
  // ... and less than this share of the amplitude A above it is a competing minimum (§4.3).
  double competing_depth_ratio = 0.15;
};

struct ConfidenceFlags {
  bool featureless = false;       // flat distance function (§3.3.5)
  bool competing_minima = false;  // two readings of the rotation (§4.3, Fig. 21)
  bool low_amplitude = false;     // set by Algorithm 1: even the frames it fell back on differ
                                  // more than its threshold allows (a large, fast change)
  bool ok() const { return !featureless && !competing_minima && !low_amplitude; }
  // "ok", or the flags joined by '+', e.g. "featureless+low_amplitude".
  std::string describe() const;
};

struct PairMatcherParams {
  DistanceParams distance;
  MinimiserParams minimiser;
  SubpixelParams subpixel;
  ConfidenceParams confidence;

  // The ranges of compass.yaml's distance, minimiser, phase, subpixel and confidence sections,
  // and the combinations that cannot work (fft needs l2). Throws UsageError naming the key
  // (core/param_check.hpp); PairMatcher's constructor calls it.
  void check() const;
};

struct PairMatch {
  int shift_px = 0;                // a_m, the integer minimum, signed in (−W/2, W/2]
  double subpixel_shift_px = 0.0;  // α_m (Eq. 11), signed
  double rotation_rad = 0.0;    // ρ = −α_m·2π/W (Eq. 4): from the first image to the second,
                                // counter-clockwise positive
  double distance_min = 0.0;    // d_m (Eq. 10)
  double amplitude = 0.0;       // 𝒜 (Eq. 12)
  double amplitude_norm = 0.0;  // 𝒜_n (Eq. 8); 0 when the first image is featureless
  double amplitude_norm_px = 0.0;  // A_n, pixel resolution (Eq. 9 normalised)
  double self_amplitude = 0.0;     // A(I_i, I_i), the normaliser
  double self_step = 0.0;  // d(I_i, I_i, 1 px): the first image against itself rolled by one
                           // column, the largest d_m a pure rotation can leave (its minimum is
                           // at most half a column from a whole shift); the compass's run-time
                           // floor for parallax (visual_compass.hpp)
  ConfidenceFlags flags;
  // The uncertainty of the minimum, columns: d_m / self_step, the residual expressed as the roll
  // of the first image against itself that costs as much (d grows about linearly with a small
  // roll). d_m is what the rotation cannot explain (parallax, tilt, noise). The slope is the
  // first image's own, not the pair's: parallax flattens the pair's function and would make the
  // ratio depend on the scene's texture (grass: 10° against 2-4° elsewhere for the same hop
  // errors, docs/compass.md "Uncertainty"). Infinite when the first image is uniform (a
  // featureless pair of textured images keeps its ratio: on the zoo such frames did not lose
  // the heading, and a uniform variance for them over-covered the rest of the route).
  double shift_sigma_px = 0.0;
  // The rotation of the other reading when there is one (competing_minima: the lowest other
  // local minimum found at least competing_separation away; the compass's global fallback sets
  // the candidate it rejected).
  std::optional<double> competing_rotation_rad;
  int evaluations = 0;  // distance evaluations by the fast kernel (FFT: the shifts it left to
                        // evaluate exactly and the sub-pixel fit's; the oracle: W)
};

class PairMatcher {
 public:
  // Throws UsageError for impossible combinations (see make_minimiser).
  explicit PairMatcher(const PairMatcherParams& params);
  ~PairMatcher();
  PairMatcher(const PairMatcher&) = delete;
  PairMatcher& operator=(const PairMatcher&) = delete;

  // Matches the second frame against the first (Eq. 2: the second is shifted). A local
  // minimiser starts at `start_shift_px`. Throws InputError when the frames differ in shape.
  PairMatch match(const CompassFrame& first, const CompassFrame& second,
                  int start_shift_px = 0) const;
  // The same match, its minimum the one the descent from `start_shift_px` ends in, with no scan
  // beyond it: the basin another estimate chose (the joint rotation, visual_compass.hpp), kept
  // even where another basin is lower.
  PairMatch match_in_basin(const CompassFrame& first, const CompassFrame& second,
                           int start_shift_px) const;

  // A(I, I) = d(I, I, W/2) (Eq. 8's normaliser), cached in the frame.
  double self_amplitude(const CompassFrame& frame) const;
  // d(I, I, 1 px), PairMatch::self_step, cached in the frame.
  double self_step(const CompassFrame& frame) const;

  // The distance function for panoramas `width_px` wide (made once per width).
  const DistanceFunction& distance_function(int width_px) const;
  const Minimiser& minimiser() const { return *minimiser_; }
  const PairMatcherParams& params() const { return params_; }

 private:
  // The match whose integer minimum `search` finds in the pair's table.
  PairMatch match_with(const CompassFrame& first, const CompassFrame& second,
                       const std::function<ShiftSearch(CostTable&)>& search) const;
  // A(I, I) (half_turn) or d(I, I, 1 px), cached in the frame by distance function.
  double self_distance(const CompassFrame& frame, bool half_turn) const;

  PairMatcherParams params_;
  std::unique_ptr<Minimiser> minimiser_;
  CostTable::Kernel kernel_;  // for the minimiser's tables and the self amplitudes
  mutable std::mutex mutex_;
  mutable std::map<int, std::unique_ptr<DistanceFunction>> distances_;
};

}  // namespace omninav::compass
