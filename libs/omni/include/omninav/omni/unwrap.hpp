#pragma once
// Unwrapping raw omnidirectional images into panoramic cylinders, and the inverse.
//
// The unwrapping is the one of the papers: a line from the mirror's centre is swept round the
// raw image, one panorama column per direction, and pixels are taken along it at regular
// radii between an inner and an outer circle (Labrosse 2006, §3.1, Fig. 4;
// Labrosse 2004, §5). The mirror's profile is not modelled, so rows are linear in
// radius, not in elevation: the `panorama:` elevations of camera.yaml are only approximated.
//
// Raw image geometry (all in OpenCV pixel coordinates: x to the right, y down, the centre of
// pixel (column j, row i) at (j, i)):
//   - a direction in the raw image is the angle φ measured counter-clockwise AS SEEN ON THE
//     SCREEN from the image's "up" (−y) direction: φ = 0 up, 90° left, 180° down, 270° right.
//     The point at radius ρ and angle φ is (x, y) = (cx − ρ·sin φ, cy − ρ·cos φ).
//   - `front_offset` is the φ at which the robot's front lies (0: front at the top of the raw
//     image, as in Labrosse 2006, §3.1).
//   - flip = false: the raw image looks like a view of the robot from above: the robot's left
//     lies 90° counter-clockwise (on screen) from its front, i.e. φ = front_offset + azimuth.
//     flip = true: the raw image is the mirror image of that, the left lies 90° clockwise from
//     the front, φ = front_offset − azimuth. A camera looking up at a mirror (or a fisheye
//     looking up) sees the mirrored view, hence "right and left are inverted in
//     omni-directional images" (Labrosse 2006, §3.1): such cameras need flip = true unless their
//     firmware already mirrors the image.
//   (azimuth: relative to the robot, counter-clockwise from above, 0 ahead, +90° its left.)
//
// The panorama follows docs/design.md (omninav/core/panorama.hpp): column c looks along azimuth
// π/2 − 2π·c/W, front at 0.25·W, left at column 0. Row r samples the radius
//   ρ(r) = outer − (r + 0.5)·(outer − inner)/H   when outer_radius_at_top (row 0 near the rim),
//   ρ(r) = inner + (r + 0.5)·(outer − inner)/H   otherwise,
// i.e. row centres split the annulus into H equal rings.
//
// Rotations. When the robot turns counter-clockwise by δ, every azimuth decreases by δ, so the
// panorama content moves to higher columns by δ·W/2π (docs/design.md) and the raw-image content
// rotates by δ CLOCKWISE on screen when flip = false, COUNTER-CLOCKWISE when flip = true.
// Equivalently: rotating the raw image counter-clockwise (on screen) by k rolls the panorama by
//   −k·W/360 columns (flip = false)   or   +k·W/360 columns (flip = true).

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "omninav/core/panorama.hpp"
#include "omninav/omni/mirror.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::omni {

// How the centre and the radii of UnwrapParams are given.
enum class LengthUnits {
  kFraction,  // fractions of the raw image's WIDTH (x and y alike), as the data README gives them
  kPixels,    // pixels, in the coordinates described above
};

enum class Interpolation {
  kNearest,   // nearest raw pixel: the papers' "not smooth" unwrapping (Labrosse 2006, §3.1,
              // Labrosse 2004, §5)
  kBilinear,  // the four nearest raw pixels: the "smooth version" (Labrosse 2004, §5; Labrosse
              // 2006, footnote 2)
};

// The `unwrap:` section of camera.yaml (config/camera.yaml documents each key the same way).
// The PixPro camera of shared/data/README.md has, as fractions of the raw width: centre
// (0.50694, 0.51042), inner radius 0.09375, outer radius 0.49028.
struct UnwrapParams {
  LengthUnits units = LengthUnits::kFraction;  // of centre_x, centre_y, inner/outer_radius
  // Mirror centre, in `units`. Absent (both): detected in the first raw image by
  // find_mirror_circle (make_unwrapper). Give both or neither.
  std::optional<double> centre_x;
  std::optional<double> centre_y;
  // Radius of the inner circle (the robot and camera reflected in the mirror, excluded),
  // in `units`. Absent: inner_fraction_of_outer × the outer radius.
  std::optional<double> inner_radius;
  // Radius of the outer circle (the mirror's rim), in `units`. Absent: the radius of the
  // detected mirror (make_unwrapper).
  std::optional<double> outer_radius;
  // Inner radius as a fraction of the outer one when inner_radius is absent; 0.2 rounds the
  // PixPro's published 0.09375 / 0.49028 = 0.19 (shared/data/README.md).
  double inner_fraction_of_outer = 0.2;
  // Output size, pixels. Default: the panorama geometry's (camera.yaml `panorama:`, 360×45, one
  // column per degree as in Labrosse 2006, §3.1); unwrap_params_for() copies it from a
  // PanoramaGeometry.
  int width_px = PanoramaGeometry{}.width_px;
  int height_px = PanoramaGeometry{}.height_px;
  // Bilinear by default: as cheap as nearest with precomputed maps, and less aliased. The
  // papers found nearest no worse for the compass (Labrosse 2006, footnote 2); choose it to
  // reproduce them.
  Interpolation interpolation = Interpolation::kBilinear;
  // Mirror the raw image left/right (see the top of this file); Labrosse 2006, §3.1's camera needs
  // true.
  bool flip = false;
  // φ of the robot's front in the raw image, counter-clockwise on screen from "up", radians
  // (degrees in camera.yaml). 0: front at the top of the raw image, as in Labrosse 2006, §3.1.
  double front_offset_rad = 0.0;
  // Top panorama row at the outer radius: far and/or tall things at the top, as for a convex
  // mirror seen from below (Labrosse 2006, §3.1). A fisheye looking up sees the zenith at the
  // centre of the raw image: set false for it.
  bool outer_radius_at_top = true;

