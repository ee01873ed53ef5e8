#include "fft_plans.hpp"

#include <map>
#include <mutex>
#include <utility>

#include "omninav/core/errors.hpp"

namespace omninav::signature::detail {
namespace {

// Plans live until the process exits: a plan handed out must stay valid for every extractor
// that holds it, and destroying plans is no more thread-safe than making them.
class PlanCache {
 public:
  ~PlanCache() {
    for (auto& [key, plan] : plans_) fftwf_destroy_plan(plan);
  }

  fftwf_plan get(int width, int lines) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto key = std::make_pair(width, lines);
    if (const auto found = plans_.find(key); found != plans_.end()) return found->second;
    FftwBuffer<float> in(static_cast<std::size_t>(width) * lines);
    FftwBuffer<fftwf_complex> out(static_cast<std::size_t>(width / 2 + 1) * lines);
    int n[] = {width};
    // FFTW_ESTIMATE: the plan depends on the sizes only, never on timing, so the same input
    // gives bit-identical signatures in every run (DESIGN.md, Determinism).
    fftwf_plan plan = fftwf_plan_many_dft_r2c(1, n, lines, in.data(), nullptr, 1, width, out.data(),
                                              nullptr, 1, width / 2 + 1, FFTW_ESTIMATE);
    if (plan == nullptr) {
      throw Error("FFTW could not plan " + std::to_string(lines) + " transforms of length " +
                  std::to_string(width));
    }
    plans_.emplace(key, plan);
    return plan;
  }

 private:
  std::mutex mutex_;
  std::map<std::pair<int, int>, fftwf_plan> plans_;
};

PlanCache& cache() {
  static PlanCache instance;
  return instance;
}

}  // namespace

fftwf_plan rows_r2c_plan(int width, int lines) {
  return cache().get(width, lines);
}

}  // namespace omninav::signature::detail
