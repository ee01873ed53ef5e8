// The rows of a CSV text a writer produced, each split at commas (for writers that quote
// nothing).
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "omninav/core/parse.hpp"

namespace omninav::testing {

inline std::vector<std::vector<std::string>> csv_text_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) rows.push_back(split(line, ','));
  return rows;
}

}  // namespace omninav::testing