  // The ranges of camera.yaml's unwrap section (the lengths' by `units`) and their consistency
  // (both centre coordinates or neither, the inner radius below the outer). Throws UsageError
  // naming the key (core/param_check.hpp); the loader calls it, and make_unwrapper turns its
  // error into a ConfigError.
  void check() const;
};

// Default parameters with the output size of `geometry` (camera.yaml's `panorama:` section).
UnwrapParams unwrap_params_for(const PanoramaGeometry& geometry);

// Reads the `unwrap:` section of camera.yaml into `params` (keys: units, centre_x, centre_y,
// inner_radius, outer_radius, inner_fraction_of_outer, interpolation, flip, front_offset_deg,
// outer_radius_at_top). Absent keys keep `params`' values; the caller calls
// ConfigReader::require_all_known() once every section was read. Throws ConfigError on
// out-of-range values and on inconsistent ones (only one of centre_x/centre_y, inner radius
// not below the outer one).
void load_unwrap_params(const ConfigReader& section, UnwrapParams& params);

// The same parameters with every length converted to pixels of a raw image `raw_width_px`
// wide (absent values stay absent).
UnwrapParams in_pixels(const UnwrapParams& params, int raw_width_px);

// The annulus actually used, in pixels.
struct Annulus {
  cv::Point2d centre_px;
  double inner_radius_px = 0.0;
  double outer_radius_px = 0.0;
};

// Resolves `params` to pixels for a raw image of `raw_size`, taking what the params lack
// (centre, outer radius) from `detected`. Throws ConfigError when something is still missing
// or inconsistent (inner radius not below the outer one, zero or negative sizes, centre outside
// the image); logs a warning when the outer circle extends more than 2 px beyond the image
// (those panorama pixels are black; published parameters of real cameras often do by a pixel).
Annulus resolve_annulus(const UnwrapParams& params, cv::Size raw_size,
                        const std::optional<MirrorCircle>& detected = std::nullopt);

// Unwraps raw images of one size with maps computed once.
class Unwrapper {
 public:
  // `params` must give the centre and the outer radius (make_unwrapper detects them). Throws
  // ConfigError on bad parameters, InputError on an empty raw size.
  Unwrapper(const UnwrapParams& params, cv::Size raw_size);
  // With the annulus already resolved (resolve_annulus); the params' lengths are then unused.
  Unwrapper(const UnwrapParams& params, cv::Size raw_size, const Annulus& annulus);

  // The panorama of `raw` (any depth, 1 to 4 channels); raw pixels outside the image read as
  // black. Throws InputError when `raw` is empty or not of the size given at construction.
  cv::Mat unwrap(const cv::Mat& raw) const;

  const Annulus& annulus() const { return annulus_; }
  cv::Size raw_size() const { return raw_size_; }
  cv::Size panorama_size() const { return map_x_.size(); }

 private:
  UnwrapParams params_;
  cv::Size raw_size_;
  Annulus annulus_;
  cv::Mat map_x_;  // CV_32F, panorama-sized: raw x of each panorama pixel
  cv::Mat map_y_;
};

// Builds an Unwrapper for raw images like `first_raw`, detecting the mirror with
// find_mirror_circle when the params lack the centre or the outer radius. Logs what it found
// ("mirror found: centre (x, y) px, radius r px") and the annulus used. Throws InputError when
// detection is needed and finds no mirror, telling the user to set centre_x/centre_y (and
// outer_radius) in camera.yaml.
Unwrapper make_unwrapper(const UnwrapParams& params, const cv::Mat& first_raw);

// The inverse of Unwrapper: a raw omnidirectional image of `raw_size` whose unwrapping is
// `panorama` (its own size is used; params.width_px/height_px are ignored). Pixels outside the
// annulus are black. `params` must give the centre and the outer radius; the panorama is
// sampled with params.interpolation, wrapping round horizontally.
cv::Mat wrap_panorama(const cv::Mat& panorama, const UnwrapParams& params, cv::Size raw_size);

std::string to_string(LengthUnits units);
std::string to_string(Interpolation interpolation);

}  // namespace omninav::omni
