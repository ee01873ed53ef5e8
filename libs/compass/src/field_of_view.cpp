#include "omninav/compass/field_of_view.hpp"

#include <algorithm>
#include <cmath>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass {

ColumnMask::ColumnMask(int width_px, std::vector<std::uint8_t> selected)
    : width_px_(width_px), selected_(std::move(selected)) {
  // FNV-1a over the selection: equal masks, equal keys.
  std::uint64_t hash = 1469598103934665603ULL ^ static_cast<std::uint64_t>(width_px);
  for (int c = 0; c < width_px_; ++c) {
    const bool on = selected_[static_cast<std::size_t>(c)] != 0;
    hash = (hash ^ (on ? 1U : 2U)) * 1099511628211ULL;
    if (!on) continue;
    ++selected_count_;
    if (!runs_.empty() && runs_.back().second == c) {
      runs_.back().second = c + 1;
    } else {
      runs_.emplace_back(c, c + 1);
    }
  }
  key_ = hash;
}

ColumnMask ColumnMask::whole(int width_px) {
  if (width_px < 1) throw UsageError("a column mask needs a width of at least 1 column");
  return ColumnMask(width_px, std::vector<std::uint8_t>(static_cast<std::size_t>(width_px), 1));
}

ColumnMask ColumnMask::front_back(int width_px, double band_width_rad) {
  if (width_px < 1) throw UsageError("a column mask needs a width of at least 1 column");
  if (!(band_width_rad > 0.0)) {
    throw UsageError("the field of view's band width must be positive");
  }
  if (band_width_rad >= kPi) return whole(width_px);
  // A column is in a band when its centre looks within f/2 of the front (column 0.25·W) or the
  // back (0.75·W), boundary included; the tolerance keeps exact boundaries (30° at W = 360)
  // from depending on rounding.
  const double half_width_px = band_width_rad * width_px / (2.0 * kTwoPi);
  const double tolerance = 1e-9 * width_px;
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(width_px), 0);
  for (int c = 0; c < width_px; ++c) {
    for (const double centre : {0.25 * width_px, 0.75 * width_px}) {
      double offset = std::fmod(std::abs(c - centre), static_cast<double>(width_px));
      offset = std::min(offset, width_px - offset);
      if (offset <= half_width_px + tolerance) selected[static_cast<std::size_t>(c)] = 1;
    }
  }
  return ColumnMask(width_px, std::move(selected));
}

ColumnMask ColumnMask::from_params(int width_px, const FieldOfViewParams& params) {
  return params.front_back ? front_back(width_px, params.band_width_rad) : whole(width_px);
}

}  // namespace omninav::compass
