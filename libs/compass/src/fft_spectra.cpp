#include "fft_spectra.hpp"

#include <algorithm>
#include <cstring>
#include <functional>
#include <mutex>
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
  FftwBuffer<fftwf_complex> block;
  std::vector<std::uint32_t> block_energy;  // Q(c) over the block's rows
  std::vector<std::uint8_t> zeros;          // the missing partner of an odd last row
  int width = 0;
  int lines = 0;                               // kBlockRows/2 × channels
  std::optional<std::uint64_t> clear_outside;  // the mask the block is zero outside of
};

Scratch& scratch(int role, const BlockPlan& plan) {
  thread_local Scratch instances[2];
  Scratch& instance = instances[role];
  if (instance.width != plan.width || instance.lines != plan.lines) {
    instance.block = FftwBuffer<fftwf_complex>(static_cast<std::size_t>(plan.stride) *
                                               static_cast<std::size_t>(plan.lines));
    std::memset(instance.block.data(), 0, sizeof(fftwf_complex) * instance.block.size());
    instance.block_energy.assign(static_cast<std::size_t>(plan.width), 0);
    instance.zeros.assign(static_cast<std::size_t>(plan.width) * plan.channels, 0);
    instance.width = plan.width;
    instance.lines = plan.lines;
    instance.clear_outside.reset();
  }
  return instance;
}

// Spectra buffers no frame holds any more, for the next frames (LineSpectra above).
class SpectraPool {
 public:
  SpectraPool() { free_.reserve(kKept); }  // give() never allocates: it runs in destructors

  FftwBuffer<fftwf_complex> take(std::size_t count) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = free_.begin(); it != free_.end(); ++it) {
        if (it->size() != count) continue;
        FftwBuffer<fftwf_complex> buffer = std::move(*it);
        free_.erase(it);
        return buffer;
      }
    }
    return FftwBuffer<fftwf_complex>(count);
  }
  void give(FftwBuffer<fftwf_complex>&& buffer) {
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
  std::vector<FftwBuffer<fftwf_complex>> free_;
};

// Never destroyed: frames may outlive every other static object.
SpectraPool& spectra_pool() {
  static SpectraPool* const pool = new SpectraPool;
  return *pool;
}

// Columns [begin, end) of two image rows of kChannels interleaved 8-bit channels into kChannels
// complex lines of floats, `stride` complex values apart: channel ch of the first row in the
// real parts of line ch, of the second row in its imaginary parts. One pass over the pixels, no
// separate deinterleaving. __restrict: the bytes cannot alias the floats, so the loop
// vectorises; compiled for AVX-512, AVX2 and the baseline like accumulate_conjugate_products
// (fft_correlation.cpp), picked at load time. Exact either way: integers below 2²⁴.
template <int kChannels>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#endif
void widen_rows_of(const std::uint8_t* __restrict first, const std::uint8_t* __restrict second,
                   float* __restrict lines, int stride, int begin, int end) {
  for (int c = begin; c < end; ++c) {
    for (int ch = 0; ch < kChannels; ++ch) {
      float* value = lines + 2 * (static_cast<std::ptrdiff_t>(ch) * stride + c);
      value[0] = first[kChannels * c + ch];
      value[1] = second[kChannels * c + ch];
    }
  }
}

// energy[c] += Σ_ch row(c, ch)². Exact: a block's sums stay below 2³² (kBlockRows·3·255²).
template <int kChannels>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=skylake-avx512", "avx2", "default")))
#endif
void add_squares_of(const std::uint8_t* __restrict row, std::uint32_t* __restrict energy,
                    int width) {
  for (int c = 0; c < width; ++c) {
    std::uint32_t sum = 0;
    for (int ch = 0; ch < kChannels; ++ch) {
      const std::uint32_t value = row[kChannels * c + ch];
      sum += value * value;
    }
    energy[c] += sum;
  }
}

// Frames have 1 or 3 channels (frame.hpp).
void widen_rows(int channels, const std::uint8_t* first, const std::uint8_t* second,
                fftwf_complex* lines, int stride, int begin, int end) {
  float* values = &lines[0][0];
  if (channels == 3) {
    widen_rows_of<3>(first, second, values, stride, begin, end);
  } else {
    widen_rows_of<1>(first, second, values, stride, begin, end);
  }
}

void add_squares(int channels, const std::uint8_t* row, std::uint32_t* energy, int width) {
  if (channels == 3) {
    add_squares_of<3>(row, energy, width);
  } else {
    add_squares_of<1>(row, energy, width);
  }
}

// Zero outside the mask's runs.
void clear_outside(fftwf_complex* line, const ColumnMask& mask, int width) {
  int previous_end = 0;
  for (const auto& [begin, end] : mask.runs()) {
    std::memset(line + previous_end, 0, sizeof(fftwf_complex) * (begin - previous_end));
    previous_end = end;
  }
  std::memset(line + previous_end, 0, sizeof(fftwf_complex) * (width - previous_end));
}

// The spectra of the frame's lines, masked when `mask` is given (columns outside it zero:
// m·J), computed kBlockRows image rows at a time so that a caller can run two transforms in
// step and use each block's spectra while they are still in cache. When `energy` is empty it
// receives the column energies Q(c) = Σ_rows,channels I(c)² of the unmasked image. `role` picks
// the scratch block: transforms that run in step need their own. Caller holds the frame's
// caches.mutex throughout.
class LineTransform {
 public:
  LineTransform(const CompassFrame& frame, const ColumnMask* mask, std::vector<double>& energy,
                FftPlanning planning, int role)
      : frame_(frame),
        mask_(mask != nullptr && !mask->is_whole() ? mask : nullptr),
        energy_(energy),
        plan_(block_plan(frame.width(), frame.channels(), planning)),
        blocks_((frame.height() + kBlockRows - 1) / kBlockRows),
        work_(scratch(role, plan_)) {
    spectra_.stride = plan_.stride;
    spectra_.lines = (frame.height() + 1) / 2 * frame.channels();
    spectra_.data =
        spectra_pool().take(static_cast<std::size_t>(blocks_) * plan_.lines * plan_.stride);
    want_energy_ = energy_.empty();
    if (want_energy_) energy_.assign(static_cast<std::size_t>(frame.width()), 0.0);
    // Only the mask's columns are loaded when the block is already clear outside them.
    runs_only_ = mask_ != nullptr && !want_energy_ && work_.clear_outside == mask_->key();
  }

