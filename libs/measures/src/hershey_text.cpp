#include "omninav/measures/hershey_text.hpp"

#include <array>
#include <cctype>
#include <utility>

namespace omninav::measures {

std::string hershey_text(std::string_view utf8) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 18> kSpelled{{
      {"\u00b0", "deg"},
      {"\u00b1", "+/-"},
      {"\u03c3", "sigma"},
      {"\u00d7", "x"},
      {"\u2212", "-"},
      {"\u2013", "-"},
      {"\u2014", "-"},
      {"\u2264", "<="},
      {"\u2265", ">="},
      {"\u2192", "->"},
      {"\u2190", "<-"},
      {"\u2032", "'"},
      {"\u2033", "\""},
      {"\u00b5", "u"},
      {"\u03b8", "theta"},
      {"\u03c8", "psi"},
      {"\u03b1", "alpha"},
      {"\u0394", "d"},
  }};
  std::string text;
  std::size_t i = 0;
  while (i < utf8.size()) {
    const auto byte = static_cast<unsigned char>(utf8[i]);
    if (byte < 0x80) {
      text += static_cast<char>(byte);
      ++i;
      continue;
    }
    bool spelled = false;
    for (const auto& [symbol, ascii] : kSpelled) {
      if (utf8.substr(i, symbol.size()) != symbol) continue;
      if (symbol == "\u00b0" && !text.empty() &&
          std::isdigit(static_cast<unsigned char>(text.back()))) {
        text += ' ';
      }
      text += ascii;
      i += symbol.size();
      spelled = true;
      break;
    }
    if (spelled) continue;
    // Another character: one '?' for its whole UTF-8 sequence (lead byte and continuations).
    text += '?';
    ++i;
    while (i < utf8.size() && (static_cast<unsigned char>(utf8[i]) & 0xC0) == 0x80) ++i;
  }
  return text;
}

}  // namespace omninav::measures
