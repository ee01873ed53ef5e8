#pragma once
// The first m components of the DFT of real rows, computed directly instead of by an FFT of
// the whole row: a signature needs 15 of a 360-column row's 181 components, and the direct sum
// folded twice by the symmetries of cosine and sine costs m·W/2 multiply-adds, which a
// vectorised loop does several times faster than FFTW computes all W/2 + 1 components
// (signature_bench, docs/memory.md: 45 rows of 360 take 8-10 µs this way, folding included,
// on the project's shared machine; FFTW takes 28-41 µs for the whole spectra).
//
// With θ_k = 2πk/W, F(k) = Σ_x f(x) e^{−iθ_k x}. Fold 1 (x ↔ W − x):
//     Re F(k) = f(0) + (−1)^k f(W/2) + Σ_{x=1}^{W/2−1} e(x) cos θ_k x,   e(x) = f(x) + f(W−x)
//     Im F(k) = −Σ_{x=1}^{W/2−1} o(x) sin θ_k x,                        o(x) = f(x) − f(W−x)
// Fold 2 (x ↔ W/2 − x; cos θ_k(W/2 − x) = (−1)^k cos θ_k x, sin θ_k(W/2 − x) = −(−1)^k sin θ_k x):
//     Σ_{x=1}^{W/2−1} e(x) cos θ_k x = Σ_{x=1}^{W/4−1} [e(x) + (−1)^k e(W/2−x)] cos θ_k x
//                                      + e(W/4) cos(πk/2)
//     Σ_{x=1}^{W/2−1} o(x) sin θ_k x = Σ_{x=1}^{W/4−1} [o(x) − (−1)^k o(W/2−x)] sin θ_k x
//                                      + o(W/4) sin(πk/2)
// so even and odd k each need one folded row, and 8 components (one 8-lane vector of the
// table) accumulate per multiply-add. Needs W divisible by 4.
//
// Two stages, so that both vectorise: fold() makes the four folded rows of a line (a
// vectorised loop over x), transform_folded() multiplies several lines' folded rows by the
// table at once: each table vector loaded serves every line, and the lines' sums are
// independent chains, so the adds do not wait on each other.
//
// Rounding differs from FFTW's in the last bits; which one runs depends only on (W, m), so the
// same input always gives the same signature. Every component's sum is made in the same order
// whatever the number of lines per call and the instruction set, so a line's result does not
// depend on its neighbours or on the machine (no fused multiply-add: see the .cpp).

#include <vector>

namespace omninav::signature::detail {

class LowFrequencyDft {
 public:
  // Lines transform_folded() takes at most per call.
  static constexpr int kMaxLines = 3;

  // Whether this transform serves rows of `width` columns and `components` components.
  static bool applicable(int width, int components);

  LowFrequencyDft(int width, int components);

  // Floats fold() writes per line: four folded rows of W/4 values.
  int folded_size() const { return width_; }

  // Folds the row `f` (W values) into `folded` (folded_size() floats): for x = 1..W/4−1,
  // [x] = e(x) + e(W/2−x), [q + x] = e(x) − e(W/2−x), [2q + x] = o(x) − o(W/2−x) and
  // [3q + x] = o(x) + o(W/2−x) (q = W/4); the x = 0 slots hold f(0) + f(W/2), f(0) − f(W/2),
  // e(W/4) and o(W/4).
  void fold(const float* f, float* folded) const;

  // Components 0..m−1 of `lines` (1..kMaxLines) folded lines, stored one after the other
  // (folded_size() floats each), unscaled like FFTW's: re[line·m + k], im[line·m + k].
  void transform_folded(const float* folded, int lines, float* re, float* im) const;

  int width() const { return width_; }
  int components() const { return components_; }

 private:
  int width_;
  int components_;
  int groups_;  // 8-lane vectors per parity: 1 for m ≤ 16, 2 for m ≤ 32
  // Per x in [0, W/4), per group: cos and sin of θ_k x for the even k = 2(8g + j) and the
  // odd k = 2(8g + j) + 1, j = 0..7: 4 · groups · 8 floats per x.
  std::vector<float> table_;
};

}  // namespace omninav::signature::detail
