#include "fft_spectra.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <opencv2/core.hpp>
#include <utility>

#include "frame_caches.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::compass::detail {
namespace {

// Plans live until the process exits: a plan handed out must stay valid for everyone holding
// it, and destroying plans is no more thread-safe than making them.
class PlanRegistry {
 public:
  ~PlanRegistry() {
    for (auto& [key, plans] : plans_) {
      fftw_destroy_plan(plans.block_r2c);
      fftw_destroy_plan(plans.one_r2c);
      fftw_destroy_plan(plans.one_c2r);
    }
  }

  const FftPlans& get(int width, FftPlanning planning) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto key = std::make_pair(width, planning);
    if (const auto found = plans_.find(key); found != plans_.end()) return found->second;
    FftPlans plans;
    plans.width = width;
    plans.bins = width / 2 + 1;
    plans.stride = (plans.bins + 3) / 4 * 4;
    // FFTW_MEASURE overwrites the arrays it plans with: plan on scratch arrays, execute later
    // on others of the same (fftw_malloc) alignment.
    FftwBuffer<double> real(static_cast<std::size_t>(width) * kBlockLines);
    FftwBuffer<fftw_complex> spectrum(static_cast<std::size_t>(plans.stride) * kBlockLines);
    const unsigned flags = planning == FftPlanning::kMeasure ? FFTW_MEASURE : FFTW_ESTIMATE;
    int n[] = {width};
    plans.block_r2c = fftw_plan_many_dft_r2c(1, n, kBlockLines, real.data(), nullptr, 1, width,
                                             spectrum.data(), nullptr, 1, plans.stride, flags);
    plans.one_r2c = fftw_plan_dft_r2c_1d(width, real.data(), spectrum.data(), flags);
    plans.one_c2r = fftw_plan_dft_c2r_1d(width, spectrum.data(), real.data(), flags);
    if (plans.block_r2c == nullptr || plans.one_r2c == nullptr || plans.one_c2r == nullptr) {
      throw Error("FFTW could not plan transforms of length " + std::to_string(width));
    }
    return plans_.emplace(key, plans).first->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::pair<int, FftPlanning>, FftPlans> plans_;
};

PlanRegistry& registry() {
  static PlanRegistry instance;
  return instance;
}

// __restrict: the bytes cannot alias the doubles, so these loops vectorise.
void widen(const std::uint8_t* __restrict row, double* __restrict line, int begin, int end) {
  for (int c = begin; c < end; ++c) line[c] = row[c];
}

void add_squares(const double* __restrict line, double* __restrict energy, int width) {
  for (int c = 0; c < width; ++c) energy[c] += line[c] * line[c];
}

// The spectra of the frame's lines, masked when `mask` is given (columns outside it zero:
// m·J). When `energy` is empty it receives the column energies Q(c) = Σ_lines line(c)² of the
// unmasked image (exact: integer sums far below 2⁵³). Caller holds the frame's caches.mutex.
LineSpectra transform_lines(const CompassFrame& frame, const ColumnMask* mask,
                            std::vector<double>& energy, FftPlanning planning) {
  const int width = frame.width();
  const int height = frame.height();
  const int channels = frame.channels();
  const FftPlans& plans = fft_plans(width, planning);
  LineSpectra spectra;
  spectra.bins = plans.bins;
  spectra.stride = plans.stride;
  spectra.lines = height * channels;
  const int blocks = (spectra.lines + kBlockLines - 1) / kBlockLines;
  spectra.data =
      FftwBuffer<fftw_complex>(static_cast<std::size_t>(blocks) * kBlockLines * plans.stride);

  const bool masked = mask != nullptr && !mask->is_whole();
  const bool want_energy = energy.empty();
  if (want_energy) energy.assign(static_cast<std::size_t>(width), 0.0);
  std::vector<cv::Mat> planes;
  cv::split(frame.image(), planes);  // vectorised by OpenCV
  FftwBuffer<double> block(static_cast<std::size_t>(width) * kBlockLines);
  for (int b = 0; b < blocks; ++b) {
    std::memset(block.data(), 0, sizeof(double) * block.size());
    for (int i = 0; i < kBlockLines; ++i) {
      const int l = b * kBlockLines + i;
      if (l >= spectra.lines) break;  // padding lines stay zero
      const std::uint8_t* row =
          planes[static_cast<std::size_t>(l / height)].ptr<std::uint8_t>(l % height);
      double* line = block.data() + static_cast<std::size_t>(i) * width;
      if (!masked || want_energy) {
        widen(row, line, 0, width);
        if (want_energy) add_squares(line, energy.data(), width);
        if (masked) {
          int previous_end = 0;
          for (const auto& [begin, end] : mask->runs()) {
            std::memset(line + previous_end, 0, sizeof(double) * (begin - previous_end));
            previous_end = end;
          }
          std::memset(line + previous_end, 0, sizeof(double) * (width - previous_end));
        }
      } else {
        for (const auto& [begin, end] : mask->runs()) widen(row, line, begin, end);
      }
    }
    fftw_execute_dft_r2c(
        plans.block_r2c, block.data(),
        spectra.data.data() + static_cast<std::size_t>(b) * kBlockLines * plans.stride);
  }
  return spectra;
}

// Caller holds caches.mutex.
std::shared_ptr<FirstSpectra> compute_first(const CompassFrame& frame, FrameCaches& caches,
                                            FftPlanning planning) {
  auto spectra = std::make_shared<FirstSpectra>();
  spectra->rows = transform_lines(frame, nullptr, caches.column_energy, planning);
  const FftPlans& plans = fft_plans(frame.width(), planning);
  FftwBuffer<double> energy_line(static_cast<std::size_t>(frame.width()));
  std::copy(caches.column_energy.begin(), caches.column_energy.end(), energy_line.data());
  spectra->column_energy = FftwBuffer<fftw_complex>(static_cast<std::size_t>(plans.bins));
  fftw_execute_dft_r2c(plans.one_r2c, energy_line.data(), spectra->column_energy.data());
  return spectra;
}

}  // namespace

const FftPlans& fft_plans(int width, FftPlanning planning) {
  return registry().get(width, planning);
}

std::shared_ptr<const FirstSpectra> first_spectra(const CompassFrame& frame, FftPlanning planning) {
  FrameCaches& caches = frame.caches();
  const std::lock_guard<std::mutex> lock(caches.mutex);
  if (!caches.first) caches.first = compute_first(frame, caches, planning);
  return caches.first;
}

std::shared_ptr<const SecondSpectra> second_spectra(const CompassFrame& frame,
                                                    const ColumnMask& mask, FftPlanning planning) {
  if (mask.width_px() != frame.width()) {
    throw InputError(frame.source() + ": a panorama " + std::to_string(frame.width()) +
                     " columns wide used with a mask for " + std::to_string(mask.width_px()));
  }
  FrameCaches& caches = frame.caches();
  const std::lock_guard<std::mutex> lock(caches.mutex);
  if (const auto found = caches.second.find(mask.key()); found != caches.second.end()) {
    return found->second;
  }
  auto spectra = std::make_shared<SecondSpectra>();
  if (mask.is_whole()) {
    // Unmasked, the second role's spectra are the first role's: one transform per frame.
    if (!caches.first) caches.first = compute_first(frame, caches, planning);
    spectra->unmasked = caches.first;
  } else {
    spectra->masked = transform_lines(frame, &mask, caches.column_energy, planning);
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

}  // namespace omninav::compass::detail
