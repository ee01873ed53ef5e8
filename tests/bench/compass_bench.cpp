// The visual compass's speed: pairs per second for the minimisers (a) exhaustive,
// (b) local + scan and (c) FFT at 360×45 and 1080×135 RGB, with and without the field-of-view
// mask, frames per second for Algorithm 1 over a sequence, and pairs per second for min-warping
// (min_warping.hpp). The ratios asked for are printed at the end, from the times of this one
// run.
//
// Run on one core:  taskset -c 1 build/bin/compass_bench
// The ratios printed at the end divide CPU times measured in this one run.
//
// What a "pair" costs here: PairMatcher::match, the whole answer a user gets (minimum, sub-pixel
// fit, amplitudes, confidence), on consecutive frames of a rendered circle (~3° and 4 cm apart),
// in steady state: each pair brings one new frame (a fresh CompassFrame, its pixels copied, its
// caches empty) and reuses the previous one, so (c) transforms every frame once per role, as it
// does along a sequence. (b) starts from 0, as for successive frames. The exhaustive search is
// measured twice: "exhaustive" is the oracle, the plain transcription of Eq. 2 that the tests
// trust; "exhaustive_fast" evaluates every shift with (b)'s vectorised kernel, to show how much
// of (c)'s lead is the FFT and how much is the oracle's plain code. The FFT is measured with
// FFTW_ESTIMATE plans (compass.yaml's default) and with FFTW_MEASURE plans ("fft_measure"); its
// evaluations_per_pair are the exact evaluations it leaves (the shifts within its error bound of
// the minimum, the sub-pixel fit's neighbours, the amplitude's half turn).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "omninav/compass/min_warping.hpp"
#include "omninav/compass/pair_matcher.hpp"
#include "omninav/compass/visual_compass.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/trajectory.hpp"

