#include "omninav/omni/unwrap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::omni {
namespace {

// Beyond this many pixels outside the image, an annulus is worth a warning: published
// parameters of real cameras (the PixPro's of shared/data/README.md) overshoot by a pixel or two.
constexpr double kAnnulusOvershootWarningPx = 2.0;

// Raw pixels outside the annulus get this map value in wrap_panorama: far enough outside the
// padded panorama that both interpolation modes read the constant (black) border.
constexpr float kOutsideMap = -10.0F;

std::string format_px(double value) {
  return fixed(value, 1);
}

std::string size_text(cv::Size size) {
  return std::to_string(size.width) + "×" + std::to_string(size.height);
}

int cv_interpolation(Interpolation interpolation) {
  return interpolation == Interpolation::kNearest ? cv::INTER_NEAREST : cv::INTER_LINEAR;
}

// +1 when the raw image is a view from above (azimuth grows counter-clockwise on screen),
// −1 when it is mirrored.
double handedness(const UnwrapParams& params) {
  return params.flip ? -1.0 : 1.0;
}

// Radius sampled by panorama row `row` (fractional allowed) of a panorama `height_px` rows high.
double radius_of_row(double row, int height_px, const Annulus& annulus, bool outer_at_top) {
  const double ring_px = (annulus.outer_radius_px - annulus.inner_radius_px) / height_px;
  return outer_at_top ? annulus.outer_radius_px - (row + 0.5) * ring_px
                      : annulus.inner_radius_px + (row + 0.5) * ring_px;
}

double row_of_radius(double radius_px, int height_px, const Annulus& annulus, bool outer_at_top) {
  const double ring_px = (annulus.outer_radius_px - annulus.inner_radius_px) / height_px;
  return outer_at_top ? (annulus.outer_radius_px - radius_px) / ring_px - 0.5
                      : (radius_px - annulus.inner_radius_px) / ring_px - 0.5;
}

// φ (counter-clockwise on screen from "up") of the raw direction that panorama column `column`
// looks along.
double raw_angle_of_column(double column, int width_px, const UnwrapParams& params) {
  return params.front_offset_rad + handedness(params) * azimuth_of_column(column, width_px);
}

void check_output_size(int width_px, int height_px) {
  if (width_px < 1 || height_px < 1) {
    throw ConfigError("unwrap: the panorama size must be positive, got " +
                      std::to_string(width_px) + "×" + std::to_string(height_px) + " px");
  }
}

}  // namespace

std::string to_string(LengthUnits units) {
  return units == LengthUnits::kPixels ? "pixels" : "fraction";
}

std::string to_string(Interpolation interpolation) {
  return interpolation == Interpolation::kNearest ? "nearest" : "bilinear";
}

UnwrapParams unwrap_params_for(const PanoramaGeometry& geometry) {
  UnwrapParams params;
  params.width_px = geometry.width_px;
  params.height_px = geometry.height_px;
  return params;
}

void load_unwrap_params(const ConfigReader& section, UnwrapParams& params) {
  std::string units = to_string(params.units);
  section.read("units", units, {"fraction", "pixels"});
  params.units = units == "pixels" ? LengthUnits::kPixels : LengthUnits::kFraction;
  section.read("centre_x", params.centre_x);
  section.read("centre_y", params.centre_y);
  section.read("inner_radius", params.inner_radius);
  section.read("outer_radius", params.outer_radius);
  section.read("inner_fraction_of_outer", params.inner_fraction_of_outer);

  std::string interpolation = to_string(params.interpolation);
  section.read("interpolation", interpolation, {"nearest", "bilinear"});
  params.interpolation =
      interpolation == "nearest" ? Interpolation::kNearest : Interpolation::kBilinear;
  section.read("flip", params.flip);
  section.read_deg("front_offset_deg", params.front_offset_rad);
  section.read("outer_radius_at_top", params.outer_radius_at_top);
  check_loaded(section.source_name(), [&] { params.check(); });
}

