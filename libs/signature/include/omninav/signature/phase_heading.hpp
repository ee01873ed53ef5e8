#pragma once
// The heading from the phases (Menegatti et al. 2004, §2.1, Eq. 1; §3.4).
//
// The shift theorem: when the robot turns counter-clockwise on the spot by δ, every row moves
// by s = δ·W/2π columns towards higher columns (docs/design.md), f'(x) = f(x − s), and so
//     F'(k) = e^{−2πi·k·s/W} F(k) = e^{−i·k·δ} F(k):
// component k's phase drops by k·δ and its magnitude stays. (Eq. 1 writes e^{−j2πas} with s the
// frequency and a the shift; for the DFT of a row of W columns the frequency is k/W.)
//
// Summing over lines the cross-power P_k = Σ_y F'_y(k)·conj(F_y(k)) = e^{−ikδ} Σ_y |F_y(k)|²
// gives δ = −arg(P_k)/k, exact for k = 1 and known only modulo 2π/k for k > 1. So:
//   1. coarse: δ from k = 1, unambiguous in (−π, π];
//   2. refined: for k = 2..m−1 the branch of −arg(P_k)/k nearest the running estimate joins a
//      weighted mean, weight k·|P_k| (larger k resolve finer, larger |P_k| are less noisy);
//   3. polished: a few Newton steps on the low-pass circular correlation
//      C(δ) = Σ_k Re(P_k e^{ikδ}), whose maximum is the turn that best aligns the two;
//   4. guarded: C is also scanned on a grid of 8·m turns; if the grid finds a clearly higher
//      peak (k = 1 was too weak to pick the branch), that peak is polished and kept.
// The result is free of the 2π/k ambiguity and exact (to float precision) for a pure roll.

#include "omninav/signature/signature.hpp"

namespace omninav::signature {

struct PhaseHeading {
  // heading(to) − heading(from): the counter-clockwise turn that takes the view of `from` to
  // the view of `to`, radians in (−π, π] (REP 103 sign, docs/design.md).
  double turn_rad = 0.0;
  // C(turn) / Σ_k Σ_y |F_y(k)|·|F'_y(k)|, in [−1, 1]: 1 when `to` is exactly `from` turned.
  double confidence = 0.0;
};

// Uses components 1..m−1 with m = `components` (−1: all both signatures hold). Throws
// UsageError when the signatures differ in lines or have fewer than 2 components.
PhaseHeading relative_heading(const Signature& from, const Signature& to, int components = -1);

}  // namespace omninav::signature
