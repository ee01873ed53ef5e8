// Text for OpenCV's Hershey fonts (cv::putText), which draw ASCII only: the symbols omninav's
// labels use are spelled out, so a title reads "cap 4 deg", never "cap 4??".
#pragma once

#include <string>
#include <string_view>

namespace omninav::measures {

// `utf8` with ° ± σ × − – — ≤ ≥ → ← ′ ″ μ θ ψ α Δ as "deg", "+/-", "sigma", "x", "-", "-", "-",
// "<=", ">=", "->", "<-", "'", "\"", "u", "theta", "psi", "alpha", "d" (a degree sign after a
// number gets a space before it); any other non-ASCII character becomes "?".
std::string hershey_text(std::string_view utf8);

}  // namespace omninav::measures
