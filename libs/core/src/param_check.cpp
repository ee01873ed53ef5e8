#include "omninav/core/param_check.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"

namespace omninav {

void check_range(const std::string& key, double value, double min, double max) {
  if (!std::isfinite(value)) {
    throw UsageError("key '" + key + "' must be a number in [" + general(min) + ", " +
                     general(max) + "]");
  }
  if (value < min || value > max) {
    throw UsageError("key '" + key + "' = " + general(value) + " is out of range [" + general(min) +
                     ", " + general(max) + "]");
  }
}

void check_range(const std::string& key, int value, int min, int max) {
  if (value < min || value > max) {
    throw UsageError("key '" + key + "' = " + std::to_string(value) + " is out of range [" +
                     std::to_string(min) + ", " + std::to_string(max) + "]");
  }
}

void check_range_deg(const std::string& key, double value_rad, double min_deg, double max_deg) {
  double degrees = rad_to_deg(value_rad);
  // A bound read from YAML in degrees comes back through radians a rounding away from itself.
  const double slack = 1e-9;
  if (std::abs(degrees - min_deg) <= slack * std::max(1.0, std::abs(min_deg))) degrees = min_deg;
  if (std::abs(degrees - max_deg) <= slack * std::max(1.0, std::abs(max_deg))) degrees = max_deg;
  check_range(key, degrees, min_deg, max_deg);
}

}  // namespace omninav
