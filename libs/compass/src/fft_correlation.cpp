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
// TWO LINES PER TRANSFORM (fft_spectra.hpp). Lines are paired, z = a + i·a' (two rows of one
// channel), the same way in both frames. For complex z_A = a + i·a', z_B = b + i·b':
//     conj(z_B(k))·z_A(k + α) = b·a(k+α) + b'·a'(k+α) + i·(b·a'(k+α) − b'·a(k+α)),
// so the real part of the complex correlation is the sum of both lines' correlations, and with
// S = Σ_pairs conj(Z_B)·Z_A over full spectra, Re IDFT[S] = IDFT[H], H(f) = (S(f) + conj(S(−f)))/2
// the Hermitian part of S, a real signal's spectrum: bins 0..W/2 of it go to one real inverse.
//
// EXACT MINIMUM, BOUNDED CURVE. For 8-bit pixels d²(α) is an integer. The line transforms and
// the products of their spectra run in single precision (u = 2⁻²⁴), the rest in double, so the
// values are estimates, with a bounded error. If a forward transform errs by at most κ·‖Z‖ in
// the 2-norm, the products conj(Ẑ_B)·Ẑ_A of a pair of lines err by at most
// (2κ + κ²)·‖Z_A‖·‖Z_B‖ = (2κ + κ²)·W·‖z_A‖·‖z_B‖ summed over bins (Cauchy-Schwarz, Parseval);
// computing the products and summing n of them in single precision before the sum goes to
// double adds √2·γ_{n+1}·(1 + κ)² to that factor (γ_k = k·u/(1 − k·u); n = kSingleSumLines =
// 16); an error δS(f) moves each value of the inverse by at most Σ_f |δS(f)|/W; and
// Σ_pairs ‖z_A‖·‖z_B‖ ≤ √(E_I·S_J) (Cauchy-Schwarz; E_I = Σ I², S_J = Σ m·J², as the masked lines
// are transformed). So with the factor 2 of C₁:
//     |estimate − d²(α)| ≤ 2·(2κ + κ² + √2·γ_{n+1}·(1 + κ)²)·√(E_I·S_J) + 64·ε·log₂W·(E_I + E_J)
// the last term covering the double-precision parts (C₂, the sums of the single-precision
// partial sums, the inverse; ε = 2⁻⁵²). For κ we take 32·u·log₂W: the form of the bound for
// Cooley-Tukey FFTs (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., Thm 24.2:
// log₂W·η with η ≈ (1 + 4√2)·u per radix-2 stage for accurate twiddles), with ~5× its constant
// for FFTW's mixed-radix codelets. FFTW publishes no worst-case bound for its codelets: this
// constant is our assumption, and the tests check the bound against the exact costs at every
// shift (on rendered 1080×135 pairs the largest error is ~1/2000 of it). At 1080×135 RGB with
// the mask it is 2-3·10⁵ (4·10⁵ without), while the lowest and the next lowest costs of rendered
// pairs differ by 5·10⁵ to 5·10⁶: one or two shifts are left to evaluate exactly.
//
// Minimiser (c) then evaluates exactly (integer kernel, distance.hpp) every shift whose estimate
// is within twice the bound of the lowest estimate, and takes the best of those in the order of
// cost_table.hpp: any other shift's exact cost exceeds its estimate − bound > lowest + bound ≥
// the exact cost of the lowest estimate's shift, so it cannot be the minimum, ties included. The
// minimum and its cost are (a)'s exactly; on textured pairs one or two shifts are evaluated, on
// a featureless one (every cost equal) every shift. The other shifts keep their estimates in the
// table (CostTable::set_estimates), which the sub-pixel fit and the amplitudes do not use: they
// ask the table for exact costs (CostTable::at).

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
std::shared_ptr<const FftwBuffer<fftw_complex>> conjugate_mask_spectrum(const ColumnMask& mask) {
  static std::mutex mutex;
  static std::map<std::pair<std::uint64_t, int>, std::shared_ptr<const FftwBuffer<fftw_complex>>>
      cache;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_pair(mask.key(), mask.width_px());
  if (const auto found = cache.find(key); found != cache.end()) return found->second;
  const int width = mask.width_px();
  const LinePlans plans = line_plans(width);
  FftwBuffer<double> line(static_cast<std::size_t>(width));
  for (int c = 0; c < width; ++c) line.data()[c] = mask.selected(c) ? 1.0 : 0.0;
  auto spectrum = std::make_shared<FftwBuffer<fftw_complex>>(static_cast<std::size_t>(plans.bins));
  fftw_execute_dft_r2c(plans.r2c, line.data(), spectrum->data());
  for (int f = 0; f < plans.bins; ++f) spectrum->data()[f][1] = -spectrum->data()[f][1];
  return cache.emplace(key, spectrum).first->second;
}

}  // namespace