  int blocks() const { return blocks_; }
  int block_lines() const { return plan_.lines; }
  const LineSpectra& spectra() const { return spectra_; }

  void run(int b) {
    const int width = frame_.width();
    const int channels = frame_.channels();
    // Pairs of rows past the image (the last block's padding) keep whatever the block held:
    // their spectra are never read. A last row without a partner is paired with zeros.
    const int rows = std::min(kBlockRows, frame_.height() - b * kBlockRows);
    if (want_energy_) std::fill(work_.block_energy.begin(), work_.block_energy.end(), 0u);
    for (int j = 0; 2 * j < rows; ++j) {
      const int r = b * kBlockRows + 2 * j;
      const bool pair = 2 * j + 1 < rows;
      const std::uint8_t* first = frame_.row(r);
      const std::uint8_t* second = pair ? frame_.row(r + 1) : work_.zeros.data();
      fftwf_complex* lines =
          work_.block.data() + static_cast<std::size_t>(j) * channels * plan_.stride;
      if (runs_only_) {
        for (const auto& [begin, end] : mask_->runs()) {
          widen_rows(channels, first, second, lines, plan_.stride, begin, end);
        }
        continue;
      }
      widen_rows(channels, first, second, lines, plan_.stride, 0, width);
      if (want_energy_) {
        add_squares(channels, first, work_.block_energy.data(), width);
        if (pair) add_squares(channels, second, work_.block_energy.data(), width);
      }
      if (mask_ != nullptr) {
        for (int ch = 0; ch < channels; ++ch) {
          clear_outside(lines + static_cast<std::size_t>(ch) * plan_.stride, *mask_, width);
        }
      }
    }
    if (want_energy_) {
      for (int c = 0; c < width; ++c) {
        energy_[static_cast<std::size_t>(c)] += work_.block_energy[static_cast<std::size_t>(c)];
      }
    }
    fftwf_execute_dft(
        plan_.forward, work_.block.data(),
        spectra_.data.data() + static_cast<std::size_t>(b) * plan_.lines * plan_.stride);
  }

  LineSpectra finish() {
    if (!runs_only_) {
      // Every block reuses the same buffer: one full block cleared all of it outside the mask
      // (a last, partial block leaves the lines past the image as the full ones left them).
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
  BlockPlan plan_;
  int blocks_;
  Scratch& work_;
  LineSpectra spectra_;
  bool want_energy_ = false;
  bool runs_only_ = false;
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
                                         LineSpectra rows) {
  auto spectra = std::make_shared<FirstSpectra>();
  spectra->rows = std::move(rows);
  const LinePlans plans = line_plans(frame.width());
  FftwBuffer<double> energy_line(static_cast<std::size_t>(frame.width()));
  std::copy(caches.column_energy.begin(), caches.column_energy.end(), energy_line.data());
  spectra->column_energy = FftwBuffer<fftw_complex>(static_cast<std::size_t>(plans.bins));
  fftw_execute_dft_r2c(plans.r2c, energy_line.data(), spectra->column_energy.data());
  return spectra;
}

// Caller holds caches.mutex.
std::shared_ptr<FirstSpectra> compute_first(const CompassFrame& frame, FrameCaches& caches,
                                            FftPlanning planning) {
  return make_first(frame, caches, transform_lines(frame, nullptr, caches.column_energy, planning));
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

// Each role alone, cached in the frame.
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

}  // namespace

LineSpectra::~LineSpectra() {
  spectra_pool().give(std::move(data));
}

LineSpectra& LineSpectra::operator=(LineSpectra&& other) noexcept {
  if (this != &other) {
    spectra_pool().give(std::move(data));
    stride = other.stride;
    lines = other.lines;
    data = std::move(other.data);
  }
  return *this;
}

LinePlans line_plans(int width) {
  LinePlans plans;
  plans.bins = width / 2 + 1;
  plans.r2c = fftw::lines_r2c({width, 1, 0, fftw::Planning::kEstimate});
  plans.c2r = fftw::lines_c2r({width, 1, 0, fftw::Planning::kEstimate});
  return plans;
}

BlockPlan block_plan(int width, int channels, FftPlanning planning) {
  BlockPlan plan;
  plan.width = width;
  plan.channels = channels;
  plan.stride = (width + 7) / 8 * 8;
  plan.lines = kBlockRows / 2 * channels;
  plan.forward =
      fftw::lines_forward_float({width, plan.lines, plan.stride, fftw_planning(planning)});
  return plan;
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
  if (first_rows) a.first = make_first(first, a, first_rows->finish());
  PairSpectra pair;
  pair.first = a.first;
  if (found != b.second.end()) {
    pair.second = found->second;
  } else if (mask.is_whole()) {
    if (second_rows) b.first = make_first(second, b, second_rows->finish());
    pair.second = make_second(mask, b, LineSpectra{});
  } else {
    pair.second = make_second(mask, b, second_rows->finish());
  }
  return pair;
}

}  // namespace omninav::compass::detail
