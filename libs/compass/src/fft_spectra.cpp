#include "fft_spectra.hpp"

#include <algorithm>
#include <cstring>
#include <functional>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>

#include "frame_caches.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass::detail {
namespace {

fftw::Planning fftw_planning(FftPlanning planning) {
  return planning == FftPlanning::kMeasure ? fftw::Planning::kMeasure : fftw::Planning::kEstimate;
}

// The block the lines of a transform pass through, one per thread and kept (no allocation per
// frame). The masked transform writes only the mask's columns, so once the block has been
// cleared outside a mask's runs it stays clear for every later frame with that mask.
struct Scratch {
  std::vector<cv::Mat> planes;  // the frame's channels apart (cv::split: vectorised)
  FftwBuffer<double> block;
  int width = 0;
  int lines = 0;
  std::optional<std::uint64_t> clear_outside;  // the mask the block is zero outside of
};

Scratch& scratch(int role, int width, int block_lines) {
  thread_local Scratch instances[2];
  Scratch& instance = instances[role];
  if (instance.width != width || instance.lines != block_lines) {
    instance.block = FftwBuffer<double>(static_cast<std::size_t>(width) * block_lines);
    std::memset(instance.block.data(), 0, sizeof(double) * instance.block.size());
    instance.width = width;
    instance.lines = block_lines;
    instance.clear_outside.reset();
  }
  return instance;
}

// Spectra buffers no frame holds any more, for the next frames (LineSpectra above).
class SpectraPool {
 public:
  SpectraPool() { free_.reserve(kKept); }  // give() never allocates: it runs in destructors

  FftwBuffer<fftw_complex> take(std::size_t count) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = free_.begin(); it != free_.end(); ++it) {
        if (it->size() != count) continue;
        FftwBuffer<fftw_complex> buffer = std::move(*it);
        free_.erase(it);
        return buffer;
      }
    }
    return FftwBuffer<fftw_complex>(count);
  }
  void give(FftwBuffer<fftw_complex>&& buffer) {
    if (buffer.size() == 0) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    // A few buffers are enough for a sequence (each frame's two roles, the reference's and the
    // current one's); the oldest go when more are given back.
    if (free_.size() == kKept) free_.erase(free_.begin());
    free_.push_back(std::move(buffer));
  }

 private:
  static constexpr std::size_t kKept = 8;
  std::mutex mutex_;
  std::vector<FftwBuffer<fftw_complex>> free_;
};

// Never destroyed: frames may outlive every other static object.
SpectraPool& spectra_pool() {
  static SpectraPool* const pool = new SpectraPool;
  return *pool;
}