namespace {

using omninav::compass::CompassFrame;
using omninav::compass::MinimiserKind;
using omninav::compass::PairMatcher;
using omninav::compass::PairMatcherParams;

constexpr int kFrames = 24;

// Frames along a circle in the default room, rendered once per size: `fast` a tight circle
// that turns ~19° and moves 5 cm between frames (the zoo's wanders at their sharpest, where
// the global fallback searches every shift), else Table 2's CIRCLE at 5 frames/s (~3°, 4 cm).
const std::vector<cv::Mat>& frames(int width, int height, bool fast = false) {
  static std::map<std::tuple<int, int, bool>, std::vector<cv::Mat>> cache;
  auto& images = cache[{width, height, fast}];
  if (images.empty()) {
    const omninav::sim::World world = omninav::sim::make_room({});
    omninav::sim::RenderParams params;
    params.geometry.width_px = width;
    params.geometry.height_px = height;
    const omninav::sim::Renderer renderer(world, params);
    const omninav::sim::Trajectory circle = omninav::sim::make_trajectory(
        fast ? "circle:cx=2.5,cy=2.9,radius_m=0.15,turns=2,speed_m_s=0.5,fps=10"
             : "circle:cx=1.5,cy=2.6,radius_m=0.9,turns=1,speed_m_s=0.2,fps=5",
        world);
    for (int i = 0; i < kFrames; ++i) {
      images.push_back(renderer.render(circle.poses[static_cast<std::size_t>(i)].pose));
    }
  }
  return images;
}

PairMatcherParams matcher_params(MinimiserKind kind, bool mask, bool variant = false) {
  PairMatcherParams params;
  params.minimiser.kind = kind;
  // The variant: the exhaustive search with (b)'s fast kernel; the FFT with FFTW_MEASURE plans.
  params.minimiser.exhaustive_fast_kernel = variant;
  if (variant) params.minimiser.fft_planning = omninav::compass::FftPlanning::kMeasure;
  params.distance.field_of_view.front_back = mask;
  return params;
}

void pairs(benchmark::State& state, MinimiserKind kind, bool variant, int width, int height,
           bool mask) {
  const std::vector<cv::Mat>& images = frames(width, height);
  const PairMatcher matcher(matcher_params(kind, mask, variant));
  // FFTW plans are made on first use (FFTW_MEASURE: ~0.4 s at 1080): once, before timing.
  matcher.match(CompassFrame(images[0]), CompassFrame(images[1]), 0);
  auto previous = std::make_unique<CompassFrame>(images[0], 0);
  int next = 1;
  long evaluations = 0;
  for (auto _ : state) {
    auto current = std::make_unique<CompassFrame>(images[static_cast<std::size_t>(next)], next);
    const auto match = matcher.match(*previous, *current, 0);
    benchmark::DoNotOptimize(match);
    evaluations += match.evaluations;
    previous = std::move(current);
    next = (next + 1) % kFrames;
  }
  state.counters["pairs_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["evaluations_per_pair"] =
      static_cast<double>(evaluations) / static_cast<double>(state.iterations());
}

// What an Algorithm 1 benchmark runs beyond compass.yaml's defaults.
struct Alg1Options {
  bool fixed_skip = false;  // Fx 0, the successive-pair compass
  bool fallback = true;     // minimiser.global_fallback
  bool fast = false;        // the fast-turning circle of frames()
  bool joint = true;        // min_warping.in_compass
};

// Algorithm 1 (Table 2's parameters) over the sequence, frames made as a camera would hand
// them over (fresh CompassFrames).
void algorithm1(benchmark::State& state, MinimiserKind kind, int width, int height,
                Alg1Options options) {
  const std::vector<cv::Mat>& images = frames(width, height, options.fast);
  omninav::compass::CompassParams params;
  params.matcher.minimiser.kind = kind;
  params.fast_turns.global_fallback = options.fallback;
  params.joint.enabled = options.joint;
  const bool fixed_skip = options.fixed_skip;
  if (fixed_skip) {
    params.sampling.policy = omninav::compass::SamplingPolicy::kFixedSkip;
    params.sampling.fixed_skip_frames = 0;
  }
  {
    omninav::compass::VisualCompass warm_up(params, 0.0);  // plans made before timing
    warm_up.push(CompassFrame(images[0], 0));
    warm_up.push(CompassFrame(images[1], 1));
  }
  std::int64_t frames_done = 0;
  for (auto _ : state) {
    omninav::compass::VisualCompass compass(params, 0.0);
    for (int i = 0; i < kFrames; ++i) {
      benchmark::DoNotOptimize(compass.push(CompassFrame(images[static_cast<std::size_t>(i)], i)));
    }
    frames_done += kFrames;
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frames_done), benchmark::Counter::kIsRate);
}

// Min-warping's joint estimate (compass.yaml's min_warping defaults) on consecutive frames of
// the circle, in steady state: each pair brings one new frame to prepare (reduce, magnify) and
// reuses the previous one's view, as along a sequence; "cold" prepares both.
void min_warping(benchmark::State& state, int width, int height, bool cold) {
  const std::vector<cv::Mat>& images = frames(width, height);
  omninav::PanoramaGeometry geometry;
  const omninav::compass::MinWarping warping({}, geometry);
  omninav::compass::MinWarpingView previous = warping.prepare(images[0], "frame 0");
  int next = 1;
  for (auto _ : state) {
    const cv::Mat& image = images[static_cast<std::size_t>(next)];
    if (cold) previous = warping.prepare(images[static_cast<std::size_t>(next - 1)], "previous");
    omninav::compass::MinWarpingView current = warping.prepare(image, "current");
    benchmark::DoNotOptimize(warping.estimate(previous, current));
    previous = std::move(current);
    next = next % (kFrames - 1) + 1;
    if (next == 1) previous = warping.prepare(images[0], "frame 0");
  }
  state.counters["pairs_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void register_all() {
  for (const auto& [width, height] : {std::make_pair(360, 45), std::make_pair(1080, 135)}) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    for (const bool mask : {true, false}) {
      const std::string suffix = size + (mask ? "/mask" : "/whole");
      const auto add = [&](const std::string& name, MinimiserKind kind, bool fast) {
        benchmark::RegisterBenchmark(("pair/" + name + "/" + suffix).c_str(), pairs, kind, fast,
                                     width, height, mask)
            ->Unit(benchmark::kMicrosecond);
      };
      add("exhaustive", MinimiserKind::kExhaustive, false);
      add("exhaustive_fast", MinimiserKind::kExhaustive, true);
      add("local_scan", MinimiserKind::kLocalScan, false);
      add("fft", MinimiserKind::kFft, false);
      add("fft_measure", MinimiserKind::kFft, true);
    }
    for (const bool cold : {false, true}) {
      benchmark::RegisterBenchmark(((cold ? "min_warping_cold/" : "min_warping/") + size).c_str(),
                                   min_warping, width, height, cold)
          ->Unit(benchmark::kMicrosecond);
    }
    for (const auto& [name, kind] : {std::make_pair("local_scan", MinimiserKind::kLocalScan),
                                     std::make_pair("fft", MinimiserKind::kFft)}) {
      benchmark::RegisterBenchmark(("algorithm1/" + std::string(name) + "/" + size).c_str(),
                                   algorithm1, kind, width, height, Alg1Options{})
          ->Unit(benchmark::kMicrosecond);
    }
    // The global fallback's cost: without it (the local scan alone), and on the fast circle with
    // and without it.
    const auto add_alg1 = [&](const std::string& name, Alg1Options options) {
      benchmark::RegisterBenchmark((name + "/local_scan/" + size).c_str(), algorithm1,
                                   MinimiserKind::kLocalScan, width, height, options)
          ->Unit(benchmark::kMicrosecond);
    };
    add_alg1("algorithm1_no_fallback", {.fallback = false});
    // The joint rotation's cost: min-warping on the pairs that show parallax.
    add_alg1("algorithm1_no_joint", {.joint = false});
    add_alg1("algorithm1_fast", {.fast = true});
    add_alg1("algorithm1_fast_no_fallback", {.fallback = false, .fast = true});
    benchmark::RegisterBenchmark(("fx0/fft/" + size).c_str(), algorithm1, MinimiserKind::kFft,
                                 width, height, Alg1Options{.fixed_skip = true})
        ->Unit(benchmark::kMicrosecond);
  }
}

// Keeps every run's time per iteration, then prints the ratios asked for (speed-ups of the
// minimisers).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      // CPU seconds per iteration: on a shared machine the wall-clock time also counts the time
      // other processes held the core, which differs between the runs a ratio compares.
      seconds_[run.benchmark_name()] =
          run.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
    }
    ConsoleReporter::ReportRuns(runs);
  }

  void print_ratios() const {
    std::printf("\nRatios from this run (CPU time per pair or frame; higher = faster):\n");
    for (const char* size : {"360x45", "1080x135"}) {
      for (const char* mask : {"mask", "whole"}) {
        const std::string suffix = std::string(size) + "/" + mask;
        const double oracle = get("pair/exhaustive/" + suffix);
        const double fast = get("pair/exhaustive_fast/" + suffix);
        const double local = get("pair/local_scan/" + suffix);
        const double fft = get("pair/fft/" + suffix);
        const double fft_measure = get("pair/fft_measure/" + suffix);
        if (oracle <= 0 || fft <= 0) continue;
        std::printf("  %-15s fft vs exhaustive (oracle) %6.1fx (FFTW_MEASURE plans: %6.1fx)",
                    suffix.c_str(), oracle / fft, fft_measure > 0 ? oracle / fft_measure : 0.0);
        if (fast > 0) std::printf(" | fft vs exhaustive_fast %5.1fx", fast / fft);
        if (local > 0) std::printf(" | local_scan %6.0f pairs/s", 1.0 / local);
        std::printf(" | fft %5.0f pairs/s\n", 1.0 / fft);
      }
      const double alg1_local = get(std::string("algorithm1/local_scan/") + size);
      const double alg1_fft = get(std::string("algorithm1/fft/") + size);
      if (alg1_local > 0 && alg1_fft > 0) {
        std::printf("  %-15s Algorithm 1: local_scan %8.0f frames/s, fft %8.0f frames/s\n", size,
                    kFrames / alg1_local, kFrames / alg1_fft);
      }
      const double warping = get(std::string("min_warping/") + size);
      const double warping_cold = get(std::string("min_warping_cold/") + size);
      if (warping > 0) {
        std::printf("  %-15s min-warping %8.0f pairs/s (both frames prepared: %8.0f)", size,
                    1.0 / warping, warping_cold > 0 ? 1.0 / warping_cold : 0.0);
        if (alg1_local > 0) {
          std::printf(" beside Algorithm 1 (local_scan) %8.0f frames/s", kFrames / alg1_local);
        }
        std::printf("\n");
      }
      const double no_fallback = get(std::string("algorithm1_no_fallback/local_scan/") + size);
      const double fast = get(std::string("algorithm1_fast/local_scan/") + size);
      const double fast_no_fallback =
          get(std::string("algorithm1_fast_no_fallback/local_scan/") + size);
      if (alg1_local > 0 && no_fallback > 0) {
        std::printf("  %-15s global fallback: circle %8.0f frames/s (%.2fx the local scan alone)",
                    size, kFrames / alg1_local, no_fallback / alg1_local);
        if (fast > 0 && fast_no_fallback > 0) {
          std::printf(", fast circle %8.0f frames/s (%.2fx)", kFrames / fast,
                      fast_no_fallback / fast);
        }
        std::printf("\n");
      }
    }
  }

 private:
  double get(const std::string& name) const {
    const auto found = seconds_.find(name);
    return found == seconds_.end() ? -1.0 : found->second;
  }
  std::map<std::string, double> seconds_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_all();
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print_ratios();
  benchmark::Shutdown();
  return 0;
}
