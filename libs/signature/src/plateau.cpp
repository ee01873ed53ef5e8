#include "omninav/signature/plateau.hpp"

#include <algorithm>
#include <utility>

#include "omninav/core/statistics.hpp"

namespace omninav::signature {

PlateauEstimate::PlateauEstimate(ComponentWeights weights, std::size_t max_samples)
    : weights_(std::move(weights)), max_samples_(std::max<std::size_t>(max_samples, 4)) {}

double PlateauEstimate::pair(const Signature& a, const Signature& b) const {
  return dissimilarity(a, b, -1, weights_) / static_cast<double>(a.size());
}

void PlateauEstimate::halve() {
  std::vector<Signature> kept;
  std::vector<std::optional<double>> kept_steps;
  for (std::size_t i = 0; i < samples_.size(); i += 2) {
    kept.push_back(std::move(samples_[i]));
    kept_steps.push_back(steps_[i]);
  }
  samples_ = std::move(kept);
  steps_ = std::move(kept_steps);
  stride_ *= 2;
  pairs_.clear();
  for (std::size_t a = 0; a < samples_.size(); ++a) {
    for (std::size_t b = a + 1; b < samples_.size(); ++b) {
      pairs_.push_back(pair(samples_[a], samples_[b]));
    }
  }
  update_estimates();
}

void PlateauEstimate::update_estimates() {
  if (!pairs_.empty()) cached_ = quantile(pairs_, kPlateauQuantile);
  std::vector<double> steps;
  for (const std::optional<double>& step : steps_) {
    if (step) steps.push_back(*step);
  }
  if (!steps.empty()) cached_floor_ = quantile(steps, kFloorQuantile);
}

void PlateauEstimate::add(const Signature& signature) {
  previous_frame_.reset();
  add(signature, nullptr);
}

void PlateauEstimate::add_frame(const Signature& signature, bool turn_only) {
  add(signature, previous_frame_ && turn_only ? &*previous_frame_ : nullptr);
  // Kept only for a step that will count.
  if (will_sample()) {
    previous_frame_ = signature;
  } else {
    previous_frame_.reset();
  }
}

bool PlateauEstimate::will_sample() const {
  // As add: a full set of samples first doubles the stride.
  const std::size_t stride = samples_.size() == max_samples_ ? 2 * stride_ : stride_;
  return seen_ % stride == 0;
}

void PlateauEstimate::add(const Signature& signature, const Signature* previous) {
  const std::size_t index = seen_++;
  if (index % stride_ != 0) return;
  if (samples_.size() == max_samples_) {
    halve();
    if (index % stride_ != 0) return;
  }
  for (const Signature& sample : samples_) pairs_.push_back(pair(sample, signature));
  samples_.push_back(signature);
  steps_.push_back(previous ? std::optional<double>(pair(*previous, signature)) : std::nullopt);
  update_estimates();
}

std::optional<double> PlateauEstimate::per_value() const {
  return cached_;
}

std::optional<double> PlateauEstimate::floor_per_value() const {
  return cached_floor_;
}

}  // namespace omninav::signature