// Columns [begin, end) of a row of 8-bit pixels into a line of doubles. __restrict: the bytes
// cannot alias the doubles, so the loops vectorise; compiled for AVX-512, AVX2 and the baseline
// like accumulate_conjugate_products (fft_correlation.cpp), picked at load time. Exact either
// way: integers below 2⁵³.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#endif
void widen(const std::uint8_t* __restrict row, double* __restrict line, int begin, int end) {
  for (int c = begin; c < end; ++c) line[c] = row[c];
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#endif
void add_squares(const double* __restrict line, double* __restrict energy, int width) {
  for (int c = 0; c < width; ++c) energy[c] += line[c] * line[c];
}

// Zero outside the mask's runs.
void clear_outside(double* line, const ColumnMask& mask, int width) {
  int previous_end = 0;
  for (const auto& [begin, end] : mask.runs()) {
    std::memset(line + previous_end, 0, sizeof(double) * (begin - previous_end));
    previous_end = end;
  }
  std::memset(line + previous_end, 0, sizeof(double) * (width - previous_end));
}

// The spectra of the frame's lines, masked when `mask` is given (columns outside it zero:
// m·J), computed kBlockRows image rows at a time so that a caller can run two transforms in
// step and use each block's spectra while they are still in cache. When `energy` is empty it
// receives the column energies Q(c) = Σ_lines line(c)² of the unmasked image (exact: integer
// sums far below 2⁵³). `role` picks the scratch block: transforms that run in step need their
// own. Caller holds the frame's caches.mutex throughout.
class LineTransform {
 public:
  LineTransform(const CompassFrame& frame, const ColumnMask* mask, std::vector<double>& energy,
                FftPlanning planning, int role)
      : frame_(frame),
        mask_(mask != nullptr && !mask->is_whole() ? mask : nullptr),
        energy_(energy),
        plans_(fft_plans(frame.width(), planning, frame.channels())),
        blocks_((frame.height() + kBlockRows - 1) / kBlockRows),
        work_(scratch(role, frame.width(), plans_.block_lines)) {
    spectra_.bins = plans_.bins;
    spectra_.stride = plans_.stride;
    spectra_.lines = frame.height() * frame.channels();
    spectra_.data =
        spectra_pool().take(static_cast<std::size_t>(blocks_) * plans_.block_lines * plans_.stride);
    want_energy_ = energy_.empty();
    if (want_energy_) energy_.assign(static_cast<std::size_t>(frame.width()), 0.0);
    // Only the mask's columns are loaded when the block is already clear outside them.
    runs_only_ = mask_ != nullptr && !want_energy_ && work_.clear_outside == mask_->key();
    if (frame.channels() > 1) {
      cv::split(frame.image(), work_.planes);  // into the kept planes: no allocation
      planes_ = &work_.planes;
    }
  }

  int blocks() const { return blocks_; }
  int block_lines() const { return plans_.block_lines; }
  const LineSpectra& spectra() const { return spectra_; }

  void run(int b) {
    const int width = frame_.width();
    const int channels = frame_.channels();
    // Rows past the image (the last block's padding) keep whatever the block held: their
    // spectra are never read.
    const int rows = std::min(kBlockRows, frame_.height() - b * kBlockRows);
    for (int i = 0; i < rows; ++i) {
      const int r = b * kBlockRows + i;
      for (int ch = 0; ch < channels; ++ch) {
        const std::uint8_t* row =
            planes_ != nullptr ? (*planes_)[static_cast<std::size_t>(ch)].ptr<std::uint8_t>(r)
                               : frame_.row(r);
        double* line = work_.block.data() + static_cast<std::size_t>(i * channels + ch) * width;
        if (runs_only_) {
          for (const auto& [begin, end] : mask_->runs()) widen(row, line, begin, end);
          continue;
        }
        widen(row, line, 0, width);
        if (want_energy_) add_squares(line, energy_.data(), width);
        if (mask_ != nullptr) clear_outside(line, *mask_, width);
      }
    }
    fftw_execute_dft_r2c(
        plans_.block_r2c, work_.block.data(),
        spectra_.data.data() + static_cast<std::size_t>(b) * plans_.block_lines * plans_.stride);
  }

  LineSpectra finish() {
    if (!runs_only_) {
      // Every block reuses the same buffer: one full block cleared all of it outside the mask
      // (a last, partial block leaves the rows past the image as the full ones left them).
      if (mask_ != nullptr && frame_.height() >= kBlockRows) {
        work_.clear_outside = mask_->key();
      } else {
        work_.clear_outside.reset();
      }
    }
    return std::move(spectra_);
  }

 private:
  const CompassFrame& frame_;
  const ColumnMask* mask_;  // null: unmasked
  std::vector<double>& energy_;
  FftPlans plans_;
  int blocks_;
  Scratch& work_;
  LineSpectra spectra_;
  bool want_energy_ = false;
  bool runs_only_ = false;
  const std::vector<cv::Mat>* planes_ = nullptr;
};

LineSpectra transform_lines(const CompassFrame& frame, const ColumnMask* mask,
                            std::vector<double>& energy, FftPlanning planning) {
  LineTransform transform(frame, mask, energy, planning, mask != nullptr ? 1 : 0);
  for (int b = 0; b < transform.blocks(); ++b) transform.run(b);
  return transform.finish();
}

// The first role from the frame's line spectra: adds the spectrum of its column energy (which
// the unmasked transform has completed). Caller holds caches.mutex.
std::shared_ptr<FirstSpectra> make_first(const CompassFrame& frame, FrameCaches& caches,
                                         LineSpectra rows, FftPlanning planning) {
  auto spectra = std::make_shared<FirstSpectra>();
  spectra->rows = std::move(rows);
  const FftPlans plans = fft_plans(frame.width(), planning);
  FftwBuffer<double> energy_line(static_cast<std::size_t>(frame.width()));
  std::copy(caches.column_energy.begin(), caches.column_energy.end(), energy_line.data());
  spectra->column_energy = FftwBuffer<fftw_complex>(static_cast<std::size_t>(plans.bins));
  fftw_execute_dft_r2c(plans.one_r2c, energy_line.data(), spectra->column_energy.data());
  return spectra;
}

// Caller holds caches.mutex.
std::shared_ptr<FirstSpectra> compute_first(const CompassFrame& frame, FrameCaches& caches,
                                            FftPlanning planning) {
  return make_first(frame, caches, transform_lines(frame, nullptr, caches.column_energy, planning),
                    planning);
}

// The second role, cached in the frame: the masked spectra (ignored for the whole mask, whose
// second role is the first role: one transform per frame) and Σ m·J². Caller holds
// caches.mutex, and for the whole mask has made caches.first.
std::shared_ptr<const SecondSpectra> make_second(const ColumnMask& mask, FrameCaches& caches,
                                                 LineSpectra masked) {
  auto spectra = std::make_shared<SecondSpectra>();
  if (mask.is_whole()) {
    spectra->unmasked = caches.first;
  } else {
    spectra->masked = std::move(masked);
  }
  double masked_energy = 0.0;
  for (const auto& [begin, end] : mask.runs()) {
    for (int c = begin; c < end; ++c) {
      masked_energy += caches.column_energy[static_cast<std::size_t>(c)];
    }
  }
  spectra->masked_energy = masked_energy;
  caches.second.emplace(mask.key(), spectra);
  return spectra;
}

void check_mask(const CompassFrame& frame, const ColumnMask& mask) {
  if (mask.width_px() != frame.width()) {
    throw InputError(frame.source() + ": a panorama " + std::to_string(frame.width()) +
                     " columns wide used with a mask for " + std::to_string(mask.width_px()));
  }
}

}  // namespace

