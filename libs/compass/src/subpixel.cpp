#include "omninav/compass/subpixel.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/errors.hpp"

namespace omninav::compass {

std::string to_string(SubpixelMode mode) {
  switch (mode) {
    case SubpixelMode::kNone:
      return "none";
    case SubpixelMode::kParabolic:
      return "parabolic";
    case SubpixelMode::kLinear:
      return "linear";
    case SubpixelMode::kMixture:
      return "mixture";
  }
  return "?";
}

SubpixelMode subpixel_mode_of(std::string_view name) {
  if (name == "none") return SubpixelMode::kNone;
  if (name == "parabolic") return SubpixelMode::kParabolic;
  if (name == "linear") return SubpixelMode::kLinear;
  if (name == "mixture") return SubpixelMode::kMixture;
  throw UsageError("unknown sub-pixel mode '" + std::string(name) +
                   "': expected none, parabolic, linear or mixture");
}

SubpixelFit parabolic_fit(double d_minus, double d_0, double d_plus) {
  const double curvature = d_minus - 2.0 * d_0 + d_plus;
  if (!(curvature > 0.0)) return {0.0, d_0};  // flat (or not a minimum): stay on the pixel
  const double offset = std::clamp((d_minus - d_plus) / (2.0 * curvature), -0.5, 0.5);
  // The parabola's value at its vertex: d_0 − (d_− − d_+)²/(8·curvature), i.e. d_0 − c·δ²/2.
  return {offset, std::max(0.0, d_0 - 0.5 * curvature * offset * offset)};
}

SubpixelFit linear_fit(double d_minus, double d_0, double d_plus) {
  // The steeper line goes through d_0 and the higher neighbour d_2; the other, of opposite
  // slope, through the lower neighbour d_1 (Fig. 9, left).
  const double slope = std::max(d_minus, d_plus) - d_0;
  if (!(slope > 0.0)) return {0.0, d_0};
  const double offset = std::clamp((d_minus - d_plus) / (2.0 * slope), -0.5, 0.5);
  return {offset, std::max(0.0, d_0 - slope * std::abs(offset))};
}

double linear_weight(double amplitude_norm, const SubpixelParams& params) {
  const double span = params.linear_from_norm_amp - params.parabolic_up_to_norm_amp;
  if (!(span > 0.0)) return amplitude_norm > params.parabolic_up_to_norm_amp ? 1.0 : 0.0;
  const double p = (amplitude_norm - params.parabolic_up_to_norm_amp) / span;
  return std::isfinite(p) ? std::clamp(p, 0.0, 1.0) : 0.0;
}

SubpixelFit subpixel_fit(double d_minus, double d_0, double d_plus, double amplitude_norm,
                         const SubpixelParams& params) {
  // A distance of 0 is an exact match: the minimum is the pixel itself. (Without this rule an
  // asymmetric "V" — the two sides of a masked self-comparison differ — would put the minimum
  // off the pixel and extrapolate a negative distance.)
  if (!(d_0 > 0.0)) return {0.0, 0.0};
  switch (params.mode) {
    case SubpixelMode::kNone:
      return {0.0, d_0};
    case SubpixelMode::kParabolic:
      return parabolic_fit(d_minus, d_0, d_plus);
    case SubpixelMode::kLinear:
      return linear_fit(d_minus, d_0, d_plus);
    case SubpixelMode::kMixture:
      break;
  }
  // Eqs. 10-11.
  const SubpixelFit parabolic = parabolic_fit(d_minus, d_0, d_plus);
  const double p = linear_weight(amplitude_norm, params);
  if (p <= 0.0) return parabolic;
  const SubpixelFit linear = linear_fit(d_minus, d_0, d_plus);
  return {p * linear.offset_px + (1.0 - p) * parabolic.offset_px,
          p * linear.value + (1.0 - p) * parabolic.value};
}

}  // namespace omninav::compass
