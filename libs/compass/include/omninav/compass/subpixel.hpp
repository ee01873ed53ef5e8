#pragma once
// The sub-pixel minimum of the distance function, Labrosse 2006, §3.4.2, Eqs. 7-12,
// from the pixel-resolution minimum d_0 = d(a_m) and its neighbours d_− = d(a_m − 1),
// d_+ = d(a_m + 1) (so d_0 ≤ d_−, d_+). Offsets are in columns, relative to a_m.
//
//   parabolic: the parabola through the three points, minimum at
//       δ̃ = (d_− − d_+) / (2·(d_− − 2·d_0 + d_+)),   d̃ = d_0 − (d_− − d_+)² / (8·(d_− − 2·d_0 +
//       d_+))
//   linear extrapolation (Fig. 9, left): the text calls the three lowest values d_m ≤ d_1 ≤ d_2;
//       our reading is a "V" of two lines of opposite slopes, the steeper one through d_0 and
//       the higher neighbour d_2 (slope s = d_2 − d_0), the other through the lower neighbour
//       d_1. They cross at
//       δ̂ = (d_− − d_+) / (2·s),   d̂ = d_0 − s·|δ̂|
//       (a sharp minimum, as between similar images, Fig. 6).
//   mixture (Eqs. 10-11): with the pixel-resolution normalised amplitude A_n (Eq. 9 over Eq. 8's
//       normaliser), parabolic when A_n ≤ 0.5, else p·linear + (1 − p)·parabolic with
//       p = (A_n − 0.5)/0.5. A_n can exceed 1 when the second image has more contrast than the
//       first; we clamp p to [0, 1] so the mixture never extrapolates beyond the linear fit.
// Degenerate shapes (a flat function) give offset 0 and value d_0. Offsets stay in [−0.5, 0.5].
// Distances are never negative: fitted values are clamped at 0, and d_0 = 0 (an exact match)
// is the minimum itself, offset 0.

#include <string>
#include <string_view>

namespace omninav::compass {

enum class SubpixelMode {
  kNone,       // the pixel-resolution minimum (Labrosse 2006, Eqs. 5-6)
  kParabolic,  // parabolic interpolation only
  kLinear,     // linear extrapolation only
  kMixture,    // Eqs. 10-11 (Table 2)
};

std::string to_string(SubpixelMode mode);
// "none", "parabolic", "linear", "mixture"; UsageError otherwise.
SubpixelMode subpixel_mode_of(std::string_view name);

struct SubpixelParams {
  SubpixelMode mode = SubpixelMode::kMixture;  // Table 2: "mixture of parabolic interpolation
                                               // and linear extrapolation"
  // Below this normalised amplitude the mixture is purely parabolic (0.5, Eqs. 10-11) ...
  double parabolic_up_to_norm_amp = 0.5;
  // ... and at this one purely linear (1.0: p = (A_n − 0.5)/0.5 reaches 1 at A_n = 1).
  double linear_from_norm_amp = 1.0;
};

struct SubpixelFit {
  double offset_px = 0.0;  // sub-pixel minimum relative to a_m, in [−0.5, 0.5]
  double value = 0.0;      // the distance there
};

SubpixelFit parabolic_fit(double d_minus, double d_0, double d_plus);
SubpixelFit linear_fit(double d_minus, double d_0, double d_plus);
// The weight p of the linear fit in the mixture for a normalised amplitude, in [0, 1].
double linear_weight(double amplitude_norm, const SubpixelParams& params);
// The fit `params.mode` asks for; amplitude_norm is only used by the mixture.
SubpixelFit subpixel_fit(double d_minus, double d_0, double d_plus, double amplitude_norm,
                         const SubpixelParams& params);

}  // namespace omninav::compass