void UnwrapParams::check() const {
  // Ranges depend on the unit. Fractions are of the raw width, so a portrait image's centre_y
  // may exceed 1; resolve_annulus checks the centre against the actual image.
  const bool fraction = units == LengthUnits::kFraction;
  const double max_centre = fraction ? 2.0 : 100000.0;
  const double max_radius = fraction ? 1.0 : 100000.0;
  const double min_outer = fraction ? 0.001 : 1.0;
  if (centre_x) check_range("unwrap.centre_x", *centre_x, 0.0, max_centre);
  if (centre_y) check_range("unwrap.centre_y", *centre_y, 0.0, max_centre);
  if (inner_radius) check_range("unwrap.inner_radius", *inner_radius, 0.0, max_radius);
  if (outer_radius) check_range("unwrap.outer_radius", *outer_radius, min_outer, max_radius);
  check_range("unwrap.inner_fraction_of_outer", inner_fraction_of_outer, 0.0, 0.95);
  check_range_deg("unwrap.front_offset_deg", front_offset_rad, -360.0, 360.0);
  if (centre_x.has_value() != centre_y.has_value()) {
    throw UsageError(
        "keys 'unwrap.centre_x' and 'unwrap.centre_y' go together: give both, or neither to "
        "detect the mirror");
  }
  if (inner_radius && outer_radius && *inner_radius >= *outer_radius) {
    throw UsageError("key 'unwrap.inner_radius' (" + general(*inner_radius) +
                     ") must be smaller than 'unwrap.outer_radius' (" + general(*outer_radius) +
                     ")");
  }
}

UnwrapParams in_pixels(const UnwrapParams& params, int raw_width_px) {
  UnwrapParams converted = params;
  if (params.units == LengthUnits::kPixels) return converted;
  const auto scale = [raw_width_px](const std::optional<double>& value) -> std::optional<double> {
    if (!value) return std::nullopt;
    return *value * raw_width_px;
  };
  converted.units = LengthUnits::kPixels;
  converted.centre_x = scale(params.centre_x);
  converted.centre_y = scale(params.centre_y);
  converted.inner_radius = scale(params.inner_radius);
  converted.outer_radius = scale(params.outer_radius);
  return converted;
}

Annulus resolve_annulus(const UnwrapParams& params, cv::Size raw_size,
                        const std::optional<MirrorCircle>& detected) {
  if (raw_size.width < 1 || raw_size.height < 1) {
    throw InputError("unwrap: the raw image is empty (" + size_text(raw_size) + ")");
  }
  check_output_size(params.width_px, params.height_px);
  const UnwrapParams pixels = in_pixels(params, raw_size.width);

  Annulus annulus;
  if (pixels.centre_x.has_value() != pixels.centre_y.has_value()) {
    throw ConfigError("unwrap: centre_x and centre_y go together: give both, or neither");
  }
  if (pixels.centre_x) {
    annulus.centre_px = {*pixels.centre_x, *pixels.centre_y};
  } else if (detected) {
    annulus.centre_px = detected->centre_px;
  } else {
    throw ConfigError(
        "unwrap: the mirror centre is not set: set centre_x and centre_y in the unwrap: "
        "section of camera.yaml, or let it be detected in the first raw image");
  }
  if (pixels.outer_radius) {
    annulus.outer_radius_px = *pixels.outer_radius;
  } else if (detected) {
    annulus.outer_radius_px = detected->radius_px;
  } else {
    throw ConfigError(
        "unwrap: the outer radius is not set: set outer_radius in the unwrap: section of "
        "camera.yaml, or let it be detected in the first raw image");
  }
  annulus.inner_radius_px = pixels.inner_radius
                                ? *pixels.inner_radius
                                : pixels.inner_fraction_of_outer * annulus.outer_radius_px;

  if (!(annulus.outer_radius_px > 0.0)) {
    throw ConfigError("unwrap: the outer radius must be positive, got " +
                      format_px(annulus.outer_radius_px) + " px");
  }
  if (!(annulus.inner_radius_px >= 0.0) || annulus.inner_radius_px >= annulus.outer_radius_px) {
    throw ConfigError("unwrap: the inner radius (" + format_px(annulus.inner_radius_px) +
                      " px) must be at least 0 and smaller than the outer radius (" +
                      format_px(annulus.outer_radius_px) + " px)");
  }
  const cv::Point2d centre = annulus.centre_px;
  if (centre.x < -0.5 || centre.y < -0.5 || centre.x > raw_size.width - 0.5 ||
      centre.y > raw_size.height - 0.5) {
    throw ConfigError("unwrap: the mirror centre (" + format_px(centre.x) + ", " +
                      format_px(centre.y) + ") px lies outside the " + size_text(raw_size) +
                      " raw image (centre_x and centre_y are in units of '" +
                      to_string(params.units) + "')");
  }
  // The image covers x in [−0.5, W − 0.5] (pixel edges); how far does the rim go beyond it?
  const double overshoot_px =
      std::max({annulus.outer_radius_px - (centre.x + 0.5),
                centre.x + annulus.outer_radius_px - (raw_size.width - 0.5),
                annulus.outer_radius_px - (centre.y + 0.5),
                centre.y + annulus.outer_radius_px - (raw_size.height - 0.5)});
  if (overshoot_px > kAnnulusOvershootWarningPx) {
    log_warning("unwrap: the outer circle (centre (" + format_px(centre.x) + ", " +
                format_px(centre.y) + ") px, radius " + format_px(annulus.outer_radius_px) +
                " px) extends " + format_px(overshoot_px) + " px beyond the " +
                size_text(raw_size) + " raw image; those panorama pixels will be black");
  }
  return annulus;
}

