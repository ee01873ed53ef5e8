#pragma once
// Ways of finding the shift that minimises d(I_i, I_j, α) (Labrosse 2006, Eq. 5), interchangeable
// behind one interface so that tests and benchmarks run every variant on the same pairs and the
// exhaustive search checks the others (STYLE.md, "BoB robotics"):
//
//   exhaustive  (a) every one of the W shifts (Fig. 3 of Labrosse 2004): the oracle.
//               It uses DistanceFunction::reference_cost, the plain transcription of Eq. 2,
//               unless built with the fast kernel (for benchmarks).
//   local_scan  (b) the minimisation of Labrosse 2006, §3.3.4: descent from a start value, then
//   eight
//               values spanning 20° centred on the local minimum; when one of them is lower the
//               descent restarts from it. Finds the global minimum when the start is good
//               (Algorithm 1 starts from the previous rotation) or when seeded by the phase.
//   fft         (c) every d(α) at once by masked circular cross-correlation in single
//               precision, within a stated bound (fft_correlation.cpp derives both), then the
//               shifts that may be the minimum evaluated exactly: the same minimum and cost.
//   phase       (d) the Fourier-phase estimate of Menegatti et al. 2004, §2.1 (phase.hpp):
//               no distance minimisation at all; its integer shift is the rounded estimate.
//
// (a), (b) and (c) return the same integer minimum in the order of cost_table.hpp whenever (b)
// reaches the global minimum; tests check it on rendered and real pairs.

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "omninav/compass/cost_table.hpp"
#include "omninav/compass/phase.hpp"

namespace omninav::compass {

enum class MinimiserKind { kExhaustive, kLocalScan, kFft, kPhase };

std::string to_string(MinimiserKind kind);
// "exhaustive", "local_scan" (also "local"), "fft", "phase"; UsageError otherwise.
MinimiserKind minimiser_kind_of(std::string_view name);

enum class FftPlanning {
  kEstimate,  // FFTW_ESTIMATE: plans from the sizes alone, made instantly
  kMeasure,   // FFTW_MEASURE: plans timed once per size (~0.4 s at 1080), faster transforms
};

struct MinimiserParams {
  MinimiserKind kind = MinimiserKind::kLocalScan;  // "local + regular scanning", Table 2
  // (b): the regular scan after each descent: scan_values values spanning scan_span_rad,
  // centred on the local minimum (eight values spanning 20°, Labrosse 2006, §3.3.4), at 360
  // columns; the count grows with the width so that the values stay as many columns apart (24 at
  // 1080).
  int scan_values = 8;
  double scan_span_rad = 20.0 * 3.14159265358979323846 / 180.0;
  // (a): use the fast kernel instead of the plain oracle code (benchmarks only).
  bool exhaustive_fast_kernel = false;
  // (c): how FFTW plans. The minimum and its cost are exact either way, so results do not
  // depend on the plan FFTW picks (the other shifts' estimates do, within their bound).
  FftPlanning fft_planning = FftPlanning::kEstimate;
  PhaseParams phase;
};

// What a minimiser found.
struct ShiftSearch {
  int shift_px = 0;  // the integer minimum a_m, signed in (−W/2, W/2]
  // (d) only: the continuous estimate the integer shift was rounded from.
  std::optional<double> continuous_shift_px;
};

class Minimiser {
 public:
  virtual ~Minimiser() = default;
  virtual MinimiserKind kind() const = 0;
  // Finds the minimum of table's pair. `start_shift_px` is where a local method starts (the
  // others ignore it). The table keeps every cost looked at, for the sub-pixel fit and the
  // confidence tests.
  virtual ShiftSearch minimise(CostTable& table, int start_shift_px) const = 0;
};

// Throws UsageError for a combination that cannot work (fft with the L1 metric: the FFT
// expands a square).
std::unique_ptr<Minimiser> make_minimiser(const MinimiserParams& params, Metric metric);

// The descent of (b) alone, from `start_shift_px`, in the order of cost_table.hpp: the local
// minimum it ends at, signed in (−W/2, W/2].
int descend(CostTable& table, int start_shift_px);

// The scan offsets of (b) in columns for a panorama `width_px` wide: scan_values offsets at 360
// columns (max(scan_values, scan_values·W/360) at W), symmetric, the outermost at
// ±scan_span/2 (±10° at W = 360: ±3, ±5, ±8, ±10 columns).
std::vector<int> scan_offsets_px(const MinimiserParams& params, int width_px);

}  // namespace omninav::compass
