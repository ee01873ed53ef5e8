#pragma once
// The range checks of the components' Params structs (docs/design.md, Conventions: Config). A
// struct's check() states its valid ranges once; the YAML loader reads the values and calls it,
// and so does the algorithm that takes the struct, so that a value set from C++ or Python is
// refused as the same value in a YAML file is. Each check throws UsageError naming the key as
// its YAML file spells it ("sampling.threshold_norm_amp") and the valid range, in the key's unit.

#include <string>

namespace omninav {

void check_range(const std::string& key, double value, double min, double max);
void check_range(const std::string& key, int value, int min, int max);
// A value kept in radians whose key is in degrees (`key` ends in _deg).
void check_range_deg(const std::string& key, double value_rad, double min_deg, double max_deg);

// For a loader: runs `check` (a Params::check()) and turns its UsageError into a ConfigError
// naming the file, as the loader's other errors do.
template <typename Check>
void check_loaded(const std::string& source_name, Check&& check);

}  // namespace omninav

#include "omninav/core/errors.hpp"

namespace omninav {

template <typename Check>
void check_loaded(const std::string& source_name, Check&& check) {
  try {
    check();
  } catch (const UsageError& error) {
    throw ConfigError(source_name + ": " + error.what());
  }
}

}  // namespace omninav
