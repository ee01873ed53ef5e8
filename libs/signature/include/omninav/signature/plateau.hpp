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

// A running estimate of the plateau over a stream of signatures seen once (a live camera as
// well as a file): every `stride`-th signature is kept as a sample, at most `max_samples` of
// them, evenly spread over the stream so far (when full, every other sample is dropped and the
// stride doubles), with its dissimilarity to every other sample; the estimate is the
// kPlateauQuantile of those pairs (core/statistics.hpp's rank), per compared value (Eq. 2/6
// over lines × components, as the exploration's threshold). Each sample costs its comparison
// with the others held (max_samples dissimilarities), a drop once all pairs of the half kept.
class PlateauEstimate {
 public:
  explicit PlateauEstimate(ComponentWeights weights = {}, std::size_t max_samples = 128);

  void add(const Signature& signature);

  // None until two samples are held.
  std::optional<double> per_value() const;
  std::size_t signatures_seen() const { return seen_; }
  std::size_t samples() const { return samples_.size(); }

 private:
  double pair(const Signature& a, const Signature& b) const;
  void halve();

  ComponentWeights weights_;
  std::size_t max_samples_;
  std::vector<Signature> samples_;
  std::vector<double> pairs_;  // per value, every pair of samples once
  std::size_t stride_ = 1;
  std::size_t seen_ = 0;
  std::optional<double> cached_;
};

}  // namespace omninav::signature