Unwrapper::Unwrapper(const UnwrapParams& params, cv::Size raw_size)
    : Unwrapper(params, raw_size, resolve_annulus(params, raw_size)) {}

Unwrapper::Unwrapper(const UnwrapParams& params, cv::Size raw_size, const Annulus& annulus)
    : params_(params), raw_size_(raw_size), annulus_(annulus) {
  if (raw_size.width < 1 || raw_size.height < 1) {
    throw InputError("unwrap: the raw image is empty (" + size_text(raw_size) + ")");
  }
  check_output_size(params.width_px, params.height_px);
  if (!(annulus.outer_radius_px > annulus.inner_radius_px) || annulus.inner_radius_px < 0.0) {
    throw ConfigError("unwrap: the inner radius (" + format_px(annulus.inner_radius_px) +
                      " px) must be at least 0 and smaller than the outer radius (" +
                      format_px(annulus.outer_radius_px) + " px)");
  }
  const int width = params.width_px;
  const int height = params.height_px;
  // Per column: the raw direction (sin φ, cos φ); per row: the radius. The map is their
  // product, (x, y) = (cx − ρ·sin φ, cy − ρ·cos φ).
  std::vector<double> sin_phi(width);
  std::vector<double> cos_phi(width);
  for (int column = 0; column < width; ++column) {
    const double phi = raw_angle_of_column(column, width, params);
    sin_phi[column] = std::sin(phi);
    cos_phi[column] = std::cos(phi);
  }
  map_x_.create(height, width, CV_32F);
  map_y_.create(height, width, CV_32F);
  for (int row = 0; row < height; ++row) {
    const double rho = radius_of_row(row, height, annulus_, params.outer_radius_at_top);
    auto* xs = map_x_.ptr<float>(row);
    auto* ys = map_y_.ptr<float>(row);
    for (int column = 0; column < width; ++column) {
      xs[column] = static_cast<float>(annulus_.centre_px.x - rho * sin_phi[column]);
      ys[column] = static_cast<float>(annulus_.centre_px.y - rho * cos_phi[column]);
    }
  }
}

cv::Mat Unwrapper::unwrap(const cv::Mat& raw) const {
  if (raw.empty()) throw InputError("unwrap: the raw image is empty");
  if (raw.size() != raw_size_) {
    throw InputError("unwrap: the raw image is " + size_text(raw.size()) +
                     " px but the unwrapper was set up for " + size_text(raw_size_) +
                     " px (all raw images of a sequence must have one size)");
  }
  cv::Mat panorama;
  cv::remap(raw, panorama, map_x_, map_y_, cv_interpolation(params_.interpolation),
            cv::BORDER_CONSTANT, cv::Scalar::all(0));
  return panorama;
}

