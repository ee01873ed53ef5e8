#pragma once
// FFTW plans and the per-frame row spectra of the masked cross-correlation (fft_minimiser.cpp)
// and the phase estimator (phase.cpp). Private to libs/compass.
//
// Double precision on purpose: the costs the FFT yields are rounded to the integers they
// approximate (fft_minimiser.cpp), which needs an absolute error well below 0.5 on values up to
// ~3·10¹⁰ (1080×135 RGB); double's ~10⁻¹⁶ relative error gives ~10⁻⁵.

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

// The plans for panoramas `width` wide, from the process-wide cache of libs/core
// (fftw_plans.hpp: made once per shape under its mutex, kept until exit; executing them on other
// FftwBuffer arrays is thread-safe).
//
// Lines are transformed kBlockRows image rows (kBlockRows × channels lines) at a time through
// a small buffer that stays in cache, rather than converting a whole frame to doubles first (at
// 1080×135 RGB that would stream 3.5 MB through memory twice per transform); a block holds whole
// rows, so one pass over a row's interleaved pixels fills its lines. Spectra rows are `stride` =
// bins rounded up to a multiple of 4 complex values (64 bytes) apart, so that every block's
// output starts with the alignment the plan was made with.
constexpr int kBlockRows = 8;

struct FftPlans {
  int width = 0;
  int bins = 0;                   // width/2 + 1
  int stride = 0;                 // bins rounded up to a multiple of 4
  fftw_plan one_r2c = nullptr;    // one line
  fftw_plan one_c2r = nullptr;    // one spectrum back (unnormalised: × width)
  int block_lines = 0;            // kBlockRows × channels (0 when asked for without channels)
  fftw_plan block_r2c = nullptr;  // block_lines lines, `width` apart → rows `stride` apart
};
// The one-line plans, and the block plan for frames of `channels` channels when channels > 0.
FftPlans fft_plans(int width, FftPlanning planning, int channels = 0);

// Row spectra of a frame's lines (rows × channels; line r·C + ch is channel ch of row r, so
// that one pass over a row of interleaved pixels fills C consecutive lines; the order does not
// matter otherwise, every sum runs over all lines).
//
// Their buffers (3.5 MB per role at 1080×135 RGB) come from a small pool and go back to it
// when the frame's caches let go of them: a sequence allocates a few once, instead of mapping
// and page-faulting fresh memory for every frame (which cost ~10 % of a pair at 1080×135).
struct LineSpectra {
  LineSpectra() = default;
  ~LineSpectra();
  LineSpectra(LineSpectra&&) noexcept = default;
  LineSpectra& operator=(LineSpectra&&) noexcept;

  int bins = 0;
  int stride = 0;
  int lines = 0;                  // real lines; the buffer is padded to whole blocks
  FftwBuffer<fftw_complex> data;  // padded lines × stride
  const fftw_complex* line(int index) const {
    return data.data() + static_cast<std::size_t>(index) * stride;
  }
};

// A frame's spectra as the FIRST image of a pair (I_i, unmasked): every line's spectrum, and
// the spectrum of its column energy Q(c) = Σ_rows,channels I(c)².
struct FirstSpectra {
  LineSpectra rows;
  FftwBuffer<fftw_complex> column_energy;  // bins
};

// A frame's spectra as the SECOND image (I_j), masked by the field of view that moves with it:
// the spectra of m·I_j's lines, and Σ m·I_j², the constant term of d².
struct SecondSpectra {
  std::shared_ptr<const FirstSpectra> unmasked;  // set instead of `masked` for the whole mask
  LineSpectra masked;
  double masked_energy = 0.0;
  const LineSpectra& rows() const { return unmasked ? unmasked->rows : masked; }
};

// Each computed once per frame (per mask for the second role) and cached in the frame.
std::shared_ptr<const FirstSpectra> first_spectra(const CompassFrame& frame, FftPlanning planning);
std::shared_ptr<const SecondSpectra> second_spectra(const CompassFrame& frame,
                                                    const ColumnMask& mask, FftPlanning planning);

// The spectra of a pair (the first role of `first`, the second role of `second` for `mask`),
// computed where missing and cached as above. `consume(first_rows, second_rows, begin, end)` is
// called for consecutive ranges of lines that together cover every line once, in order, each as
// soon as both spectra hold it: transforms that are made here run in step, block by block, so
// that a sum over lines reads each block while it is still in cache instead of streaming both
// frames' spectra (2 × 3.5 MB at 1080×135 RGB) back from memory.
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
