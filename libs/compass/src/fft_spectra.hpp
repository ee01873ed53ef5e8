#pragma once
// FFTW plans and the per-frame row spectra of the masked cross-correlation (fft_minimiser.cpp)
// and the phase estimator (phase.cpp). Private to libs/compass.
//
// Double precision on purpose: the costs the FFT yields are rounded to the integers they
// approximate (fft_minimiser.cpp), which needs an absolute error well below 0.5 on values up to
// ~3·10¹⁰ (1080×135 RGB); double's ~10⁻¹⁶ relative error gives ~10⁻⁵. It also keeps this
// library on FFTW's double-precision planner, apart from libs/signature's single-precision one.

#include <fftw3.h>

#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "omninav/compass/field_of_view.hpp"
#include "omninav/compass/frame.hpp"
#include "omninav/compass/minimiser.hpp"

namespace omninav::compass::detail {

// A buffer from fftw_malloc (SIMD-aligned, as every array a plan runs on must be).
template <typename T>
class FftwBuffer {
 public:
  FftwBuffer() = default;
  explicit FftwBuffer(std::size_t count)
      : data_(static_cast<T*>(fftw_malloc(sizeof(T) * (count > 0 ? count : 1)))), size_(count) {
    if (data_ == nullptr) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftw_free(data_); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  FftwBuffer(FftwBuffer&& other) noexcept : data_(other.data_), size_(other.size_) {
    other.data_ = nullptr;
    other.size_ = 0;
  }
  FftwBuffer& operator=(FftwBuffer&& other) noexcept {
    if (this != &other) {
      fftw_free(data_);
      data_ = other.data_;
      size_ = other.size_;
      other.data_ = nullptr;
      other.size_ = 0;
    }
    return *this;
  }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

// The plans for panoramas `width` wide. Made once per (width, planning) under a process-wide
// mutex (FFTW's planner is not thread-safe) and kept until exit; executing them on other
// fftw_malloc'd arrays of the same alignment is thread-safe.
//
// Lines are transformed kBlockLines at a time through a small buffer that stays in cache,
// rather than converting a whole frame to doubles first (at 1080×135 RGB that would stream
// 3.5 MB through memory twice per transform). Spectra rows are `stride` = bins rounded up to
// a multiple of 4 complex values (64 bytes) apart, so that every block's output starts with
// the alignment the plan was made with.
constexpr int kBlockLines = 32;

struct FftPlans {
  int width = 0;
  int bins = 0;                   // width/2 + 1
  int stride = 0;                 // bins rounded up to a multiple of 4
  fftw_plan block_r2c = nullptr;  // kBlockLines lines, `width` apart → rows `stride` apart
  fftw_plan one_r2c = nullptr;    // one line
  fftw_plan one_c2r = nullptr;    // one spectrum back (unnormalised: × width)
};
const FftPlans& fft_plans(int width, FftPlanning planning);

// Row spectra of a frame's lines (rows × channels; line ch·H + r is channel ch of row r; the
// order does not matter, every sum runs over all lines).
struct LineSpectra {
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

// Minimiser (c) on a table (fft_correlation.cpp).
ShiftSearch fft_minimise(CostTable& table, FftPlanning planning);

}  // namespace omninav::compass::detail
