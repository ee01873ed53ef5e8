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
  for (std::size_t i = 0; i < samples_.size(); i += 2) kept.push_back(std::move(samples_[i]));
  samples_ = std::move(kept);
  stride_ *= 2;
  pairs_.clear();
  for (std::size_t a = 0; a < samples_.size(); ++a) {
    for (std::size_t b = a + 1; b < samples_.size(); ++b) {
      pairs_.push_back(pair(samples_[a], samples_[b]));
    }
  }
  cached_ = quantile(pairs_, kPlateauQuantile);
}

void PlateauEstimate::add(const Signature& signature) {
  const std::size_t index = seen_++;
  if (index % stride_ != 0) return;
  if (samples_.size() == max_samples_) {
    halve();
    if (index % stride_ != 0) return;
  }
  for (const Signature& sample : samples_) pairs_.push_back(pair(sample, signature));
  samples_.push_back(signature);
  if (!pairs_.empty()) cached_ = quantile(pairs_, kPlateauQuantile);
}

std::optional<double> PlateauEstimate::per_value() const {
  return cached_;
}

}  // namespace omninav::signature
