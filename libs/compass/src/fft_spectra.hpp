#pragma once
// FFTW plans and the per-frame line spectra of the masked cross-correlation
// (fft_correlation.cpp). Private to libs/compass.
//
// Single precision, two real lines per complex transform. A complex FFT of z = a + i·b yields
// the correlation of two real lines with two others in its real part, with no unpacking
// (fft_correlation.cpp), and FFTW's single-precision complex transforms are the fastest way
// it has of transforming 405 lines of 1080 points (~2× faster than its double-precision real
// transforms, measured: docs/compass.md, Performance). The costs are then estimates within a
// stated bound; fft_correlation.cpp makes the minimum exact.

#include <fftw3.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "omninav/compass/field_of_view.hpp"
#include "omninav/compass/frame.hpp"
#include "omninav/compass/minimiser.hpp"
#include "omninav/core/fftw_plans.hpp"

namespace omninav::compass::detail {

// A buffer from FFTW's allocator (SIMD-aligned, as every array a plan runs on must be).
template <typename T>
using FftwBuffer = fftw::Buffer<T>;

// Lines are transformed kBlockRows image rows at a time through a small buffer that stays in
// cache, rather than converting a whole frame first (at 1080×135 RGB that would stream the
// frame through memory twice per transform). A block holds whole pairs of rows: complex line
// j·C + ch of a block is channel ch of its rows 2j (real part) and 2j + 1 (imaginary part).
constexpr int kBlockRows = 8;
static_assert(kBlockRows % 2 == 0, "a block holds whole pairs of rows");

// The plans for panoramas `width` wide, from the process-wide cache of libs/core
// (fftw_plans.hpp: made once per shape under its mutex, kept until exit; executing them on other
// FftwBuffer arrays is thread-safe).
//
// One real line forward and back, double precision (the column energy, the mask, the one inverse
// transform of a pair, the phase). They take ~1 % of a pair; FFTW_MEASURE would spend ~1.5 s
// planning them at 1080 columns (measured), so they are always estimated.
struct LinePlans {
  int bins = 0;             // width/2 + 1
  fftw_plan r2c = nullptr;  // FFTW's forward transform
  fftw_plan c2r = nullptr;  // back, unnormalised: × width
};
LinePlans line_plans(int width);

// The block of complex lines of frames of `channels` channels, single precision, planned as
// `planning` says (compass.yaml's fft_planning).
struct BlockPlan {
  int width = 0;
  int channels = 0;
  int stride = 0;  // width rounded up to 8 complex values (64 bytes)
  int lines = 0;   // kBlockRows/2 × channels
  fftwf_plan forward = nullptr;
};
BlockPlan block_plan(int width, int channels, FftPlanning planning);

// The spectra of a frame's complex lines (pairs of rows, per channel, as above), `stride`
// apart. Only `lines` = ⌈rows/2⌉·channels of them hold data; an odd last row is paired with
// zeros.
//
// Their buffers (1.7 MB per role at 1080×135 RGB) come from a small pool and go back to it when
// the frame's caches let go of them: a sequence allocates a few once, instead of mapping and
// page-faulting fresh memory for every frame (which cost ~10 % of a pair at 1080×135).
struct LineSpectra {
  LineSpectra() = default;
  ~LineSpectra();
  LineSpectra(LineSpectra&&) noexcept = default;
  LineSpectra& operator=(LineSpectra&&) noexcept;

  int stride = 0;
  int lines = 0;
  FftwBuffer<fftwf_complex> data;  // whole blocks of lines × stride
  const fftwf_complex* line(int index) const {
    return data.data() + static_cast<std::size_t>(index) * stride;
  }
};

// A frame's spectra as the FIRST image of a pair (I_i, unmasked): its lines' spectra, and the
// spectrum of its column energy Q(c) = Σ_rows,channels I(c)² (double precision: bins values).
struct FirstSpectra {
  LineSpectra rows;
  FftwBuffer<fftw_complex> column_energy;
};

// A frame's spectra as the SECOND image (I_j), masked by the field of view that moves with it:
// the spectra of m·I_j's lines, and Σ m·I_j², the constant term of d².
struct SecondSpectra {
  std::shared_ptr<const FirstSpectra> unmasked;  // set instead of `masked` for the whole mask
  LineSpectra masked;
  double masked_energy = 0.0;
  const LineSpectra& rows() const { return unmasked ? unmasked->rows : masked; }
};

// The spectra of a pair (the first role of `first`, the second role of `second` for `mask`),
// each computed at most once per frame (per mask for the second role) and cached in the frame.
// `consume(first_rows, second_rows, begin, end)` is called for consecutive ranges of lines that
// together cover every line once, in order, each as soon as both spectra hold it: transforms
// that are made here run in step, block by block, so that a sum over lines reads each block
// while it is still in cache instead of streaming both frames' spectra back from memory.
struct PairSpectra {
  std::shared_ptr<const FirstSpectra> first;
  std::shared_ptr<const SecondSpectra> second;
};
PairSpectra pair_spectra(
    const CompassFrame& first, const CompassFrame& second, const ColumnMask& mask,
    FftPlanning planning,
    const std::function<void(const LineSpectra&, const LineSpectra&, int, int)>& consume);

// Minimiser (c) on a table (fft_correlation.cpp).
ShiftSearch fft_minimise(CostTable& table, FftPlanning planning);

}  // namespace omninav::compass::detail