Unwrapper make_unwrapper(const UnwrapParams& params, const cv::Mat& first_raw) {
  if (first_raw.empty()) throw InputError("unwrap: the first raw image is empty");
  check_loaded("unwrap", [&] { params.check(); });
  std::optional<MirrorCircle> detected;
  const bool needs_detection = !params.centre_x || !params.centre_y || !params.outer_radius;
  if (needs_detection) {
    detected = find_mirror_circle(first_raw);
    if (!detected) {
      throw InputError(
          "unwrap: no mirror (a bright disc on a darker surround) found in the " +
          size_text(first_raw.size()) +
          " raw image: set centre_x, centre_y and outer_radius in the unwrap: section of "
          "camera.yaml (or --centre-x, --centre-y, --outer)");
    }
    log_info("mirror found: centre (" + format_px(detected->centre_px.x) + ", " +
             format_px(detected->centre_px.y) + ") px, radius " + format_px(detected->radius_px) +
             " px");
  }
  const Annulus annulus = resolve_annulus(params, first_raw.size(), detected);
  log_info("unwrapping: centre (" + format_px(annulus.centre_px.x) + ", " +
           format_px(annulus.centre_px.y) + ") px, radii " + format_px(annulus.inner_radius_px) +
           " to " + format_px(annulus.outer_radius_px) + " px, panorama " +
           std::to_string(params.width_px) + "×" + std::to_string(params.height_px) + " px");
  return Unwrapper(params, first_raw.size(), annulus);
}

cv::Mat wrap_panorama(const cv::Mat& panorama, const UnwrapParams& params, cv::Size raw_size) {
  if (panorama.empty()) throw InputError("wrap_panorama: the panorama is empty");
  UnwrapParams sized = params;
  sized.width_px = panorama.cols;
  sized.height_px = panorama.rows;
  const Annulus annulus = resolve_annulus(sized, raw_size);
  const int width = panorama.cols;
  const int height = panorama.rows;

  // One extra row above and below (replicated: the annulus' edge rings sit half a row outside
  // the outermost row centres) and one column each side (wrapped round: the panorama is a
  // cylinder), so interpolation never reads a border.
  cv::Mat rows_padded;
  cv::Mat padded;
  cv::copyMakeBorder(panorama, rows_padded, 1, 1, 0, 0, cv::BORDER_REPLICATE);
  cv::copyMakeBorder(rows_padded, padded, 0, 0, 1, 1, cv::BORDER_WRAP);

  cv::Mat map_x(raw_size, CV_32F);
  cv::Mat map_y(raw_size, CV_32F);
  const double sign = handedness(sized);
  for (int y = 0; y < raw_size.height; ++y) {
    auto* xs = map_x.ptr<float>(y);
    auto* ys = map_y.ptr<float>(y);
    for (int x = 0; x < raw_size.width; ++x) {
      const double dx = x - annulus.centre_px.x;
      const double dy = y - annulus.centre_px.y;
      const double rho = std::hypot(dx, dy);
      if (rho < annulus.inner_radius_px || rho > annulus.outer_radius_px) {
        xs[x] = kOutsideMap;
        ys[x] = kOutsideMap;
        continue;
      }
      // Inverse of (x, y) = (cx − ρ·sin φ, cy − ρ·cos φ), then φ = offset + sign·azimuth.
      const double phi = std::atan2(-dx, -dy);
      const double azimuth = sign * (phi - sized.front_offset_rad);
      xs[x] = static_cast<float>(column_of_azimuth(azimuth, width) + 1.0);
      ys[x] =
          static_cast<float>(row_of_radius(rho, height, annulus, sized.outer_radius_at_top) + 1.0);
    }
  }
  cv::Mat raw;
  cv::remap(padded, raw, map_x, map_y, cv_interpolation(sized.interpolation), cv::BORDER_CONSTANT,
            cv::Scalar::all(0));
  return raw;
}

}  // namespace omninav::omni
