#pragma once
// The distance between two panoramas as a function of the column shift of the second one:
// Eqs. 1-2 of Labrosse 2006 (Fig. 3's distance() in Labrosse 2004).
//
// SHIFT CONVENTION. Shifting the second image I_j by α columns is core's roll_columns(I_j, α):
// the content at column c moves to column c + α (mod W), the image the robot would see after
// turning counter-clockwise by α·360/W degrees. So
//     d(I_i, I_j, α) = sqrt( Σ_c m(c − α) Σ_rows,channels (I_j(c − α) − I_i(c))² )      (Eq. 2)
// with the mask m of field_of_view.hpp moving with I_j. The minimum α_m "un-rotates" I_j onto
// I_i, and the robot's rotation from I_i to I_j is ρ = −α_m·360/W (Eq. 4). With docs/design.md's
// convention (a counter-clockwise turn moves content to higher columns) ρ is counter-clockwise
// positive: if I_j = roll_columns(I_i, s), the minimum is at α = −s and ρ = +s·360/W, the turn
// that made I_j. Tests check this against rendered ground truth.
//
// EXACT COSTS. Pixels are 8-bit integers, so the sum under the root of Eq. 2 (L2) or the sum of
// absolute differences (L1) is an exact integer, a Cost. Every minimiser compares Costs, never
// rounded distances, so "the same minimum" has one meaning, ties included (shift_order.hpp).
// The distance itself, sqrt(cost) for L2 (the root is kept as in Eq. 1: "not to give too much
// importance to large distances") and the cost itself for L1, is what the sub-pixel fit and the
// amplitudes (Eqs. 7-12) use.

#include <cstdint>
#include <string>

#include "omninav/compass/field_of_view.hpp"
#include "omninav/compass/frame.hpp"

namespace omninav::compass {

// L2: the Euclidean distance over all colour components (Eq. 1, used throughout the paper);
// L1: the Manhattan distance, which §3.2 reports tried with no difference in results.
enum class Metric { kL2, kL1 };

std::string to_string(Metric metric);

using Cost = std::int64_t;

struct DistanceParams {
  Metric metric = Metric::kL2;  // Eq. 1 of Labrosse 2006
  FieldOfViewParams field_of_view;
};

// d as a function of its exact cost: sqrt for L2, the cost itself for L1.
double distance_of_cost(Cost cost, Metric metric);

// Wraps a shift to [0, W).
inline int wrap_shift(int shift_px, int width_px) {
  const int wrapped = shift_px % width_px;
  return wrapped < 0 ? wrapped + width_px : wrapped;
}

// Wraps a shift to (−W/2, W/2].
inline int signed_shift(int shift_px, int width_px) {
  const int wrapped = wrap_shift(shift_px, width_px);
  return 2 * wrapped > width_px ? wrapped - width_px : wrapped;
}

// The distance function between panoramas of one width: a metric and a mask of that width.
class DistanceFunction {
 public:
  DistanceFunction(Metric metric, ColumnMask mask);
  DistanceFunction(const DistanceParams& params, int width_px);

  Metric metric() const { return metric_; }
  const ColumnMask& mask() const { return mask_; }
  int width_px() const { return mask_.width_px(); }

  // The cost at shift α (any integer; taken modulo W), by the fast kernel: on the frames'
  // column-major copies, each run of mask columns is one pass over contiguous bytes (split
  // where it wraps round) that the compiler vectorises. Frames must have this function's width
  // and equal shapes (checked: InputError).
  Cost cost(const CompassFrame& first, const CompassFrame& second, int shift_px) const;

  // The same cost by the same kernel on the frames' rows as they are stored: one pass per row
  // and band, ~1.5× slower per shift at 1080×135 RGB, but no column-major copy is made (a
  // transpose, 0.1-0.4 ms per frame there): for the few shifts left to evaluate after the FFT.
  Cost cost_on_rows(const CompassFrame& first, const CompassFrame& second, int shift_px) const;

  // The same cost by a plain transcription of Eq. 2: for every column c of the first image,
  // the column c − α of the second, skipped when the mask excludes it, one component at a
  // time. Written independently of cost() so that the exhaustive oracle does not share the
  // fast kernel's bugs; tests check that both agree exactly.
  Cost reference_cost(const CompassFrame& first, const CompassFrame& second, int shift_px) const;

  double distance(Cost cost) const { return distance_of_cost(cost, metric_); }

  // How many components (row × channel × masked column) one evaluation compares.
  std::int64_t compared_components(const CompassFrame& frame) const;

  // The distance that corresponds to a mean difference of `grey_levels` per compared
  // component (RMS for L2, mean absolute for L1): a scale for thresholds on amplitudes.
  double distance_of_mean_difference(double grey_levels, const CompassFrame& frame) const;

  // Throws InputError unless both frames have this width and the same shape.
  void check(const CompassFrame& first, const CompassFrame& second) const;

 private:
  Metric metric_;
  ColumnMask mask_;
};

}  // namespace omninav::compass
