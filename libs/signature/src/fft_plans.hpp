#pragma once
// FFTW plans shared by every SignatureExtractor of the process. FFTW's planner is not
// thread-safe, so plans are made under one mutex and kept until exit; executing a plan on new
// arrays (fftwf_execute_dft_r2c) is thread-safe as long as the arrays have the alignment of
// those it was planned with, which fftwf_malloc guarantees for both.

#include <fftw3.h>

#include <cstddef>

namespace omninav::signature::detail {

// The plan of `lines` real transforms of length `width`, input lines × width floats, output
// lines × (width/2 + 1) complex values, both contiguous and line after line.
fftwf_plan rows_r2c_plan(int width, int lines);

// A buffer from fftwf_malloc, freed with fftwf_free.
template <typename T>
class FftwBuffer {
 public:
  FftwBuffer() = default;
  explicit FftwBuffer(std::size_t count)
      : data_(static_cast<T*>(fftwf_malloc(sizeof(T) * (count > 0 ? count : 1)))), size_(count) {}
  ~FftwBuffer() { fftwf_free(data_); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  FftwBuffer(FftwBuffer&& other) noexcept : data_(other.data_), size_(other.size_) {
    other.data_ = nullptr;
    other.size_ = 0;
  }
  FftwBuffer& operator=(FftwBuffer&& other) noexcept {
    if (this != &other) {
      fftwf_free(data_);
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

}  // namespace omninav::signature::detail
