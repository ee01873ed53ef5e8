#include "omninav/compass/phase.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <vector>

#include "fft_spectra.hpp"
#include "frame_caches.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {
namespace {

// Components 1..K of every line's spectrum, computed once per frame and K. Double precision,
// one line at a time, not the FFT minimiser's single-precision spectra (fft_spectra.hpp): the
// estimate keeps the accuracy it was written and tested with (rolls within 10⁻⁶ columns).
std::shared_ptr<const std::vector<std::complex<double>>> low_frequencies(const CompassFrame& frame,
                                                                         int components) {
  detail::FrameCaches& caches = frame.caches();
  const std::lock_guard<std::mutex> lock(caches.mutex);
  auto& slot = caches.low_frequencies[components];
  if (slot) return slot;
  const int width = frame.width();
  const int channels = frame.channels();
  const detail::LinePlans plans = detail::line_plans(width);
  detail::FftwBuffer<double> line(static_cast<std::size_t>(width));
  detail::FftwBuffer<fftw_complex> spectrum(static_cast<std::size_t>(plans.bins));
  auto values = std::make_shared<std::vector<std::complex<double>>>();
  values->reserve(static_cast<std::size_t>(frame.height()) * channels * components);
  for (int r = 0; r < frame.height(); ++r) {
    const std::uint8_t* row = frame.row(r);
    for (int ch = 0; ch < channels; ++ch) {
      for (int c = 0; c < width; ++c) line.data()[c] = row[c * channels + ch];
      fftw_execute_dft_r2c(plans.r2c, line.data(), spectrum.data());
      for (int k = 1; k <= components; ++k) {
        values->emplace_back(spectrum.data()[k][0], spectrum.data()[k][1]);
      }
    }
  }
  slot = values;
  return slot;
}

}  // namespace

PhaseEstimate estimate_phase_shift(const CompassFrame& first, const CompassFrame& second,
                                   const PhaseParams& params) {
  require_same_shape(first, second);
  const int width = first.width();
  const int components = std::min(params.components, width / 2 - 1);
  PhaseEstimate estimate;
  if (components < 1) return estimate;  // too narrow to have a phase
  const auto first_lines = low_frequencies(first, components);
  const auto second_lines = low_frequencies(second, components);

  // P(k) = Σ_lines F_second(k)·conj(F_first(k)) for k = 1..K.
  std::vector<std::complex<double>> cross(static_cast<std::size_t>(components) + 1);
  for (std::size_t i = 0; i < first_lines->size(); ++i) {
    cross[i % static_cast<std::size_t>(components) + 1] +=
        (*second_lines)[i] * std::conj((*first_lines)[i]);
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
