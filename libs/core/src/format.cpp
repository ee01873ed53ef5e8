#include "omninav/core/format.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace omninav {

std::string fixed(double value, int decimals) {
  return fmt::format("{:.{}f}", value, decimals);
}

std::string signed_fixed(double value, int decimals) {
  return fmt::format("{:+.{}f}", value, decimals);
}

std::string fixed_or_empty(const std::optional<double>& value, int decimals) {
  return value ? fixed(*value, decimals) : std::string();
}

std::string trimmed(double value, int decimals) {
  std::string text = fixed(value, decimals);
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  return text == "-0" ? "0" : text;
}

std::string general(double value, int significant) {
  return fmt::format("{:.{}g}", value, significant);
}

std::string shortest(double value) {
  return fmt::format("{}", value);
}

double rounded(double value, int decimals) {
  if (!std::isfinite(value)) return value;
  const std::string text = fixed(value, decimals);
  double result = value;
  std::from_chars(text.data(), text.data() + text.size(), result);
  return result;
}

}  // namespace omninav
