#include "omninav/compass/phase.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "fft_spectra.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {

PhaseEstimate estimate_phase_shift(const CompassFrame& first, const CompassFrame& second,
                                   const PhaseParams& params) {
  require_same_shape(first, second);
  const int width = first.width();
  const int components = std::min(params.components, width / 2 - 1);
  PhaseEstimate estimate;
  if (components < 1) return estimate;  // too narrow to have a phase
  // The unmasked row spectra, shared with the FFT minimiser through the frames' caches.
  const auto first_role = detail::first_spectra(first, FftPlanning::kEstimate);
  const auto second_role = detail::first_spectra(second, FftPlanning::kEstimate);

  // P(k) = Σ_lines F_second(k)·conj(F_first(k)) for k = 1..K.
  std::vector<std::complex<double>> cross(static_cast<std::size_t>(components) + 1);
  for (int l = 0; l < first_role->rows.lines; ++l) {
    const fftw_complex* a = first_role->rows.line(l);
    const fftw_complex* b = second_role->rows.line(l);
    for (int k = 1; k <= components; ++k) {
      cross[static_cast<std::size_t>(k)] +=
          std::complex<double>(b[k][0], b[k][1]) * std::complex<double>(a[k][0], -a[k][1]);
    }
  }

  // Coarse from k = 1, refined by k = 2..K: each phase unwrapped next to the prediction of
  // the current estimate, then the weighted least-squares fit φ_k ≈ 2πk·α/W (phase.hpp).
  double numerator = 0.0;    // Σ w_k·k·φ_k
  double denominator = 0.0;  // Σ w_k·k²
  double alpha = 0.0;
  for (int k = 1; k <= components; ++k) {
    const std::complex<double> p = cross[static_cast<std::size_t>(k)];
    const double weight = std::abs(p);
    estimate.weight += weight;
    if (!(weight > 0.0)) continue;
    const double predicted = kTwoPi * k * alpha / width;
    const double phase = predicted + wrap_angle(std::arg(p) - predicted);
    numerator += weight * k * phase;
    denominator += weight * k * k;
    alpha = width * numerator / (kTwoPi * denominator);
  }
  if (!(denominator > 0.0) || !std::isfinite(alpha)) return PhaseEstimate{};
  // Into (−W/2, W/2]. A half turn is ±W/2 up to rounding (the sums' order moves it by ~10⁻¹⁴
  // columns either way): within 10⁻⁹ columns of −W/2 it is read as +W/2, the interval's end.
  alpha = std::fmod(alpha, static_cast<double>(width));
  if (alpha > width / 2.0) alpha -= width;
  if (alpha <= -width / 2.0 + 1e-9) alpha += width;
  estimate.shift_px = alpha;
  return estimate;
}

}  // namespace omninav::compass
