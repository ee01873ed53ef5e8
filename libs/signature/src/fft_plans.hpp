#pragma once
// The signature library's names for the process-wide FFTW plan cache of libs/core
// (omninav/core/fftw_plans.hpp): plans made once per shape under one mutex, shared with every
// other user of FFTW in the process.

#include "omninav/core/fftw_plans.hpp"

namespace omninav::signature::detail {

// A buffer from FFTW's allocator (fftwf_malloc for float and fftwf_complex).
template <typename T>
using FftwBuffer = fftw::Buffer<T>;

// The plan of `lines` real transforms of length `width`, input lines × width floats, output
// lines × (width/2 + 1) complex values, both contiguous and line after line. FFTW_ESTIMATE: the
// plan depends on the sizes only, never on timing, so the same input gives bit-identical
// signatures in every run (DESIGN.md, Determinism).
inline fftwf_plan rows_r2c_plan(int width, int lines) {
  return fftw::lines_r2c_float({width, lines, 0, fftw::Planning::kEstimate});
}

}  // namespace omninav::signature::detail
