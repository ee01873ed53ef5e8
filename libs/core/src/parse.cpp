#include "omninav/core/parse.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"

namespace omninav {

std::string_view trim(std::string_view text) {
  constexpr std::string_view kBlanks = " \t\r\n";
  const std::size_t first = text.find_first_not_of(kBlanks);
  if (first == std::string_view::npos) return {};
  const std::size_t last = text.find_last_not_of(kBlanks);
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    fields.emplace_back(
        trim(text.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) return fields;
    start = end + 1;
  }
}

double parse_double(std::string_view text, const std::string& where) {
  const std::string_view trimmed = trim(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(trimmed.data(), trimmed.data() + trimmed.size(), value);
  if (trimmed.empty() || error != std::errc() || end != trimmed.data() + trimmed.size() ||
      !std::isfinite(value)) {
    throw InputError(where + ": '" + std::string(text) + "' is not a number");
  }
  return value;
}

int parse_int(std::string_view text, const std::string& where) {
  const std::string_view trimmed = trim(text);
  int value = 0;
  const auto [end, error] = std::from_chars(trimmed.data(), trimmed.data() + trimmed.size(), value);
  if (trimmed.empty() || error != std::errc() || end != trimmed.data() + trimmed.size()) {
    throw InputError(where + ": '" + std::string(text) + "' is not a whole number");
  }
  return value;
}

double parse_double_argument(std::string_view text, const std::string& where) {
  try {
    return parse_double(text, where);
  } catch (const InputError& error) {
    throw UsageError(error.what());
  }
}

int parse_int_argument(std::string_view text, const std::string& where) {
  try {
    return parse_int(text, where);
  } catch (const InputError& error) {
    throw UsageError(error.what());
  }
}

double check_coordinate_m(double value_m, const std::string& where) {
  if (!std::isfinite(value_m)) {
    throw InputError(
        fmt::format("{}: {} m is not a position (not a finite number)", where, general(value_m)));
  }
  if (std::abs(value_m) > kMaxCoordinateM) {
    throw InputError(fmt::format("{}: {} m is not a position (beyond ±{} m)", where,
                                 general(value_m), general(kMaxCoordinateM)));
  }
  return value_m;
}

const CameraPose& check_pose(const CameraPose& pose, const std::string& where) {
  check_coordinate_m(pose.x_m, where + ": x");
  check_coordinate_m(pose.y_m, where + ": y");
  check_coordinate_m(pose.z_m, where + ": z");
  for (const auto& [angle, name] :
       {std::pair{pose.heading_rad, "heading"}, std::pair{pose.pitch_rad, "pitch"},
        std::pair{pose.roll_rad, "roll"}}) {
    if (!std::isfinite(angle)) {
      throw InputError(where + ": " + name + " is " + general(angle) + ", not a finite angle");
    }
  }
  return pose;
}

}  // namespace omninav
