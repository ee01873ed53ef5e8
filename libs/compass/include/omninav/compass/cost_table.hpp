#pragma once
// The costs of one pair of frames at the shifts a minimiser has looked at, and the one order
// every minimiser uses to say which shift is best.
//
// TIE-BREAK. Shifts are ordered by exact cost (distance.hpp); equal costs are ordered by the
// smaller rotation, |signed shift| in (−W/2, W/2]; and a remaining tie between +s and −s goes to
// +s. This is a strict total order on the W shifts, so "the minimum" is unique for any input,
// and the exhaustive search, the descent and the FFT return the same shift whenever they find
// the global minimum. Preferring the smaller rotation makes a featureless pair (every cost
// equal) read as "no rotation", and lets the descent walk along a plateau towards 0.

#include <vector>

#include "omninav/compass/distance.hpp"
#include "omninav/compass/frame.hpp"

namespace omninav::compass {

// Whether shift a (with cost cost_a) comes before shift b in the order above.
bool shift_before(int shift_a, Cost cost_a, int shift_b, Cost cost_b, int width_px);

class CostTable {
 public:
  // How at() evaluates a cost (distance.hpp): on the frames' column-major copies, made once per
  // frame, for searches that visit many shifts; on their rows when only a few are evaluated.
  enum class Kernel { kColumns, kRows };

  // Keeps references to its arguments: they must outlive the table.
  CostTable(const DistanceFunction& distance, const CompassFrame& first, const CompassFrame& second,
            Kernel kernel = Kernel::kColumns);

  int width_px() const { return static_cast<int>(costs_.size()); }

  // The exact cost at `shift_px` (any integer), evaluated by the table's kernel the first time
  // it is asked for.
  Cost at(int shift_px);
  double distance_at(int shift_px) { return distance_.distance(at(shift_px)); }
  bool known(int shift_px) const { return costs_[index(shift_px)] >= 0; }
  // Records a cost found another way (by the oracle).
  void set(int shift_px, Cost cost) { costs_[index(shift_px)] = cost; }
  // Records estimates of every shift's cost (the FFT's, within the bound of fft_correlation.hpp;
  // rounded, negative ones to 0). They never stand in for exact costs: at() still evaluates a
  // shift exactly the first time it is asked for, and best_known() ignores them.
  void set_estimates(const std::vector<double>& estimates);
  // The exact cost at `shift_px` when known, else its estimate, else −1.
  Cost cost_or_estimate(int shift_px) const;

  // Whether every shift is known, exactly or by an estimate.
  bool complete() const;
  // How many costs at() had to evaluate (the minimisers' work, for reports and benchmarks).
  int evaluations() const { return evaluations_; }
  void add_evaluations(int count) { evaluations_ += count; }

  // The best known shift in the order above, signed in (−W/2, W/2]; 0 when nothing is known.
  int best_known() const;
  // The known costs, indexed by shift in [0, W), −1 where unknown.
  const std::vector<Cost>& costs() const { return costs_; }

  const DistanceFunction& distance() const { return distance_; }
  const CompassFrame& first() const { return first_; }
  const CompassFrame& second() const { return second_; }

 private:
  std::size_t index(int shift_px) const {
    return static_cast<std::size_t>(wrap_shift(shift_px, width_px()));
  }

  const DistanceFunction& distance_;
  const CompassFrame& first_;
  const CompassFrame& second_;
  Kernel kernel_;
  std::vector<Cost> costs_;
  std::vector<Cost> estimates_;  // empty, or one per shift
  int evaluations_ = 0;
};

}  // namespace omninav::compass
