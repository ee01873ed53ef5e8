#include "two_way_fit.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/signature/motion.hpp"

namespace omninav::lattice {

std::optional<TwoWayFit> fit_two_way(const memory::VisualMemory& memory, int a, int b,
                                     double turn) {
  const signature::MotionEstimate there =
      signature::estimate_motion(memory.place(a).signature, memory.place(b).signature, -1, turn);
  const signature::MotionEstimate back =
      signature::estimate_motion(memory.place(b).signature, memory.place(a).signature, -1, -turn);
  if (!there.valid || !back.valid) return std::nullopt;
  // b's view of a, turned round and into a's frame; the two fits averaged.
  const double back_at_a = wrap_angle(back.bearing_rad + kPi + turn);
  const double disagreement = signed_difference(back_at_a, there.bearing_rad);
  TwoWayFit fit;
  fit.direction_at_a_rad = wrap_angle(there.bearing_rad + 0.5 * disagreement);
  fit.direction_at_b_rad = wrap_angle(fit.direction_at_a_rad + kPi - turn);
  fit.residual = std::max(there.residual, back.residual);
  fit.parallax_rad = 0.5 * (there.parallax_rad + back.parallax_rad);
  fit.disagreement_rad = std::abs(disagreement);
  return fit;
}

}  // namespace omninav::lattice
