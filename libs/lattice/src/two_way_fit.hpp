#pragma once
// The direction of motion between two places fitted from both ends (Menegatti et al. 2004,
// §3.4; signature/motion.hpp), with the turn held at `turn`: heading(b) − heading(a), radians.

#include <optional>
#include <vector>

#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice {

struct TwoWayFit {
  double direction_at_a_rad = 0.0;  // from a towards b, relative to a's heading
  double direction_at_b_rad = 0.0;  // from b towards a, relative to b's heading
  double residual = 0.0;            // the worse of the two fits' (MotionEstimate::residual)
  double parallax_rad = 0.0;        // the two fits' mean
  double disagreement_rad = 0.0;    // between the fit from a and the one from b, reversed
};

// None when either fit fails (no displacement to measure).
std::optional<TwoWayFit> fit_two_way(const memory::VisualMemory& memory, int a, int b, double turn);

}  // namespace omninav::lattice