// Lines whose products are summed in single precision before the sum goes to double (EXACT
// MINIMUM, BOUNDED CURVE): short enough to add little to the bound, long enough that the
// double-precision additions cost nothing.
constexpr int kSingleSumLines = 16;

// The work arrays of correlation_costs for one width.
struct CorrelationScratch {
  int width = 0;
  std::vector<float> part_re, part_im;  // width: up to kSingleSumLines lines' products
  std::vector<double> sum_re, sum_im;   // width: full spectra
  FftwBuffer<fftw_complex> spectrum;    // bins (FFTW-aligned: the inverse plan runs on it)
  FftwBuffer<double> correlation;       // width
  void resize(int new_width, int bins) {
    if (new_width == width) return;
    width = new_width;
    part_re.assign(static_cast<std::size_t>(new_width), 0.0f);
    part_im.assign(static_cast<std::size_t>(new_width), 0.0f);
    sum_re.assign(static_cast<std::size_t>(new_width), 0.0);
    sum_im.assign(static_cast<std::size_t>(new_width), 0.0);
    spectrum = FftwBuffer<fftw_complex>(static_cast<std::size_t>(bins));
    correlation = FftwBuffer<double>(static_cast<std::size_t>(new_width));
  }
  // sum += Σ_lines conj(b)·a over lines [begin, end), kSingleSumLines at a time in single
  // precision.
  void add_lines(const LineSpectra& a, const LineSpectra& b, int begin, int end);
};

// re += Re(conj(b)·a), im += Im(conj(b)·a) over `count` interleaved complex floats. Compiled
// for AVX-512, AVX2 and the baseline, picked at load time (the same sums in every version: no
// fused multiply-add is allowed to change the rounding, -ffp-contract stays off).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#endif
static void
accumulate_conjugate_products(const float* __restrict a, const float* __restrict b,
                              float* __restrict re, float* __restrict im, int count) {
  for (int f = 0; f < count; ++f) {
    const float a_re = a[2 * f], a_im = a[2 * f + 1];
    const float b_re = b[2 * f], b_im = b[2 * f + 1];
    re[f] += b_re * a_re + b_im * a_im;
    im[f] += b_re * a_im - b_im * a_re;
  }
}

void CorrelationScratch::add_lines(const LineSpectra& a, const LineSpectra& b, int begin, int end) {
  for (int part = begin; part < end; part += kSingleSumLines) {
    std::fill(part_re.begin(), part_re.end(), 0.0f);
    std::fill(part_im.begin(), part_im.end(), 0.0f);
    for (int l = part; l < std::min(end, part + kSingleSumLines); ++l) {
      accumulate_conjugate_products(&a.line(l)[0][0], &b.line(l)[0][0], part_re.data(),
                                    part_im.data(), width);
    }
    for (std::size_t f = 0; f < sum_re.size(); ++f) {
      sum_re[f] += part_re[f];
      sum_im[f] += part_im[f];
    }
  }
}

// Σ I² over a frame, from its column energies (cached by the time the correlation has run).
double frame_energy(const CompassFrame& frame) {
  FrameCaches& caches = frame.caches();
  const std::lock_guard<std::mutex> lock(caches.mutex);
  double total = 0.0;
  for (const double value : caches.column_energy) total += value;
  return total;
}

