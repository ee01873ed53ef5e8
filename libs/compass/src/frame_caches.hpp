#pragma once
// What a CompassFrame caches about itself (frame.hpp). Private to libs/compass.

#include <complex>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <vector>

namespace omninav::compass::detail {

struct FirstSpectra;
struct SecondSpectra;

struct FrameCaches {
  // The image column-major (cv::transpose: row c holds column c's H·channels bytes), for the
  // fast distance kernel: a band of mask columns is then one contiguous run of bytes.
  std::once_flag columns_once;
  cv::Mat columns;

  std::mutex mutex;  // guards everything below
  std::shared_ptr<const FirstSpectra> first;
  std::map<std::uint64_t, std::shared_ptr<const SecondSpectra>> second;  // by ColumnMask::key
  std::map<std::uint64_t, double> self_amplitude;  // by distance function (metric and mask)
  std::map<std::uint64_t, double> self_step;       // d(I, I, 1 px), by distance function
  // Components 1..K of every line's spectrum (line r·C + ch, K values each), by K, for the
  // phase estimate (phase.cpp).
  std::map<int, std::shared_ptr<const std::vector<std::complex<double>>>> low_frequencies;
  // Q(c) = Σ_rows,channels I(c)², exact in doubles (below 2⁵³), for the FFT's constant terms.
  std::vector<double> column_energy;
};

}  // namespace omninav::compass::detail
