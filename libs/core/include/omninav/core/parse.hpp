#pragma once
// Parsing numbers out of text files and command lines with errors that say where.

#include <string>
#include <string_view>
#include <vector>

#include "omninav/core/pose.hpp"

namespace omninav {

// Parses the whole of `text` (surrounding blanks allowed) as a finite number; otherwise throws
// InputError "<where>: '<text>' is not a number".
double parse_double(std::string_view text, const std::string& where);
int parse_int(std::string_view text, const std::string& where);
// The same for a value on the command line: a bad one is a UsageError (exit status 2), whichever
// option or spec it came in.
double parse_double_argument(std::string_view text, const std::string& where);
int parse_int_argument(std::string_view text, const std::string& where);

// Returns `value_m` when it is finite and within ±kMaxCoordinateM; otherwise throws InputError
// "<where>: <value> m is not a position (beyond ±1e+07 m)", or "(not a finite number)".
double check_coordinate_m(double value_m, const std::string& where);

// `pose` when each of x, y, z passes check_coordinate_m and its angles are finite; otherwise
// InputError "<where>: x: 1e+300 m is not a position (beyond ±1e+07 m)", "<where>: heading is
// not a finite angle". The one bound of every pose omninav takes in: bags' pose topics, CSV and
// BoB files (through check_coordinate_m), poses given from Python, places added to a memory.
const CameraPose& check_pose(const CameraPose& pose, const std::string& where);

// Removes leading and trailing blanks (spaces, tabs, CR, LF).
std::string_view trim(std::string_view text);

// Splits on `separator`, keeping empty fields, each trimmed.
std::vector<std::string> split(std::string_view text, char separator);

}  // namespace omninav