LineSpectra::~LineSpectra() {
  spectra_pool().give(std::move(data));
}

LineSpectra& LineSpectra::operator=(LineSpectra&& other) noexcept {
  if (this != &other) {
    spectra_pool().give(std::move(data));
    bins = other.bins;
    stride = other.stride;
    lines = other.lines;
    data = std::move(other.data);
  }
  return *this;
}

FftPlans fft_plans(int width, FftPlanning planning, int channels) {
  FftPlans plans;
  plans.width = width;
  plans.bins = width / 2 + 1;
  plans.stride = (plans.bins + 3) / 4 * 4;
  const fftw::Planning how = fftw_planning(planning);
  plans.one_r2c = fftw::lines_r2c({width, 1, plans.stride, how});
  plans.one_c2r = fftw::lines_c2r({width, 1, plans.stride, how});
  if (channels > 0) {
    plans.block_lines = kBlockRows * channels;
    plans.block_r2c = fftw::lines_r2c({width, plans.block_lines, plans.stride, how});
  }
  return plans;
}

std::shared_ptr<const FirstSpectra> first_spectra(const CompassFrame& frame, FftPlanning planning) {
  FrameCaches& caches = frame.caches();
  const std::lock_guard<std::mutex> lock(caches.mutex);
  if (!caches.first) caches.first = compute_first(frame, caches, planning);
  return caches.first;
}

std::shared_ptr<const SecondSpectra> second_spectra(const CompassFrame& frame,
                                                    const ColumnMask& mask, FftPlanning planning) {
  check_mask(frame, mask);
  FrameCaches& caches = frame.caches();
  const std::lock_guard<std::mutex> lock(caches.mutex);
  if (const auto found = caches.second.find(mask.key()); found != caches.second.end()) {
    return found->second;
  }
  if (mask.is_whole()) {
    if (!caches.first) caches.first = compute_first(frame, caches, planning);
    return make_second(mask, caches, LineSpectra{});
  }
  return make_second(mask, caches, transform_lines(frame, &mask, caches.column_energy, planning));
}

PairSpectra pair_spectra(
    const CompassFrame& first, const CompassFrame& second, const ColumnMask& mask,
    FftPlanning planning,
    const std::function<void(const LineSpectra&, const LineSpectra&, int, int)>& consume) {
  check_mask(second, mask);
  FrameCaches& a = first.caches();
  FrameCaches& b = second.caches();
  if (&a == &b) {  // one frame in both roles (it shares its caches with its copies)
    PairSpectra pair{first_spectra(first, planning), second_spectra(second, mask, planning)};
    consume(pair.first->rows, pair.second->rows(), 0, pair.first->rows.lines);
    return pair;
  }
  const std::scoped_lock lock(a.mutex, b.mutex);
  const auto found = b.second.find(mask.key());
  // What is missing: the first's unmasked transform; the second's masked one, or for the whole
  // mask its unmasked one (its first role).
  std::optional<LineTransform> first_rows, second_rows;
  if (!a.first) first_rows.emplace(first, nullptr, a.column_energy, planning, 0);
  if (found == b.second.end() && !(mask.is_whole() && b.first)) {
    second_rows.emplace(second, &mask, b.column_energy, planning, 1);
  }
  const LineSpectra& rows_a = first_rows ? first_rows->spectra() : a.first->rows;
  const LineSpectra& rows_b = second_rows               ? second_rows->spectra()
                              : found != b.second.end() ? found->second->rows()
                                                        : b.first->rows;
  const int lines = rows_a.lines;
  if (first_rows || second_rows) {
    // In step, block by block: each block's lines are used while they are in cache.
    const LineTransform& any = first_rows ? *first_rows : *second_rows;
    for (int block = 0; block < any.blocks(); ++block) {
      if (first_rows) first_rows->run(block);
      if (second_rows) second_rows->run(block);
      const int begin = block * any.block_lines();
      consume(rows_a, rows_b, begin, std::min(lines, begin + any.block_lines()));
    }
  } else {
    consume(rows_a, rows_b, 0, lines);
  }
  if (first_rows) a.first = make_first(first, a, first_rows->finish(), planning);
  PairSpectra pair;
  pair.first = a.first;
  if (found != b.second.end()) {
    pair.second = found->second;
  } else if (mask.is_whole()) {
    if (second_rows) b.first = make_first(second, b, second_rows->finish(), planning);
    pair.second = make_second(mask, b, LineSpectra{});
  } else {
    pair.second = make_second(mask, b, second_rows->finish());
  }
  return pair;
}

}  // namespace omninav::compass::detail
