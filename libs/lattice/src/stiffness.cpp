#include "omninav/lattice/stiffness.hpp"

#include <cmath>

namespace omninav::lattice {

double spring_stiffness(double estimated_length_m, double correlation_range_m) {
  const double ratio = estimated_length_m / correlation_range_m;
  return std::exp(ratio * ratio * std::log(0.1));
}

double negligible_length_m(double correlation_range_m, double min_stiffness) {
  // Solve 0.1^((x/x₁)²) = K_min for x.
  return correlation_range_m * std::sqrt(std::log(min_stiffness) / std::log(0.1));
}

}  // namespace omninav::lattice
