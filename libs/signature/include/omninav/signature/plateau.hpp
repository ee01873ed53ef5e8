#pragma once
// The plateau of Fig. 7 (Menegatti et al. 2004, §3.2): the dissimilarity of two views grows
// with the distance between them and then saturates. The papers show the curve and give no
// formula; we read its level as the 90th percentile of the dissimilarity over pairs of a map's
// places (the lattice's calibration, lattice/organise.hpp) or of a stream's frames (exploration's
// new-place threshold, memory/exploration.hpp): most pairs of a map are far apart, and the top
// tenth leaves out the outliers of views that pass right by an object.

#include <cstddef>
#include <optional>
#include <vector>

#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::signature {

inline constexpr double kPlateauQuantile = 0.9;

// The other end of the curve, its floor: what two views from one spot differ by (the camera's
// noise, the resampling of a turn). It is read from the steps between consecutive frames of a
// stream that a turn on the spot explains (the caller says which: memory/exploration.hpp asks
// the compass), at their closest: the (1 − kPlateauQuantile) quantile, whose bottom tenth leaves
// out repeated frames as the plateau's top tenth leaves out views passing by an object.
inline constexpr double kFloorQuantile = 1.0 - kPlateauQuantile;

// A running estimate of the plateau over a stream of signatures seen once (a live camera as
// well as a file): every `stride`-th signature is kept as a sample, at most `max_samples` of
// them, evenly spread over the stream so far (when full, every other sample is dropped and the
// stride doubles), with its dissimilarity to every other sample; the estimate is the
// kPlateauQuantile of those pairs (core/statistics.hpp's rank), per compared value (Eq. 2/6
// over lines × components, as the exploration's threshold). Each sample costs its comparison
// with the others held (max_samples dissimilarities), a drop once all pairs of the half kept.
// The floor is estimated from the same samples: a sampled frame of a stream (add_frame) whose
// step from the frame before it is a turn on the spot also keeps that step's dissimilarity.
class PlateauEstimate {
 public:
  explicit PlateauEstimate(ComponentWeights weights = {}, std::size_t max_samples = 128);

  // A signature with no predecessor in a stream (a place of a map).
  void add(const Signature& signature);
  // The next frame of a stream; `turn_only`: the step from the frame before it (also given by
  // add_frame) is a turn on the spot, and its dissimilarity is one for the floor.
  void add_frame(const Signature& signature, bool turn_only);
  // Whether the next signature added will be kept as a sample (only a sample's step counts, so
  // that the caller may judge the steps of those alone).
  bool will_sample() const;

  // None until two samples are held.
  std::optional<double> per_value() const;
  // kFloorQuantile of the sampled frames' turns on the spot, per value; none until one is held.
  std::optional<double> floor_per_value() const;
  std::size_t signatures_seen() const { return seen_; }
  std::size_t samples() const { return samples_.size(); }

 private:
  double pair(const Signature& a, const Signature& b) const;
  void halve();
  void add(const Signature& signature, const Signature* previous);
  void update_estimates();  // cached_ and cached_floor_ from the samples held

  ComponentWeights weights_;
  std::size_t max_samples_;
  std::vector<Signature> samples_;
  std::vector<double> pairs_;  // per value, every pair of samples once
  // Per sample, its step from the stream's frame before it, when that was a turn on the spot.
  std::vector<std::optional<double>> steps_;
  std::optional<Signature> previous_frame_;  // the last add_frame's
  std::size_t stride_ = 1;
  std::size_t seen_ = 0;
  std::optional<double> cached_;
  std::optional<double> cached_floor_;
};

}  // namespace omninav::signature
