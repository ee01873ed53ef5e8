#include "omninav/compass/pair_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

#include "frame_caches.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::compass {
namespace {

// d at a fractional shift, linear between its two integer neighbours (used at α_m + W/2 for
// Eq. 12, and at a_m + W/2 for odd widths).
double distance_at(CostTable& table, double shift_px) {
  const double lower = std::floor(shift_px);
  const double fraction = shift_px - lower;
  const int base = static_cast<int>(lower);
  const double at_lower = table.distance_at(base);
  if (fraction == 0.0) return at_lower;
  return (1.0 - fraction) * at_lower + fraction * table.distance_at(base + 1);
}

int circular_gap(int a, int b, int width) {
  const int gap = wrap_shift(a - b, width);
  return std::min(gap, width - gap);
}

// Another local minimum at least `separation` columns from `best` and below `ceiling`: its shift
// (the lowest such minimum of a complete table, the first descent's end otherwise).
std::optional<int> competing_minimum(CostTable& table, int best, int separation, double ceiling) {
  const int width = table.width_px();
  if (2 * separation > width) return std::nullopt;
  if (table.complete()) {
    // With the FFT's estimates where no exact cost is known: they err by at most the bound of
    // fft_correlation.cpp, ~10⁻³ of the amplitude at 1080×135 (the errors measured, ~10⁻⁶),
    // far below the 15 % this test looks for.
    std::optional<int> lowest;
    Cost lowest_cost = 0;
    for (int s = 0; s < width; ++s) {
      if (circular_gap(s, best, width) < separation) continue;
      const Cost here = table.cost_or_estimate(s);
      const Cost left = table.cost_or_estimate(s - 1);
      const Cost right = table.cost_or_estimate(s + 1);
      // Strict on the left, so that a plateau counts once.
      if (here < left && here <= right && table.distance().distance(here) < ceiling &&
          (!lowest || here < lowest_cost)) {
        lowest = s;
        lowest_cost = here;
      }
    }
    return lowest;
  }
  // Only some shifts are known (local_scan): descend from the lowest known ones that come
  // close enough, and flag a descent that ends far from the best.
  std::vector<std::pair<Cost, int>> candidates;
  const std::vector<Cost>& costs = table.costs();
  for (int s = 0; s < width; ++s) {
    const Cost cost = costs[static_cast<std::size_t>(s)];
    if (cost < 0 || circular_gap(s, best, width) < separation) continue;
    if (table.distance().distance(cost) < ceiling) candidates.emplace_back(cost, s);
  }
  std::sort(candidates.begin(), candidates.end());
  constexpr std::size_t kMaxDescents = 3;
  for (std::size_t i = 0; i < std::min(candidates.size(), kMaxDescents); ++i) {
    const int minimum = descend(table, candidates[i].second);
    if (circular_gap(minimum, best, width) >= separation && table.distance_at(minimum) < ceiling) {
      return minimum;
    }
  }
  return std::nullopt;
}

// The FFT and the phase leave only a few shifts to evaluate (the FFT's candidates, the sub-pixel
// fit's neighbours, the amplitude's half turn): on the frames' rows, without column-major copies.
// The searches visit many: on the copies.
CostTable::Kernel kernel_for(MinimiserKind kind) {
  return kind == MinimiserKind::kFft || kind == MinimiserKind::kPhase ? CostTable::Kernel::kRows
                                                                      : CostTable::Kernel::kColumns;
}

std::uint64_t distance_key(const DistanceFunction& distance) {
  return distance.mask().key() * 2 + (distance.metric() == Metric::kL2 ? 0 : 1);
}

}  // namespace

std::string ConfidenceFlags::describe() const {
  std::string text;
  const auto add = [&text](bool flag, const char* name) {
    if (!flag) return;
    if (!text.empty()) text += '+';
    text += name;
  };
  add(featureless, "featureless");
  add(competing_minima, "competing_minima");
  add(low_amplitude, "low_amplitude");
  return text.empty() ? "ok" : text;
}

namespace {

// The parameters, once check() has passed: the minimiser is made from them in the initialiser.
const PairMatcherParams& checked(const PairMatcherParams& params) {
  params.check();
  return params;
}

}  // namespace

void PairMatcherParams::check() const {
  check_range_deg("distance.band_width_deg", distance.field_of_view.band_width_rad, 1.0, 180.0);
  check_range("minimiser.scan_values", minimiser.scan_values, 2, 64);
  check_range_deg("minimiser.scan_span_deg", minimiser.scan_span_rad, 0.1, 180.0);
  check_range("phase.components", minimiser.phase.components, 1, 4096);
  check_range("subpixel.parabolic_up_to_norm_amp", subpixel.parabolic_up_to_norm_amp, 0.0, 10.0);
  check_range("subpixel.linear_from_norm_amp", subpixel.linear_from_norm_amp, 0.0, 10.0);
  check_range("confidence.flat_below_grey", confidence.flat_below_grey, 0.0, 255.0);
  check_range_deg("confidence.competing_separation_deg", confidence.competing_separation_rad, 0.1,
                  180.0);
  check_range("confidence.competing_depth_ratio", confidence.competing_depth_ratio, 0.0, 1.0);
  if (minimiser.kind == MinimiserKind::kFft && distance.metric == Metric::kL1) {
    throw UsageError(
        "minimiser.kind 'fft' needs distance.metric 'l2' (the FFT expands the square of Eq. 2)");
  }
}

