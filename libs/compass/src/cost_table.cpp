#include "omninav/compass/cost_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace omninav::compass {

bool shift_before(int shift_a, Cost cost_a, int shift_b, Cost cost_b, int width_px) {
  if (cost_a != cost_b) return cost_a < cost_b;
  const int signed_a = signed_shift(shift_a, width_px);
  const int signed_b = signed_shift(shift_b, width_px);
  if (std::abs(signed_a) != std::abs(signed_b)) return std::abs(signed_a) < std::abs(signed_b);
  return signed_a > signed_b;  // +s before −s; equal shifts are not "before" each other
}

CostTable::CostTable(const DistanceFunction& distance, const CompassFrame& first,
                     const CompassFrame& second, Kernel kernel)
    : distance_(distance),
      first_(first),
      second_(second),
      kernel_(kernel),
      costs_(static_cast<std::size_t>(distance.width_px()), Cost{-1}) {
  distance_.check(first_, second_);
}

Cost CostTable::at(int shift_px) {
  Cost& slot = costs_[index(shift_px)];
  if (slot < 0) {
    slot = kernel_ == Kernel::kColumns ? distance_.cost(first_, second_, shift_px)
                                       : distance_.cost_on_rows(first_, second_, shift_px);
    ++evaluations_;
  }
  return slot;
}

void CostTable::set_estimates(const std::vector<double>& estimates) {
  estimates_.resize(costs_.size());
  for (std::size_t i = 0; i < estimates_.size(); ++i) {
    estimates_[i] = estimates[i] <= 0.0 ? Cost{0} : static_cast<Cost>(std::llround(estimates[i]));
  }
}

Cost CostTable::cost_or_estimate(int shift_px) const {
  const std::size_t i = index(shift_px);
  if (costs_[i] >= 0 || estimates_.empty()) return costs_[i];
  return estimates_[i];
}

bool CostTable::complete() const {
  return !estimates_.empty() ||
         std::none_of(costs_.begin(), costs_.end(), [](Cost cost) { return cost < 0; });
}

int CostTable::best_known() const {
  int best = -1;
  for (int shift = 0; shift < width_px(); ++shift) {
    const Cost cost = costs_[static_cast<std::size_t>(shift)];
    if (cost < 0) continue;
    if (best < 0 ||
        shift_before(shift, cost, best, costs_[static_cast<std::size_t>(best)], width_px())) {
      best = shift;
    }
  }
  return best < 0 ? 0 : signed_shift(best, width_px());
}

}  // namespace omninav::compass
