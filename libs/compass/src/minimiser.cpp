#include "omninav/compass/minimiser.hpp"

#include <algorithm>
#include <cmath>

#include "fft_spectra.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {
namespace {

bool before(CostTable& table, int a, int b) {
  return shift_before(a, table.at(a), b, table.at(b), table.width_px());
}

// (a) Every shift (Fig. 3 of Labrosse 2004), best in the order of cost_table.hpp.
class ExhaustiveMinimiser : public Minimiser {
 public:
  explicit ExhaustiveMinimiser(bool fast_kernel) : fast_kernel_(fast_kernel) {}
  MinimiserKind kind() const override { return MinimiserKind::kExhaustive; }
  ShiftSearch minimise(CostTable& table, int /*start_shift_px*/) const override {
    const int width = table.width_px();
    for (int shift = 0; shift < width; ++shift) {
      if (fast_kernel_) {
        table.at(shift);
      } else {
        table.set(shift, table.distance().reference_cost(table.first(), table.second(), shift));
      }
    }
    if (!fast_kernel_) table.add_evaluations(width);
    return ShiftSearch{table.best_known(), std::nullopt};
  }

 private:
  bool fast_kernel_;
};

// (b) Descent, then the regular scan around the local minimum, restarting from any scan value
// that is lower (Labrosse 2006, §3.3.4).
class LocalScanMinimiser : public Minimiser {
 public:
  explicit LocalScanMinimiser(const MinimiserParams& params) : params_(params) {}
  MinimiserKind kind() const override { return MinimiserKind::kLocalScan; }
  ShiftSearch minimise(CostTable& table, int start_shift_px) const override {
    const int width = table.width_px();
    const std::vector<int> offsets = scan_offsets_px(params_, width);
    int best = descend(table, start_shift_px);
    // Each restart starts from a shift strictly before the current minimum in a total order,
    // so this ends after at most W restarts.
    for (int guard = 0; guard < width; ++guard) {
      int candidate = best;
      for (const int offset : offsets) {
        if (before(table, best + offset, candidate)) candidate = best + offset;
      }
      if (candidate == best) break;
      best = descend(table, candidate);
    }
    return ShiftSearch{signed_shift(best, width), std::nullopt};
  }

 private:
  MinimiserParams params_;
};

// (d) The rounded Fourier-phase estimate.
class PhaseMinimiser : public Minimiser {
 public:
  explicit PhaseMinimiser(const PhaseParams& params) : params_(params) {}
  MinimiserKind kind() const override { return MinimiserKind::kPhase; }
  ShiftSearch minimise(CostTable& table, int /*start_shift_px*/) const override {
    const PhaseEstimate phase = estimate_phase_shift(table.first(), table.second(), params_);
    const int width = table.width_px();
    return ShiftSearch{signed_shift(static_cast<int>(std::lround(phase.shift_px)), width),
                       phase.shift_px};
  }

 private:
  PhaseParams params_;
};

class FftMinimiser : public Minimiser {
 public:
  explicit FftMinimiser(FftPlanning planning) : planning_(planning) {}
  MinimiserKind kind() const override { return MinimiserKind::kFft; }
  ShiftSearch minimise(CostTable& table, int /*start_shift_px*/) const override {
    return detail::fft_minimise(table, planning_);
  }

 private:
  FftPlanning planning_;
};

}  // namespace

std::string to_string(MinimiserKind kind) {
  switch (kind) {
    case MinimiserKind::kExhaustive:
      return "exhaustive";
    case MinimiserKind::kLocalScan:
      return "local_scan";
    case MinimiserKind::kFft:
      return "fft";
    case MinimiserKind::kPhase:
      return "phase";
  }
  return "?";
}

MinimiserKind minimiser_kind_of(std::string_view name) {
  if (name == "exhaustive") return MinimiserKind::kExhaustive;
  if (name == "local_scan" || name == "local") return MinimiserKind::kLocalScan;
  if (name == "fft") return MinimiserKind::kFft;
  if (name == "phase") return MinimiserKind::kPhase;
  throw UsageError("unknown minimiser '" + std::string(name) +
                   "': expected exhaustive, local_scan, fft or phase");
}

int descend(CostTable& table, int start_shift_px) {
  const int width = table.width_px();
  int current = wrap_shift(start_shift_px, width);
  // At most W steps: each one moves to a shift strictly before the current one.
  for (int step = 0; step < width; ++step) {
    int next = current;
    if (before(table, current - 1, next)) next = current - 1;
    if (before(table, current + 1, next)) next = current + 1;
    if (next == current) break;
    const int direction = next - current;
    current = next;
    // Keep going the same way while it descends: about r + 1 evaluations for a rotation of r
    // columns (§3.3.4).
    while (before(table, current + direction, current) && ++step < width) current += direction;
    current = wrap_shift(current, width);
  }
  return signed_shift(current, width);
}

std::vector<int> scan_offsets_px(const MinimiserParams& params, int width_px) {
  std::vector<int> offsets;
  // §3.3.4's eight values spanning 20° were used at one column per degree: a value every 2.5
  // columns. At W columns the count grows as W/360 (never below the configured count) so that
  // they stay 2.5 columns apart: at 1080 columns (3 px/°) the distance function has ripples a
  // third as wide in degrees (finer texture is resolved), and eight values 7.5 columns apart
  // step over the basin of the global minimum (docs/evaluation.md, "Compass: the local scan at
  // higher resolution").
  const int scaled = static_cast<int>(std::lround(params.scan_values * width_px / 360.0 / 2.0)) * 2;
  const int half = std::max(params.scan_values, scaled) / 2;
  if (half < 1) return offsets;
  // Values at ±k·step, k = 1..half, the outermost at ±span/2: eight values spanning 20° at
  // 360 columns are ±2.5°, ±5°, ±7.5°, ±10°.
  const double step_px = params.scan_span_rad / 2.0 / half * width_px / kTwoPi;
  for (int k = 1; k <= half; ++k) {
    // (+1e-9: 7.5 columns must round to 8 whatever the last bit of step_px.)
    const int offset = std::max(1, static_cast<int>(std::lround(k * step_px + 1e-9)));
    if (std::find(offsets.begin(), offsets.end(), offset) != offsets.end()) continue;
    if (2 * offset >= width_px) break;
    offsets.push_back(offset);
    offsets.push_back(-offset);
  }
  return offsets;
}

std::unique_ptr<Minimiser> make_minimiser(const MinimiserParams& params, Metric metric) {
  switch (params.kind) {
    case MinimiserKind::kExhaustive:
      return std::make_unique<ExhaustiveMinimiser>(params.exhaustive_fast_kernel);
    case MinimiserKind::kLocalScan:
      if (params.scan_values < 2 || params.scan_values % 2 != 0) {
        throw UsageError("the local minimiser's scan needs an even number of values (>= 2), got " +
                         std::to_string(params.scan_values));
      }
      return std::make_unique<LocalScanMinimiser>(params);
    case MinimiserKind::kFft:
      if (metric != Metric::kL2) {
        throw UsageError(
            "the fft minimiser needs the l2 metric: it expands the square of Eq. 2 (choose "
            "metric: l2, or another minimiser)");
      }
      return std::make_unique<FftMinimiser>(params.fft_planning);
    case MinimiserKind::kPhase:
      return std::make_unique<PhaseMinimiser>(params.phase);
  }
  throw UsageError("unknown minimiser");
}

}  // namespace omninav::compass
