#pragma once
// Tilt between two panoramas, and levelling a panorama (docs/compass.md, "Tilt").
//
// A camera pitched p and rolled r (docs/design.md: positive pitch is nose down, positive roll is
// left side up) casts, through the pixel at azimuth φ (relative to the robot) and elevation e,
// the ray of the level camera's elevation e + δ(φ), to first order in the tilt:
//     δ(φ) = −p·cos φ + r·sin φ                       (independent of e)
// so, rows growing as the elevation falls, the tilted panorama is the level one with column φ
// moved down by δ(φ)/rad_per_row rows: the horizon becomes one period of a sinusoid across the
// columns (Labrosse 2006, §3.3.3 and §5 name tilt as one of the two causes of the
// compass's error, the other being parallax).
//
// The relative tilt of a second panorama against a first needs no horizon: it is the tilt that,
// undone on the second (level_panorama), makes it look as the first would from the second's
// heading. It is what the compass needs to compare a frame with its reference, and it works
// indoors, where no horizon is visible. Estimated in two steps:
//   1. blocks of columns (`blocks` of them round the circle) are averaged into one vertical
//      profile each (grey, the mean of the channels); the second's block is matched against
//      the first's by a 1-D search over whole row shifts within ±max_tilt_rad, then refined to
//      a fraction of a row by Gauss-Newton (Lucas-Kanade) steps on the linearly interpolated
//      profile; each block's weight is its profile's vertical-gradient energy;
//   2. δ_b = −shift_b·rad_per_row is fitted by δ(φ_b) = −p·cos φ_b + r·sin φ_b by weighted
//      least squares, re-weighted (Tukey's biweight) so that blocks where something moved, or
//      where parallax changed the profile, drop out.

#include <opencv2/core.hpp>

#include "omninav/compass/pair_matcher.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::compass {

struct TiltParams {
  int blocks = 36;                        // blocks of columns round the circle (4..W)
  double max_tilt_rad = deg_to_rad(8.0);  // searched row shifts: ±max_tilt / rad_per_row
  int refinement_steps = 3;               // Gauss-Newton steps per block after the search
  double outlier_rows = 1.5;              // Tukey biweight scale, rows: 4.685 × the robust
                                          // sigma (1.4826 × MAD) of the residuals, but at
                                          // least this
  int reweighting_steps = 4;              // iteratively re-weighted least-squares steps
};

struct TiltEstimate {
  double pitch_rad = 0.0;  // of the second panorama relative to the first, in its own frame
  double roll_rad = 0.0;
  double residual_rows = 0.0;  // weighted RMS of the block shifts about the fitted sinusoid
  int blocks_used = 0;         // blocks with a profile and a weight left after re-weighting
};

// The tilt of `second` relative to `first`. `second_shift_px` is the column shift that aligns
// the second on the first (the pair matcher's α_m, PairMatch::subpixel_shift_px: rolling the
// second by it turns it onto the first); only its nearest whole column is used to pair the
// blocks, the azimuths of the sinusoid use it exactly. Both images 8-bit, 1 or 3 channels, of
// the same size, laid out as `geometry` says (its width and height must match them). Throws
// InputError for bad or mismatched images, UsageError for bad params.
TiltEstimate estimate_relative_tilt(const cv::Mat& first, const cv::Mat& second,
                                    const PanoramaGeometry& geometry, double second_shift_px,
                                    const TiltParams& params = {});

// The panorama a camera at the same place and heading but with its tilt reduced by (pitch_rad,
// roll_rad) would see: exact, by the rotation of the unit sphere (Ry(pitch)·Rx(roll) as the
// renderer draws it), bilinear; rows that would come from outside the panorama's elevation band
// repeat its first or last row. level_panorama(tilted, g, p, r) of a panorama rendered with
// pitch p and roll r is the level one.
cv::Mat level_panorama(const cv::Mat& panorama, const PanoramaGeometry& geometry, double pitch_rad,
                       double roll_rad);

// The turn and the tilt of a pair together. The tilt is estimated at the turn the matcher
// finds, the second is levelled by it, and the levelled second is matched again (starting at
// the previous shift); `rounds` times. A tilt of a few degrees can move the unlevelled match
// far off (a 26 degree error in the field at 10 cm, docs/compass.md "Tilt"); the second round
// re-estimates the tilt at the corrected turn. Throws as estimate_relative_tilt and
// PairMatcher::match, and UsageError for rounds < 1.
struct TurnAndTilt {
  PairMatch match;    // of the levelled second against the first
  TiltEstimate tilt;  // of the second relative to the first
  cv::Mat levelled;   // the second, levelled by `tilt`
};
TurnAndTilt match_levelled(const PairMatcher& matcher, const cv::Mat& first, const cv::Mat& second,
                           const PanoramaGeometry& geometry, const TiltParams& params = {},
                           int rounds = 2);

}  // namespace omninav::compass
