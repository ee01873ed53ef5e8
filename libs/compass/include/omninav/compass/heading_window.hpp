#pragma once
// The multi-baseline window (ours; docs/compass.md "Many baselines"): less drift, and wrong
// matches outvoted, by measuring each frame against several earlier frames and solving the
// headings of a sliding window together, instead of chaining one reference (Algorithm 1 of
// Labrosse 2006, §3.5).
//
// Measurements. Algorithm 1 (visual_compass.hpp) gives each frame one: r_rc, the rotation from
// its reference (CompassEstimate::reference_rotation_rad). The window adds the frame matched
// against up to K earlier keyframes, the frames that served as a reference before the current
// one: the local minimiser started from the rotation the window predicts, and where that match
// fails Table 2's t the whole d(α) (fft; exhaustive under l1), whose global minimum does not
// depend on the prediction. A match counts while the amplitude allows it: 𝒜_n >= t (Algorithm
// 1's own test, no new threshold), not featureless and without a competing minimum; a keyframe
// whose match fails is dropped (the robot has moved away from it). Each match is a relative
// heading θ_to − θ_from = ρ with the standard deviation of the uncertainty model
// (match_variance_rad2) and, under it, the sub-pixel fit's own: a uniform error of one column,
// 1/12 column² (so that a perfect match does not weigh infinitely).
//
// Long baselines (WindowParams::gate_long_baselines, off by default): a keyframe's match beyond
// the rotation cap with parallax is a hop the cap would have cut, biased by the turn's parallax;
// with the gate it counts only where the baselines together put the frame two readings' separation
// (confidence.competing_separation) or more from Algorithm 1's reading.
//
// Solution. The new frame's heading starts at the prediction of one of its measurements, the one
// the others agree with best (the least total robust loss): a chain that took a wrong minimum is
// not where the solver starts when the other baselines disagree with it. Then the headings of
// the last N frames are solved together, min Σ ρ_Cauchy(wrap(θ_to − θ_from − ρ)/σ), by Ceres;
// headings older than the window stay as they were last solved (fixed), frame 0 is the start.
// Every heading may be revised while it is in the window: push() returns the frame's first
// estimate (a stream cannot wait), headings_rad() every frame's latest, which is final once the
// frame has left the window (CompassRun::revise: what `omninav compass` writes).

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "omninav/compass/visual_compass.hpp"

namespace omninav::compass {

class HeadingWindow {
 public:
  // Throws UsageError for impossible parameters (keyframes < 0, length_frames < 2, loss_scale
  // <= 0).
  explicit HeadingWindow(const CompassParams& params);
  ~HeadingWindow();
  HeadingWindow(const HeadingWindow&) = delete;
  HeadingWindow& operator=(const HeadingWindow&) = delete;

  // `frame` with Algorithm 1's estimate of it (VisualCompass::push of the same frame, frames in
  // the same order): the estimate with the window's heading and rotation.
  CompassEstimate push(const CompassFrame& frame, const CompassEstimate& chain);

  // Every frame's heading so far (unwrapped, by position in the sequence): the window's latest
  // solution; final for the frames that have left the window.
  const std::vector<double>& headings_rad() const { return headings_rad_; }
  // Measurements from keyframes other than the reference that passed, over the run.
  int keyframe_matches() const { return keyframe_matches_; }

 private:
  struct Keyframe {
    CompassFrame frame;
    int position = 0;
  };
  struct Measurement {
    int from = 0;  // positions in the sequence
    int to = 0;
    double rotation_rad = 0.0;
    double sigma_rad = 0.0;
    bool long_baseline = false;  // beyond the rotation cap, with parallax
  };

  // The frame against a keyframe, when the amplitude allows it.
  std::optional<Measurement> measure(const Keyframe& keyframe, const CompassFrame& frame,
                                     int position, double predicted_heading_rad) const;
  // The new frame's starting heading: the prediction its measurements agree with best.
  double starting_heading(const std::vector<Measurement>& incoming) const;
  // Solves the headings of the window ending at the newest frame.
  void solve();

  CompassParams params_;
  std::unique_ptr<PairMatcher> local_;
  std::unique_ptr<PairMatcher> global_;  // the whole d(α)
  std::deque<Keyframe> keyframes_;       // oldest first; the newest is the current reference
  std::optional<CompassFrame> previous_;
  std::deque<Measurement> measurements_;  // those reaching into the window
  std::vector<double> headings_rad_;
  int keyframe_matches_ = 0;
};

}  // namespace omninav::compass
