#pragma once
// The first m components of the DFT of real rows, computed directly instead of by an FFT of
// the whole row: a signature needs 15 of a 360-column row's 181 components, and the direct sum
// folded twice by the symmetries of cosine and sine costs m·W/2 multiply-adds, which a
// vectorised loop does faster than FFTW computes all W/2 + 1 components (signature_bench: on
// the 2.3 GHz Xeon of the project's machine, 45 rows of 360 take ~15 µs this way, 28-41 µs with
// FFTW).
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
// Rounding differs from FFTW's in the last bits; which one runs depends only on (W, m), so the
// same input always gives the same signature.

#include <vector>

namespace omninav::signature::detail {

class LowFrequencyDft {
 public:
  // Whether this transform serves rows of `width` columns and `components` components.
  static bool applicable(int width, int components);

  LowFrequencyDft(int width, int components);

  // Components 0..m−1 of the row `f` (W values), unscaled like FFTW's: re[k], im[k].
  void transform(const float* f, float* re, float* im) const;

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
