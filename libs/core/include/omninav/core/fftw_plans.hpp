#pragma once
// FFTW plans made once per process and shared by every library that transforms panorama lines
// (libs/compass: the masked cross-correlation and the Fourier phase; libs/signature: Fourier
// signatures). One cache, below both (docs/design.md: core ← compass, signature).
//
// FFTW's planner is not thread-safe: every plan is made under one process-wide mutex, once per
// shape, and kept until the process exits (a plan handed out must stay valid for everyone
// holding it, and destroying plans is no more thread-safe than making them). Executing a plan on
// other arrays (fftw_execute_dft_r2c and friends) is thread-safe as long as those arrays have the
// alignment of the ones it was planned with: plans are made on Buffer arrays, so execute them on
// Buffer arrays.

#include <fftw3.h>

#include <compare>
#include <cstddef>
#include <new>
#include <type_traits>

namespace omninav::fftw {

enum class Planning {
  kEstimate,  // FFTW_ESTIMATE: from the shape alone, instantly; the same plan in every run
  kMeasure,   // FFTW_MEASURE: FFTW times candidates once per shape (~0.3 s at 1080 columns)
};

// A buffer from FFTW's allocator (SIMD-aligned, as every array a plan runs on must be): the
// single-precision one for float and fftwf_complex, the double-precision one otherwise.
template <typename T>
class Buffer {
  static constexpr bool kSingle = std::is_same_v<T, float> || std::is_same_v<T, fftwf_complex>;

 public:
  Buffer() = default;
  explicit Buffer(std::size_t count) : data_(allocate(count)), size_(count) {}
  ~Buffer() { release(data_); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& other) noexcept : data_(other.data_), size_(other.size_) {
    other.data_ = nullptr;
    other.size_ = 0;
  }
  Buffer& operator=(Buffer&& other) noexcept {
    if (this != &other) {
      release(data_);
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
  static T* allocate(std::size_t count) {
    const std::size_t bytes = sizeof(T) * (count > 0 ? count : 1);
    void* memory = kSingle ? fftwf_malloc(bytes) : fftw_malloc(bytes);
    if (memory == nullptr) throw std::bad_alloc();
    return static_cast<T*>(memory);
  }
  static void release(T* data) {
    if (kSingle) {
      fftwf_free(data);
    } else {
      fftw_free(data);
    }
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
};

// `lines` one-dimensional transforms of length `width`: real lines one after another, `width`
// values apart; spectra of width/2 + 1 complex values, `stride` complex values apart (0: packed,
// width/2 + 1; a larger stride keeps every spectrum's start SIMD-aligned). For complex lines
// (lines_forward_float) lines and spectra both have `width` values, `stride` apart (0: width).
struct LinesShape {
  int width = 0;
  int lines = 1;
  int stride = 0;
  Planning planning = Planning::kEstimate;
  auto operator<=>(const LinesShape&) const = default;
};

// The plans of that shape, made on first use. Throw omninav::Error for an impossible shape or when
// FFTW cannot plan it.
// Real lines → spectra (FFTW's forward transform, unnormalised). Keeps its input.
fftw_plan lines_r2c(const LinesShape& shape);
fftwf_plan lines_r2c_float(const LinesShape& shape);
// Complex lines → their spectra (the forward transform, unnormalised). Keeps its input.
fftwf_plan lines_forward_float(const LinesShape& shape);
// Spectra → real lines (the backward transform, unnormalised: × width). Overwrites its input.
fftw_plan lines_c2r(const LinesShape& shape);

}  // namespace omninav::fftw