PairMatcher::PairMatcher(const PairMatcherParams& params)
    : params_(checked(params)),
      minimiser_(make_minimiser(params.minimiser, params.distance.metric)),
      kernel_(kernel_for(params.minimiser.kind)) {}

PairMatcher::~PairMatcher() = default;

const DistanceFunction& PairMatcher::distance_function(int width_px) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = distances_[width_px];
  if (!slot) slot = std::make_unique<DistanceFunction>(params_.distance, width_px);
  return *slot;
}

double PairMatcher::self_distance(const CompassFrame& frame, bool half_turn) const {
  const DistanceFunction& distance = distance_function(frame.width());
  const std::uint64_t key = distance_key(distance);
  detail::FrameCaches& caches = frame.caches();
  std::map<std::uint64_t, double>& cache = half_turn ? caches.self_amplitude : caches.self_step;
  {
    const std::lock_guard<std::mutex> lock(caches.mutex);
    if (const auto found = cache.find(key); found != cache.end()) return found->second;
  }
  // A(I, I) = d(I, I, W/2) − d(I, I, 0), and d(I, I, 0) = 0; the step is d(I, I, 1).
  CostTable table(distance, frame, frame, kernel_);
  const double value = half_turn ? distance_at(table, frame.width() / 2.0) - table.distance_at(0)
                                 : table.distance_at(1);
  const std::lock_guard<std::mutex> lock(caches.mutex);
  cache[key] = value;
  return value;
}

double PairMatcher::self_amplitude(const CompassFrame& frame) const {
  return self_distance(frame, true);
}

double PairMatcher::self_step(const CompassFrame& frame) const {
  return self_distance(frame, false);
}

PairMatch PairMatcher::match(const CompassFrame& first, const CompassFrame& second,
                             int start_shift_px) const {
  return match_with(first, second,
                    [&](CostTable& table) { return minimiser_->minimise(table, start_shift_px); });
}

PairMatch PairMatcher::match_in_basin(const CompassFrame& first, const CompassFrame& second,
                                      int start_shift_px) const {
  return match_with(first, second, [&](CostTable& table) {
    return ShiftSearch{descend(table, start_shift_px), std::nullopt};
  });
}

PairMatch PairMatcher::match_with(const CompassFrame& first, const CompassFrame& second,
                                  const std::function<ShiftSearch(CostTable&)>& minimise) const {
  require_same_shape(first, second);
  const int width = first.width();
  const DistanceFunction& distance = distance_function(width);
  CostTable table(distance, first, second, kernel_);
  const ShiftSearch search = minimise(table);

  PairMatch match;
  match.shift_px = search.shift_px;
  const int a = search.shift_px;
  const double d_minus = table.distance_at(a - 1);
  const double d_0 = table.distance_at(a);
  const double d_plus = table.distance_at(a + 1);
  const double half_turn = width / 2.0;

  // Eq. 9 and its normalisation by A(I_i, I_i) (Eq. 8).
  match.self_amplitude = self_amplitude(first);
  match.self_step = self_step(first);
  const double amplitude_px = distance_at(table, a + half_turn) - d_0;
  match.amplitude_norm_px = match.self_amplitude > 0.0 ? amplitude_px / match.self_amplitude : 0.0;

  // Eqs. 10-11, or the phase estimate itself when the minimiser is (d).
  if (search.continuous_shift_px) {
    match.subpixel_shift_px = *search.continuous_shift_px;
    match.distance_min = d_0;
  } else {
    const SubpixelFit fit =
        subpixel_fit(d_minus, d_0, d_plus, match.amplitude_norm_px, params_.subpixel);
    match.subpixel_shift_px = a + fit.offset_px;
    match.distance_min = fit.value;
  }
  // Eq. 12 and Eq. 8.
  match.amplitude = distance_at(table, match.subpixel_shift_px + half_turn) - match.distance_min;
  match.amplitude_norm = match.self_amplitude > 0.0 ? match.amplitude / match.self_amplitude : 0.0;
  // Eq. 4: ρ = −α_m·360/W, counter-clockwise positive (distance.hpp).
  match.rotation_rad = wrap_angle(-rotation_of_shift_px(match.subpixel_shift_px, width));

  // Confidence.
  const ConfidenceParams& confidence = params_.confidence;
  const double flat = distance.distance_of_mean_difference(confidence.flat_below_grey, first);
  match.flags.featureless = !(amplitude_px >= flat) || !(match.self_amplitude >= flat);
  if (!match.flags.featureless) {
    const int separation = std::max(
        2, static_cast<int>(std::lround(confidence.competing_separation_rad * width / kTwoPi)));
    const std::optional<int> competing = competing_minimum(
        table, a, separation, d_0 + confidence.competing_depth_ratio * amplitude_px);
    match.flags.competing_minima = competing.has_value();
    if (competing) {
      match.competing_rotation_rad =
          wrap_angle(-rotation_of_shift_px(signed_shift(*competing, width), width));
    }
  }
  // The minimum's uncertainty: the residual d_m as the roll of the first image that costs as much.
  match.shift_sigma_px = match.self_step > 0.0 ? match.distance_min / match.self_step
                                               : std::numeric_limits<double>::infinity();
  match.evaluations = table.evaluations();
  return match;
}

}  // namespace omninav::compass
