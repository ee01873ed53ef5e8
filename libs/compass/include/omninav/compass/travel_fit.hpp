#pragma once
// The turn between two panoramas fitted together with the parallax of a displacement (ours,
// after the warping methods: Franz, Schölkopf, Mallot, Bülthoff 1998; Möller's min-warping).
//
// A pair taken at two poses differs by a turn and a displacement. Seen from the first pose, a
// point at column angle θ = 2πc/W moves by a small angle proportional to sin(θ − φ) when the
// camera moves towards φ (away from the focus of expansion, towards the focus of contraction),
// scaled by the displacement over the point's distance. With every distance taken equal, the
// second image is the first warped by a shift that varies with the column:
//     I_1(c) ≈ I_2(c − u(c)),   u(c) = α + a·sin θ_c + b·cos θ_c                (columns)
// α is Eq. 2's shift (the turn ρ = −α·2π/W, Eq. 4) and (a, b) the parallax. Fitting α alone
// with the masked bands of §3.4.3 biases it by the parallax (docs/compass.md, "The rotation
// cap"): the expansion inside the bands is lopsided when they sit off the direction of travel.
// Fitting α, a and b together lets the sinusoid take the expansion.
//
// The fit: Gauss-Newton from the pair's sub-pixel minimum (PairMatch::subpixel_shift_px), on
// the columns of the mask (the bands, where the equal-distance sinusoid fits best: off them
// the nearest objects dominate), the second image interpolated linearly between columns, its
// gradient by central differences. Rows are sampled so that ~45 are used (camera.yaml's
// 360×45 has every row; 1080×135 every third). It keeps the iterate with the smallest sum of
// squared differences, the start included, and falls back on the start when the fit moves α by
// more than max_correction_rad: the sinusoid never replaces the search, only refines its minimum.

#include <opencv2/core.hpp>

#include "omninav/compass/field_of_view.hpp"

namespace omninav::compass {

struct TravelFitParams {
  int iterations = 5;  // Gauss-Newton steps
  int rows_used = 45;  // rows sampled evenly (all when the image has fewer)
  bool whole = false;  // every column; false: the compass's bands only (measured better on
                       // the zoo's routes, docs/compass.md)
  // The fit may move α by at most this, radians, else the start stands (the sinusoid refines
  // the search's minimum, never replaces it).
  double max_correction_rad = 2.0 * 3.14159265358979323846 / 180.0;
};

struct TravelFit {
  double shift_px = 0.0;         // α, refined (the start when the fit did not improve it)
  double parallax_sin_px = 0.0;  // a
  double parallax_cos_px = 0.0;  // b
  bool improved = false;         // the fit lowered the sum of squared differences
};

// Fits α, a, b for the pair (first, second) from `start_shift_px`, over the columns `mask`
// selects. Images of one shape, 8-bit, any number of channels.
TravelFit fit_turn_and_travel(const cv::Mat& first, const cv::Mat& second, const ColumnMask& mask,
                              double start_shift_px, const TravelFitParams& params = {});

}  // namespace omninav::compass
