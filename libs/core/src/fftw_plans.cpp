#include "omninav/core/fftw_plans.hpp"

#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "omninav/core/errors.hpp"

namespace omninav::fftw {
namespace {

enum class Direction { kR2c, kC2r, kForward };

// One of FFTW's two precisions (its functions carry the precision in their names), so that one
// cache serves both.
template <typename RealType, typename ComplexType, typename PlanType,
          PlanType (*kR2c)(int, const int*, int, RealType*, const int*, int, int, ComplexType*,
                           const int*, int, int, unsigned),
          PlanType (*kC2r)(int, const int*, int, ComplexType*, const int*, int, int, RealType*,
                           const int*, int, int, unsigned),
          PlanType (*kDft)(int, const int*, int, ComplexType*, const int*, int, int, ComplexType*,
                           const int*, int, int, int, unsigned),
          void (*kDestroy)(PlanType)>
struct Precision {
  using Real = RealType;
  using Complex = ComplexType;
  using Plan = PlanType;
  static constexpr auto r2c = kR2c;
  static constexpr auto c2r = kC2r;
  static constexpr auto dft = kDft;
  static constexpr auto destroy = kDestroy;
};
using Double = Precision<double, fftw_complex, fftw_plan, fftw_plan_many_dft_r2c,
                         fftw_plan_many_dft_c2r, fftw_plan_many_dft, fftw_destroy_plan>;
using Single = Precision<float, fftwf_complex, fftwf_plan, fftwf_plan_many_dft_r2c,
                         fftwf_plan_many_dft_c2r, fftwf_plan_many_dft, fftwf_destroy_plan>;

// The one mutex every plan of the process is made under (both precisions: one planner lock is
// simpler to reason about, and planning is rare).
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

template <typename P>
class PlanCache {
 public:
  using Plan = typename P::Plan;

  ~PlanCache() {
    for (auto& [key, plan] : plans_) P::destroy(plan);
  }

  Plan get(Direction direction, LinesShape shape) {
    // Complex lines have `width` values; a real line's spectrum has width/2 + 1.
    const int values = direction == Direction::kForward ? shape.width : shape.width / 2 + 1;
    if (shape.stride == 0) shape.stride = values;
    if (shape.width < 1 || shape.lines < 1 || shape.stride < values) {
      throw Error("FFTW: no transforms of " + std::to_string(shape.lines) + " lines of length " +
                  std::to_string(shape.width) + " with spectra " + std::to_string(shape.stride) +
                  " values apart");
    }
    const std::lock_guard<std::mutex> lock(planner_mutex());
    const auto key = std::make_pair(direction, shape);
    if (const auto found = plans_.find(key); found != plans_.end()) return found->second;
    // FFTW_MEASURE overwrites the arrays it plans with: plan on scratch arrays, execute later on
    // others of the same (Buffer) alignment.
    Buffer<typename P::Complex> spectra(static_cast<std::size_t>(shape.stride) * shape.lines);
    // The other side: real lines, or complex lines laid out as the spectra.
    Buffer<typename P::Real> real(
        direction == Direction::kForward ? 0 : static_cast<std::size_t>(shape.width) * shape.lines);
    Buffer<typename P::Complex> lines(direction == Direction::kForward
                                          ? static_cast<std::size_t>(shape.stride) * shape.lines
                                          : 0);
    const unsigned flags = shape.planning == Planning::kMeasure ? FFTW_MEASURE : FFTW_ESTIMATE;
    int n[] = {shape.width};
    // Lines one after another: unit stride inside a line, `width` (real) or `stride`
    // (complex) values from one line to the next.
    Plan plan = nullptr;
    switch (direction) {
      case Direction::kR2c:
        plan = P::r2c(1, n, shape.lines, real.data(), nullptr, 1, shape.width, spectra.data(),
                      nullptr, 1, shape.stride, flags);
        break;
      case Direction::kC2r:
        plan = P::c2r(1, n, shape.lines, spectra.data(), nullptr, 1, shape.stride, real.data(),
                      nullptr, 1, shape.width, flags);
        break;
      case Direction::kForward:
        plan = P::dft(1, n, shape.lines, lines.data(), nullptr, 1, shape.stride, spectra.data(),
                      nullptr, 1, shape.stride, FFTW_FORWARD, flags);
        break;
    }
    if (plan == nullptr) {
      throw Error("FFTW could not plan " + std::to_string(shape.lines) + " transforms of length " +
                  std::to_string(shape.width));
    }
    plans_.emplace(key, plan);
    return plan;
  }

 private:
  std::map<std::pair<Direction, LinesShape>, Plan> plans_;  // guarded by planner_mutex()
};

template <typename P>
PlanCache<P>& cache() {
  static PlanCache<P> instance;
  return instance;
}

}  // namespace

fftw_plan lines_r2c(const LinesShape& shape) {
  return cache<Double>().get(Direction::kR2c, shape);
}

fftwf_plan lines_r2c_float(const LinesShape& shape) {
  return cache<Single>().get(Direction::kR2c, shape);
}

fftwf_plan lines_forward_float(const LinesShape& shape) {
  return cache<Single>().get(Direction::kForward, shape);
}

fftw_plan lines_c2r(const LinesShape& shape) {
  return cache<Double>().get(Direction::kC2r, shape);
}

}  // namespace omninav::fftw