// The bound on the estimates' absolute error in d² (EXACT MINIMUM, BOUNDED CURVE above).
double error_bound(double first_energy, double second_energy, double second_masked_energy,
                   int width) {
  const double u = std::ldexp(1.0, -24);
  const double stages = std::log2(std::max(width, 2));
  const double kappa = 32.0 * u * stages;
  const double sums = std::sqrt(2.0) * (kSingleSumLines + 1) * u /
                      (1.0 - (kSingleSumLines + 1) * u) * (1.0 + kappa) * (1.0 + kappa);
  return 2.0 * (2.0 * kappa + kappa * kappa + sums) *
             std::sqrt(first_energy * second_masked_energy) +
         64.0 * std::numeric_limits<double>::epsilon() * stages * (first_energy + second_energy);
}

}  // namespace detail

CorrelationCosts correlation_costs(const DistanceFunction& distance, const CompassFrame& first,
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

  // S = Σ_pairs conj(Z_B)·Z_A, real and imaginary parts apart so that the loop vectorises;
  // summed line after line as the transforms deliver them (fft_spectra.hpp, pair_spectra).
  std::fill(work.sum_re.begin(), work.sum_re.end(), 0.0);
  std::fill(work.sum_im.begin(), work.sum_im.end(), 0.0);
  const detail::PairSpectra pair = detail::pair_spectra(
      first, second, distance.mask(), planning,
      [](const detail::LineSpectra& first_rows, const detail::LineSpectra& second_rows, int begin,
         int end) { work.add_lines(first_rows, second_rows, begin, end); });
  const auto mask = detail::conjugate_mask_spectrum(distance.mask());

  // conj(M)·Q̂ − 2·H with 2·H(f) = S(f) + conj(S(W − f)), then one inverse transform.
  const detail::LinePlans plans = detail::line_plans(width);
  fftw_complex* spectrum = work.spectrum.data();
  const fftw_complex* q = pair.first->column_energy.data();
  const fftw_complex* m = mask->data();
  for (int f = 0; f < bins; ++f) {
    const std::size_t i = static_cast<std::size_t>(f);
    const std::size_t mirror = static_cast<std::size_t>((width - f) % width);
    spectrum[f][0] = m[f][0] * q[f][0] - m[f][1] * q[f][1] - (work.sum_re[i] + work.sum_re[mirror]);
    spectrum[f][1] = m[f][0] * q[f][1] + m[f][1] * q[f][0] - (work.sum_im[i] - work.sum_im[mirror]);
  }
  double* correlation = work.correlation.data();
  fftw_execute_dft_c2r(plans.c2r, spectrum, correlation);

  CorrelationCosts result;
  result.costs.resize(static_cast<std::size_t>(width));
  const double scale = 1.0 / width;
  const double masked_energy = pair.second->masked_energy;
  for (int shift = 0; shift < width; ++shift) {
    result.costs[static_cast<std::size_t>(shift)] = masked_energy + correlation[shift] * scale;
  }
  result.error_bound = detail::error_bound(detail::frame_energy(first),
                                           detail::frame_energy(second), masked_energy, width);
  return result;
}

namespace detail {

ShiftSearch fft_minimise(CostTable& table, FftPlanning planning) {
  const CorrelationCosts estimate =
      correlation_costs(table.distance(), table.first(), table.second(), planning);
  table.set_estimates(estimate.costs);
  // Every shift that may be the minimum, evaluated exactly (EXACT MINIMUM, BOUNDED CURVE).
  const double lowest = *std::min_element(estimate.costs.begin(), estimate.costs.end());
  for (int shift = 0; shift < table.width_px(); ++shift) {
    if (estimate.costs[static_cast<std::size_t>(shift)] <= lowest + 2.0 * estimate.error_bound) {
      table.at(shift);
    }
  }
  return ShiftSearch{table.best_known(), std::nullopt};
}

}  // namespace detail
}  // namespace omninav::compass
