#pragma once
// The rotation between two panoramas from the phase of their row spectra: the Shift Theorem of
// Menegatti et al. 2004, §2.1, Eq. 1, F{f(x − a)} = e^{−j2πas} F{f(x)}: shifting a row by a
// columns turns the phase of its k-th Fourier component (k cycles per W columns) by
// −2π·k·a/W and leaves the magnitudes alone.
//
// Our reading, in the shift convention of distance.hpp (the second image I_j is shifted by α to
// match the first I_i; if I_j = roll(I_i, s), α = −s):
//   P(k) = Σ_rows,channels F_j(k) · conj(F_i(k)) ≈ Σ |F_i(k)|² e^{−j2πk·s/W} = |P(k)| e^{j2πk·α/W}
// so every component votes for α = W·arg P(k) / (2πk), modulo W/k. Component 1 is unambiguous
// over the whole circle and gives the coarse estimate; components 2..K refine it: each phase is
// unwrapped to the value nearest the current estimate's prediction 2πk·α̂/W, and α̂ is updated to
// the weighted least-squares fit of all unwrapped phases so far, φ_k ≈ 2πk·α/W, weights |P(k)|
// (the summed cross-power, large where the images have energy):
//   α̂ = W/(2π) · Σ_k |P(k)|·k·φ_k / Σ_k |P(k)|·k².
// This uses the whole image (a mask would break the Shift Theorem) and is exact for rolled
// images; under parallax it is a rougher estimate than the distance minimum, good as a seed.

#include <optional>

#include "omninav/compass/frame.hpp"

namespace omninav::compass {

struct PhaseParams {
  // K, the highest component used; capped at W/2 − 1. Menegatti et al. 2004, §2.1 keeps the first
  // 15 components for its signatures; the rotation needs fewer.
  int components = 8;
};

struct PhaseEstimate {
  double shift_px = 0.0;  // α̂, in (−W/2, W/2]
  double weight = 0.0;    // Σ_k |P(k)|: zero when the images have no non-constant content
};

// Throws InputError when the frames differ in shape.
PhaseEstimate estimate_phase_shift(const CompassFrame& first, const CompassFrame& second,
                                   const PhaseParams& params);

}  // namespace omninav::compass
