#pragma once
// The direction of motion between two places, from the Fourier phases (Menegatti et al. 2004,
// §3.4: "if we also include the phase component of the Fourier transform, we can obtain
// qualitative information about the agent's motion direction"). The paper gives no formula;
// this is ours.
//
// Model. Let the robot move a short distance d in direction φ (relative to its heading at
// `from`, counter-clockwise) and turn by τ. A thing at bearing θ and distance r is then seen at
// bearing θ + (d/r)·sin(θ − φ) − τ: things ahead (θ = φ) and behind stay put, things abeam
// move backwards the most. In the column angle u = 2π·x/W = π/2 − θ (docs/design.md's columns) the
// content at u in `from` appears at u + D(u) in `to`, with
//     D(u) = τ − ρ·cos(u + φ) = a + b·cos u + c·sin u,   ρ = d/r,
// so τ = a, ρ = √(b² + c²) and φ = atan2(c, −b): three linear parameters, taken to be the same
// for every row (one typical depth r; rows at other depths only add noise).
//
// Fit. Each line's low-pass signal is rebuilt from its components 1..m−1 (the mean, k = 0, is
// left out so that a brightness change is not mistaken for motion), and (a, b, c) minimise
//     Σ_lines Σ_u [g_to(u + D(u)) − g_from(u)]²
// by Gauss-Newton, starting from a = the phase heading (phase_heading.hpp) and from five
// guesses of (b, c), on components 1..3 first, then 1..7, then all: the coarse fit cannot
// alias, the fine one is precise. Only the phases and magnitudes of the two signatures are
// used, so edges of a stored map can be re-estimated without the images.
//
// Known turn. When the heading change between the two views is known (both places have
// headings, from the visual compass or a database), τ is held at it and only (b, c) are
// fitted. A free τ can trade turn for translation and settle on a wrong pair of both, and a
// fit that cannot explain the known turn shows it in its residual instead. Measured on five
// rendered maps (30 cm grids, 60 cm zig-zags; headings from the truth), over the pairs of
// places truly within 0.9 m, each place with its 3 most similar: bearings more than 30° off
// fell from 41 of 1,054 pairs to 9, the 90th percentile of the error on the two grids
// round furniture from 20-25° to 13-16°, the median from 5.3-7.1° to 5.1-5.9°. The turn must
// be known to a few degrees: held 5° off (Gaussian, one way of the two), the 90th percentile
// rose to 17-30°, 10° off to 50-59°; letting the turn go free again after the held fit gives
// back the free fit's errors.

#include <optional>

#include "omninav/signature/signature.hpp"

namespace omninav::signature {

struct MotionEstimate {
  // Direction of travel from `from` to `to`, seen from `from`: counter-clockwise from its
  // front, radians in (−π, π]. Meaningless when !valid.
  double bearing_rad = 0.0;
  double turn_rad = 0.0;                   // τ, the heading change the fit found (or was given)
  double parallax_rad = 0.0;               // ρ = d/r: how far things abeam moved, radians
  double bearing_stddev_rad = kNoBearing;  // from the fit's covariance; large: don't trust it
  double residual = 1.0;                   // rms residual / rms signal after the fit, 0..~1.4
  bool valid = false;                      // ρ is at least 3 standard deviations from 0

  static constexpr double kNoBearing = 3.141592653589793;
};

// Uses components up to `components` (−1: all both signatures hold; at least 2), and holds the
// turn at `known_turn_rad` (heading at `to` minus heading at `from`) when given. Throws
// UsageError when the signatures differ in lines.
MotionEstimate estimate_motion(const Signature& from, const Signature& to, int components = -1,
                               std::optional<double> known_turn_rad = std::nullopt);

}  // namespace omninav::signature
