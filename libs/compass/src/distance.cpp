#include "omninav/compass/distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "omninav/core/errors.hpp"

namespace omninav::compass {
namespace {

// Σ (a_i − b_i)² or Σ |a_i − b_i| over n bytes. Partial sums stay in 32 bits, which the
// compiler vectorises well: 32768 squared differences of at most 255² = 65025 stay below 2³².
// On x86-64 the function is compiled for AVX-512, AVX2 and the baseline and the best one the
// processor has is picked when the program loads (integer sums: every version gives the same).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define OMNINAV_KERNEL_CLONES \
  __attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#else
#define OMNINAV_KERNEL_CLONES
#endif

template <Metric kMetric>
Cost run_cost_impl(const std::uint8_t* a, const std::uint8_t* b, std::size_t n) {
  constexpr std::size_t kChunk = 32768;
  Cost total = 0;
  while (n > 0) {
    const std::size_t chunk = std::min(n, kChunk);
    std::uint32_t partial = 0;
    for (std::size_t i = 0; i < chunk; ++i) {
      const int difference = static_cast<int>(a[i]) - static_cast<int>(b[i]);
      if constexpr (kMetric == Metric::kL2) {
        partial += static_cast<std::uint32_t>(difference * difference);
      } else {
        partial += static_cast<std::uint32_t>(difference < 0 ? -difference : difference);
      }
    }
    total += partial;
    a += chunk;
    b += chunk;
    n -= chunk;
  }
  return total;
}

OMNINAV_KERNEL_CLONES Cost run_cost_l2(const std::uint8_t* a, const std::uint8_t* b,
                                       std::size_t n) {
  return run_cost_impl<Metric::kL2>(a, b, n);
}

OMNINAV_KERNEL_CLONES Cost run_cost_l1(const std::uint8_t* a, const std::uint8_t* b,
                                       std::size_t n) {
  return run_cost_impl<Metric::kL1>(a, b, n);
}

// The fast kernels. Eq. 2 written over the second image's columns (field_of_view.hpp): column k
// of the second image is compared with column k + α of the first, so each run [begin, end) of
// mask columns is one contiguous run of bytes in both images, split in two where it wraps
// round, in any layout where a column's bytes are `column_bytes` contiguous bytes: the frames'
// column-major copies (one run per band: H·C bytes per column) or one row of each frame (C
// bytes per column).
template <Metric kMetric>
Cost shifted_cost(const std::uint8_t* first, const std::uint8_t* second, std::size_t column_bytes,
                  const ColumnMask& mask, int shift_px) {
  const int width = mask.width_px();
  const int shift = wrap_shift(shift_px, width);
  const auto run_cost = kMetric == Metric::kL2 ? run_cost_l2 : run_cost_l1;
  Cost total = 0;
  for (const auto& [begin, end] : mask.runs()) {
    const int start = wrap_shift(begin + shift, width);
    const int length = end - begin;
    const int before_wrap = std::min(length, width - start);
    total += run_cost(second + begin * column_bytes, first + start * column_bytes,
                      static_cast<std::size_t>(before_wrap) * column_bytes);
    if (before_wrap < length) {
      total += run_cost(second + (begin + before_wrap) * column_bytes, first,
                        static_cast<std::size_t>(length - before_wrap) * column_bytes);
    }
  }
  return total;
}

template <Metric kMetric>
Cost shifted_cost_on_columns(const CompassFrame& first, const CompassFrame& second,
                             const ColumnMask& mask, int shift_px) {
  const std::size_t column_bytes =
      static_cast<std::size_t>(first.height()) * static_cast<std::size_t>(first.channels());
  return shifted_cost<kMetric>(first.column_major(), second.column_major(), column_bytes, mask,
                               shift_px);
}

template <Metric kMetric>
Cost shifted_cost_on_rows(const CompassFrame& first, const CompassFrame& second,
                          const ColumnMask& mask, int shift_px) {
  const std::size_t column_bytes = static_cast<std::size_t>(first.channels());
  Cost total = 0;
  for (int r = 0; r < first.height(); ++r) {
    total += shifted_cost<kMetric>(first.row(r), second.row(r), column_bytes, mask, shift_px);
  }
  return total;
}

}  // namespace

std::string to_string(Metric metric) {
  return metric == Metric::kL2 ? "l2" : "l1";
}

double distance_of_cost(Cost cost, Metric metric) {
  return metric == Metric::kL2 ? std::sqrt(static_cast<double>(cost)) : static_cast<double>(cost);
}

DistanceFunction::DistanceFunction(Metric metric, ColumnMask mask)
    : metric_(metric), mask_(std::move(mask)) {}

DistanceFunction::DistanceFunction(const DistanceParams& params, int width_px)
    : DistanceFunction(params.metric, ColumnMask::from_params(width_px, params.field_of_view)) {}

void DistanceFunction::check(const CompassFrame& first, const CompassFrame& second) const {
  require_same_shape(first, second);
  if (first.width() != width_px()) {
    throw InputError(first.source() + ": a panorama " + std::to_string(first.width()) +
                     " columns wide given to a distance function for " +
                     std::to_string(width_px()) + " columns");
  }
}

Cost DistanceFunction::cost(const CompassFrame& first, const CompassFrame& second,
                            int shift_px) const {
  check(first, second);
  return metric_ == Metric::kL2
             ? shifted_cost_on_columns<Metric::kL2>(first, second, mask_, shift_px)
             : shifted_cost_on_columns<Metric::kL1>(first, second, mask_, shift_px);
}

Cost DistanceFunction::cost_on_rows(const CompassFrame& first, const CompassFrame& second,
                                    int shift_px) const {
  check(first, second);
  return metric_ == Metric::kL2 ? shifted_cost_on_rows<Metric::kL2>(first, second, mask_, shift_px)
                                : shifted_cost_on_rows<Metric::kL1>(first, second, mask_, shift_px);
}

Cost DistanceFunction::reference_cost(const CompassFrame& first, const CompassFrame& second,
                                      int shift_px) const {
  check(first, second);
  // Eq. 2 as written: the second image shifted by α, so its column c − α sits on the first
  // image's column c, and the mask travels with it (m(c − α)).
  const int width = first.width();
  const int channels = first.channels();
  Cost total = 0;
  for (int r = 0; r < first.height(); ++r) {
    const std::uint8_t* first_row = first.row(r);
    const std::uint8_t* second_row = second.row(r);
    for (int c = 0; c < width; ++c) {
      const int source_column = wrap_shift(c - shift_px, width);
      if (!mask_.selected(source_column)) continue;
      for (int l = 0; l < channels; ++l) {
        const Cost difference = static_cast<Cost>(second_row[source_column * channels + l]) -
                                static_cast<Cost>(first_row[c * channels + l]);
        total += metric_ == Metric::kL2 ? difference * difference
                                        : (difference < 0 ? -difference : difference);
      }
    }
  }
  return total;
}

std::int64_t DistanceFunction::compared_components(const CompassFrame& frame) const {
  return static_cast<std::int64_t>(frame.height()) * frame.channels() * mask_.selected_count();
}

double DistanceFunction::distance_of_mean_difference(double grey_levels,
                                                     const CompassFrame& frame) const {
  const double components = static_cast<double>(compared_components(frame));
  return metric_ == Metric::kL2 ? grey_levels * std::sqrt(components) : grey_levels * components;
}

}  // namespace omninav::compass
