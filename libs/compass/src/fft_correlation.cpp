// Minimiser (c): d(α) for every shift at once by masked circular cross-correlation.
//
// DERIVATION. With the conventions of distance.hpp and field_of_view.hpp (the second image J is
// shifted by α, its mask m moves with it, I is the first image), for one line (a row of one
// colour channel) and summing over the columns k of J:
//     d²(α) = Σ_k m(k)·(J(k) − I(k + α))²
//           = Σ_k m(k)·J(k)²  −  2·Σ_k (m·J)(k)·I(k + α)  +  Σ_k m(k)·I(k + α)²
//           =      S_J        −  2·C₁(α)                  +  C₂(α)
// (m ∈ {0, 1}, so m² = m). S_J does not depend on α. C₁ is the circular cross-correlation of
// the masked second image with the first; C₂ that of the mask with the first image squared.
// Summed over all lines (rows × channels), S_J and C₁ simply add up, and since the mask is the
// same on every line, C₂ only needs the column energy Q(c) = Σ_lines I(c)²:
//     d²(α) = S_J − 2·Σ_lines C₁,line(α) + Σ_k m(k)·Q(k + α).
// Correlation theorem, for real a, b of length W with spectra A, B (FFTW's forward DFT):
//     Σ_k a(k)·b(k + α) = (1/W)·Σ_f conj(A(f))·B(f)·e^{+2πifα/W}  = (1/W)·IDFT[conj(A)·B](α)
// (FFTW's backward c2r transform is the unnormalised IDFT). Hence, with the spectra of every
// line of m·J (B_l) and of I (A_l), of the mask (M) and of Q (Q̂):
//     d²(α) = S_J + (1/W)·IDFT[ conj(M)·Q̂ − 2·Σ_lines conj(B_l)·A_l ](α)
// The sum over lines happens in the frequency domain, before ONE inverse transform of length W.
// The forward transforms depend on one frame each: A_l and Q̂ on the first image ("first
// role"), B_l and S_J on the second ("second role", per mask). Each is computed once per frame
// and cached in it (fft_spectra.cpp), so a frame that is the second image of one pair and the
// first of the next is transformed once per role; without a mask both roles share one
// transform. Check: J = roll(I, s) gives J(k) = I(k − s), and d²(−s) = 0.
//
// EXACTNESS. For 8-bit pixels d²(α) is an integer. FFT-based correlation in floating point
// has an error bounded by about ε·log₂W times Σ_lines ‖I_l‖·‖m·J_l‖ ≤ E_I + E_J (Cauchy-Schwarz;
// E the images' energies Σ pixel², ε = 2⁻⁵²). We take 64·ε·log₂W·(E_I + E_J) as the bound: at
// 1080×135 RGB it is ~4·10⁻³, far below 0.5, so rounding every value to the nearest integer
// recovers the exact cost, and minimiser (c) then orders shifts exactly as (a) does, ties
// included, whatever plan FFTW picked (tests check every value against the oracle). Only for
// images so large that the bound reaches 0.25 (~10¹³ energy, e.g. 16384×4096 RGB) does (c)
// re-evaluate, with the exact kernel, every shift whose rounded cost lies within twice the
// bound of the minimum.

#include "omninav/compass/fft_correlation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

#include "fft_spectra.hpp"
#include "frame_caches.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {

namespace detail {
namespace {

// conj(M̂) per mask, made once.
std::shared_ptr<const FftwBuffer<fftw_complex>> conjugate_mask_spectrum(const ColumnMask& mask,
                                                                        FftPlanning planning) {
  static std::mutex mutex;
  static std::map<std::pair<std::uint64_t, int>, std::shared_ptr<const FftwBuffer<fftw_complex>>>
      cache;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_pair(mask.key(), mask.width_px());
  if (const auto found = cache.find(key); found != cache.end()) return found->second;
  const int width = mask.width_px();
  const FftPlans plans = fft_plans(width, planning);
  FftwBuffer<double> line(static_cast<std::size_t>(width));
  for (int c = 0; c < width; ++c) line.data()[c] = mask.selected(c) ? 1.0 : 0.0;
  auto spectrum = std::make_shared<FftwBuffer<fftw_complex>>(static_cast<std::size_t>(plans.bins));
  fftw_execute_dft_r2c(plans.one_r2c, line.data(), spectrum->data());
  for (int f = 0; f < plans.bins; ++f) spectrum->data()[f][1] = -spectrum->data()[f][1];
  return cache.emplace(key, spectrum).first->second;
}

}  // namespace

// The work arrays of correlation_costs for one width.
struct CorrelationScratch {
  int width = 0;
  std::vector<double> sum_re, sum_im;  // bins
  FftwBuffer<fftw_complex> spectrum;   // bins (FFTW-aligned: the inverse plan runs on it)
  FftwBuffer<double> correlation;      // width
  void resize(int new_width, int bins) {
    if (new_width == width) return;
    width = new_width;
    sum_re.assign(static_cast<std::size_t>(bins), 0.0);
    sum_im.assign(static_cast<std::size_t>(bins), 0.0);
    spectrum = FftwBuffer<fftw_complex>(static_cast<std::size_t>(bins));
    correlation = FftwBuffer<double>(static_cast<std::size_t>(new_width));
  }
};

// re += Re(conj(b)·a), im += Im(conj(b)·a) over `bins` interleaved complex values. Compiled
// for AVX-512, AVX2 and the baseline, picked at load time (the same sums in every version:
// no fused multiply-add is allowed to change the rounding, -ffp-contract stays off).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#endif
static void
accumulate_conjugate_products(const double* __restrict a, const double* __restrict b,
                              double* __restrict re, double* __restrict im, int bins) {
  for (int f = 0; f < bins; ++f) {
    const double a_re = a[2 * f], a_im = a[2 * f + 1];
    const double b_re = b[2 * f], b_im = b[2 * f + 1];
    re[f] += b_re * a_re + b_im * a_im;
    im[f] += b_re * a_im - b_im * a_re;
  }
}

// The a-priori bound on the FFT's absolute error in d² (EXACTNESS above).
double error_bound(const CompassFrame& first, const CompassFrame& second, int width) {
  // Both frames' column energies are cached by the time the correlation has run.
  const auto energy = [](const CompassFrame& frame) {
    FrameCaches& caches = frame.caches();
    const std::lock_guard<std::mutex> lock(caches.mutex);
    double total = 0.0;
    for (const double value : caches.column_energy) total += value;
    return total;
  };
  return 64.0 * std::numeric_limits<double>::epsilon() * std::log2(std::max(width, 2)) *
         (energy(first) + energy(second));
}

}  // namespace detail

