#include "omninav/signature/dissimilarity.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::signature {

double ComponentWeights::operator[](int k) const {
  if (alpha.empty()) return 1.0;
  return alpha[std::min<std::size_t>(static_cast<std::size_t>(k), alpha.size() - 1)];
}

ComponentWeights parse_component_weights(const std::string& text, const std::string& where) {
  ComponentWeights weights;
  weights.alpha.clear();
  for (const std::string& field : split(text, ',')) {
    double value = 0.0;
    try {
      value = parse_double(field, where);
    } catch (const InputError& error) {
      throw ConfigError(error.what());
    }
    if (value < 0.0 || value > 1e6) {
      throw ConfigError(where + ": weight " + field + " is out of range [0, 1e6]");
    }
    weights.alpha.push_back(value);
  }
  if (weights.alpha.empty()) throw ConfigError(where + ": no weights given");
  return weights;
}

std::string to_string(const ComponentWeights& weights) {
  std::string text;
  for (std::size_t i = 0; i < weights.alpha.size(); ++i) {
    if (i > 0) text += ',';
    text += general(weights.alpha[i], 17);
  }
  return text;
}

namespace {

// The components two signatures are compared on: `components`, or all both hold when < 0.
// Throws UsageError when their layouts differ or they hold fewer.
int compared_components(const Signature& a, const Signature& b, int components) {
  if (!a.same_layout(b)) {
    throw UsageError("cannot compare signatures of " + std::to_string(a.rows) + "x" +
                     std::to_string(a.channels) + " and " + std::to_string(b.rows) + "x" +
                     std::to_string(b.channels) + " rows x channels");
  }
  const int m = components < 0 ? std::min(a.components, b.components) : components;
  if (m > a.components || m > b.components) {
    throw UsageError("asked for " + std::to_string(m) + " components of signatures holding " +
                     std::to_string(std::min(a.components, b.components)));
  }
  return m;
}

}  // namespace

double dissimilarity(const Signature& a, const Signature& b, int components,
                     const ComponentWeights& weights) {
  const int m = compared_components(a, b, components);
  double total = 0.0;
  for (int k = 0; k < m; ++k) {
    double sum_k = 0.0;
    for (int line = 0; line < a.lines(); ++line) {
      sum_k += std::fabs(static_cast<double>(a.magnitude[a.at(line, k)]) -
                         static_cast<double>(b.magnitude[b.at(line, k)]));
    }
    total += weights[k] * sum_k;
  }
  return total;
}

double rotational_dissimilarity(const Signature& from, const Signature& to, double turn_rad,
                                int components, const ComponentWeights& weights) {
  const int m = compared_components(from, to, components);
  double total = 0.0;
  for (int k = 0; k < m; ++k) {
    // |b − e^{−ik·turn}·a|² = |a|² + |b|² − 2|a||b|·cos(φ_b − φ_a + k·turn).
    const double k_turn = static_cast<double>(k) * turn_rad;
    double sum_k = 0.0;
    for (int line = 0; line < from.lines(); ++line) {
      const double a = from.magnitude[from.at(line, k)];
      const double b = to.magnitude[to.at(line, k)];
      const double angle = static_cast<double>(to.phase_rad[to.at(line, k)]) -
                           static_cast<double>(from.phase_rad[from.at(line, k)]) + k_turn;
      sum_k += std::sqrt(std::max(0.0, a * a + b * b - 2.0 * a * b * std::cos(angle)));
    }
    total += weights[k] * sum_k;
  }
  return total;
}

double similarity_0_1000(double dissimilarity, double min_dissimilarity, double max_dissimilarity) {
  if (!(max_dissimilarity > min_dissimilarity)) return 1000.0;
  const double sim = 1000.0 - 1000.0 * (dissimilarity - min_dissimilarity) /
                                  (max_dissimilarity - min_dissimilarity);
  return std::clamp(sim, 0.0, 1000.0);
}

std::vector<double> rescale_similarities(std::span<const double> dissimilarities) {
  std::vector<double> out(dissimilarities.size());
  if (dissimilarities.empty()) return out;
  const auto [lo, hi] = std::minmax_element(dissimilarities.begin(), dissimilarities.end());
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = similarity_0_1000(dissimilarities[i], *lo, *hi);
  }
  return out;
}

}  // namespace omninav::signature
