#pragma once
// Numbers as text, the one formatter of the project (through libfmt: GCC 12 has no
// std::format). Every table, message and report formats its numbers here, so that the same
// value reads the same everywhere.

#include <optional>
#include <string>

namespace omninav {

// `decimals` digits after the point, rounded ("%.*f"): fixed(2.345, 1) = "2.3".
std::string fixed(double value, int decimals);
// The same with a sign always: "+2.3", "-0.5".
std::string signed_fixed(double value, int decimals);
// fixed(), or "" for a missing value (an empty CSV field).
std::string fixed_or_empty(const std::optional<double>& value, int decimals);
// fixed() without the trailing zeros of the fraction (and its point), "-0" read as "0":
// trimmed(1.2, 3) = "1.2", trimmed(2.0, 3) = "2".
std::string trimmed(double value, int decimals);
// `significant` significant digits, in the shorter of fixed and exponent notation ("%.*g"):
// general(0.5) = "0.5", general(1e-7) = "1e-07".
std::string general(double value, int significant = 6);
// The shortest text that reads back to exactly `value`.
std::string shortest(double value);

// `value` rounded to `decimals` digits after the point, as the double nearest to fixed()'s
// text: what a JSON writer prints as that text without its trailing zeros.
double rounded(double value, int decimals);

}  // namespace omninav
