#include "omninav/io/natural_sort.hpp"

#include <algorithm>
#include <cctype>

namespace omninav::io {
namespace {

bool is_digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}
char lower(char c) {
  return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}

std::size_t digit_run_end(std::string_view text, std::size_t start) {
  while (start < text.size() && is_digit(text[start])) ++start;
  return start;
}

// The digits of the run starting at `start`, without leading zeros.
std::string_view number_at(std::string_view text, std::size_t start, std::size_t end) {
  while (start < end && text[start] == '0') ++start;
  return text.substr(start, end - start);
}

}  // namespace

bool natural_less(std::string_view a, std::string_view b) {
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() && j < b.size()) {
    if (is_digit(a[i]) && is_digit(b[j])) {
      // Compare the runs as numbers of any length: without leading zeros, the longer run is
      // the larger number, and equal lengths compare digit by digit.
      const std::size_t a_end = digit_run_end(a, i);
      const std::size_t b_end = digit_run_end(b, j);
      const std::string_view a_number = number_at(a, i, a_end);
      const std::string_view b_number = number_at(b, j, b_end);
      if (a_number.size() != b_number.size()) return a_number.size() < b_number.size();
      if (a_number != b_number) return a_number < b_number;
      i = a_end;
      j = b_end;
      continue;
    }
    // A non-digit is either below '0' or above '9' in ASCII (letters too, once lowered), so
    // comparing it with the first digit of a run orders it the same against every number.
    const char a_char = lower(a[i]);
    const char b_char = lower(b[j]);
    if (a_char != b_char) return a_char < b_char;
    ++i;
    ++j;
  }
  if ((i == a.size()) != (j == b.size())) return i == a.size();
  return a < b;
}

void natural_sort(std::vector<std::filesystem::path>& files) {
  std::sort(files.begin(), files.end(),
            [](const std::filesystem::path& a, const std::filesystem::path& b) {
              return natural_less(a.filename().string(), b.filename().string());
            });
}

}  // namespace omninav::io
