#pragma once
// JSON output through nlohmann-json: objects keep their keys in the order written.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace omninav {

using Json = nlohmann::ordered_json;

// `value` rounded to `decimals` digits after the point (format.hpp's rounded()); null when
// missing or not finite.
Json json_number(const std::optional<double>& value, int decimals);

// `json` as text, indented by two spaces; bytes that are not UTF-8 (a file name in another
// encoding) become U+FFFD rather than an exception.
std::string json_text(const Json& json);

}  // namespace omninav