std::vector<double> correlation_costs(const DistanceFunction& distance, const CompassFrame& first,
                                      const CompassFrame& second, FftPlanning planning) {
  if (distance.metric() != Metric::kL2) {
    throw UsageError(
        "the FFT minimiser needs the l2 metric: it expands the square of Eq. 2 (choose "
        "metric: l2, or another minimiser)");
  }
  distance.check(first, second);
  const int width = first.width();
  const int bins = width / 2 + 1;

  // Per-thread work arrays, kept between calls (no allocation per pair).
  thread_local detail::CorrelationScratch work;
  work.resize(width, bins);

  // Σ_lines conj(B_l)·A_l, real and imaginary parts apart so that the loop vectorises; summed
  // line after line as the transforms deliver them (fft_spectra.hpp, pair_spectra).
  std::fill(work.sum_re.begin(), work.sum_re.end(), 0.0);
  std::fill(work.sum_im.begin(), work.sum_im.end(), 0.0);
  const detail::PairSpectra pair =
      detail::pair_spectra(first, second, distance.mask(), planning,
                           [bins](const detail::LineSpectra& first_rows,
                                  const detail::LineSpectra& second_rows, int begin, int end) {
                             for (int l = begin; l < end; ++l) {
                               detail::accumulate_conjugate_products(
                                   &first_rows.line(l)[0][0], &second_rows.line(l)[0][0],
                                   work.sum_re.data(), work.sum_im.data(), bins);
                             }
                           });
  const auto& first_role = pair.first;
  const auto& second_role = pair.second;
  const auto mask = detail::conjugate_mask_spectrum(distance.mask(), planning);

  // conj(M)·Q̂ − 2·Σ conj(B_l)·A_l, then one inverse transform.
  const detail::FftPlans plans = detail::fft_plans(width, planning);
  fftw_complex* spectrum = work.spectrum.data();
  const fftw_complex* q = first_role->column_energy.data();
  const fftw_complex* m = mask->data();
  for (int f = 0; f < bins; ++f) {
    const std::size_t i = static_cast<std::size_t>(f);
    spectrum[f][0] = m[f][0] * q[f][0] - m[f][1] * q[f][1] - 2.0 * work.sum_re[i];
    spectrum[f][1] = m[f][0] * q[f][1] + m[f][1] * q[f][0] - 2.0 * work.sum_im[i];
  }
  double* correlation = work.correlation.data();
  fftw_execute_dft_c2r(plans.one_c2r, spectrum, correlation);

  std::vector<double> costs(static_cast<std::size_t>(width));
  const double scale = 1.0 / width;
  for (int shift = 0; shift < width; ++shift) {
    costs[static_cast<std::size_t>(shift)] =
        second_role->masked_energy + correlation[shift] * scale;
  }
  return costs;
}

namespace detail {

ShiftSearch fft_minimise(CostTable& table, FftPlanning planning) {
  const std::vector<double> raw =
      correlation_costs(table.distance(), table.first(), table.second(), planning);
  const int width = table.width_px();
  for (int shift = 0; shift < width; ++shift) {
    const double value = raw[static_cast<std::size_t>(shift)];
    table.set(shift, value <= 0.0 ? Cost{0} : static_cast<Cost>(std::llround(value)));
  }
  int best = table.best_known();
  const double bound = error_bound(table.first(), table.second(), width);
  if (bound >= 0.25) {
    const Cost lowest = table.costs()[static_cast<std::size_t>(wrap_shift(best, width))];
    const double window = 2.0 * bound + 1.0;
    for (int shift = 0; shift < width; ++shift) {
      const Cost rounded = table.costs()[static_cast<std::size_t>(shift)];
      if (static_cast<double>(rounded - lowest) <= window) {
        table.set(shift, table.distance().cost(table.first(), table.second(), shift));
        table.add_evaluations(1);
      }
    }
    best = table.best_known();
  }
  return ShiftSearch{best, std::nullopt};
}

}  // namespace detail
}  // namespace omninav::compass
