#include "omninav/core/json.hpp"

#include <cmath>

#include "omninav/core/format.hpp"

namespace omninav {

Json json_number(const std::optional<double>& value, int decimals) {
  if (!value || !std::isfinite(*value)) return nullptr;
  return rounded(*value, decimals);
}

std::string json_text(const Json& json) {
  return json.dump(2, ' ', false, Json::error_handler_t::replace);
}

}  // namespace omninav
