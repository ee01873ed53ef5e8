// The visual memory's speed and size. Targets on one core: ≤ 20 µs per 360×45
// signature; ≤ 10 ms per query at 100,000 places.
// Run: build/bin/signature_bench   (one core: taskset -c 1 build/bin/signature_bench; the
// signature alone: --benchmark_filter=signature_time --benchmark_repetitions=5; the motion fit,
// fast and line by line, and the phase heading it starts from: --benchmark_filter=motion)
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <random>

#include "../../libs/signature/src/fast_math.hpp"
#include "../../libs/signature/src/low_frequency_dft.hpp"
#include "../../libs/signature/src/panorama_lines.hpp"
#include "../../libs/signature/src/warp_fit.hpp"
#include "../signature/direct_phase_heading.hpp"
#include "../signature/direct_warp_fit.hpp"
#include "../signature/rendered_room.hpp"
#include "../signature/synthetic_signatures.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/signature/hierarchy.hpp"
#include "omninav/signature/motion.hpp"
#include "omninav/signature/phase_heading.hpp"
#include "omninav/signature/signature.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"

namespace {

using namespace omninav;
using signature::ColourMode;

cv::Mat rendered_panorama(int width, int height) {
  static const sim::World world = sim::make_room({});
  sim::RenderParams params;
  params.geometry.width_px = width;
  params.geometry.height_px = height;
  const sim::Renderer renderer(world, params);
  return renderer.render(CameraPose{2.2, 1.9, 1.0, 0.4, 0.0, 0.0});
}

// Signature time per panorama: colour conversion, the transform of every row, magnitudes,
// phases. The fast path (the default) and, as its baseline in the same run, the reference path
// (cv::cvtColor, FFTW, the C library's atan2; the tests' oracle).
void signature_time(benchmark::State& state, int width, int height, ColourMode mode,
                    signature::SignaturePath path) {
  const cv::Mat panorama = rendered_panorama(width, height);
  signature::SignatureExtractor extractor({15, mode}, path);
  for (auto _ : state) benchmark::DoNotOptimize(extractor.compute(panorama));
  state.counters["rows_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * height, benchmark::Counter::kIsRate);
}
constexpr auto kFast = signature::SignaturePath::kFast;
constexpr auto kReference = signature::SignaturePath::kReference;
BENCHMARK_CAPTURE(signature_time, 360x45_luminance, 360, 45, ColourMode::kLuminance, kFast)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 360x45_luminance_reference, 360, 45, ColourMode::kLuminance,
                  kReference)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 360x45_per_channel, 360, 45, ColourMode::kPerChannel, kFast)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 360x45_per_channel_reference, 360, 45, ColourMode::kPerChannel,
                  kReference)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 720x80_luminance, 720, 80, ColourMode::kLuminance, kFast)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 720x80_luminance_reference, 720, 80, ColourMode::kLuminance,
                  kReference)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 720x80_per_channel, 720, 80, ColourMode::kPerChannel, kFast)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_time, 720x80_per_channel_reference, 720, 80, ColourMode::kPerChannel,
                  kReference)
    ->Unit(benchmark::kMicrosecond);

// The fast path's stages for a 360×45 panorama (the library's internals, as in
// tests/signature/fast_path_test.cpp), for the breakdown in docs/memory.md. As in compute(),
// each stage works on one line (or one batch of lines) at a time in small buffers that stay in
// the L1 cache; whole-image buffers would make the stages look slower than they are together.
void signature_stage(benchmark::State& state, int stage) {
  const cv::Mat panorama = rendered_panorama(360, 45);
  const int width = panorama.cols, rows = panorama.rows, m = 15;
  const signature::detail::LowFrequencyDft dft(width, m);
  const int batch = signature::detail::LowFrequencyDft::kMaxLines;
  std::vector<float> line(static_cast<std::size_t>(width));
  std::vector<float> folded(static_cast<std::size_t>(batch) * width);
  std::vector<float> re(static_cast<std::size_t>(rows) * m), im(re.size());
  std::vector<float> magnitude(re.size()), phase(re.size());
  for (int j = 0; j < batch; ++j) {
    signature::detail::load_line(panorama, ColourMode::kLuminance, 20 + j, line.data());
    dft.fold(line.data(), folded.data() + static_cast<std::size_t>(j) * width);
  }
  for (auto _ : state) {
    switch (stage) {
      case 0:  // every row's luminance, into one line buffer
        for (int y = 0; y < rows; ++y) {
          signature::detail::load_line(panorama, ColourMode::kLuminance, y, line.data());
          benchmark::ClobberMemory();
        }
        break;
      case 1:  // folding 45 lines
        for (int y = 0; y < rows; ++y) {
          dft.fold(line.data(), folded.data() + static_cast<std::size_t>(y % batch) * width);
          benchmark::ClobberMemory();
        }
        break;
      case 2:  // the first 15 components of 45 folded lines, a batch at a time
        for (int first = 0; first < rows; first += batch) {
          dft.transform_folded(folded.data(), std::min(batch, rows - first), re.data() + first * m,
                               im.data() + first * m);
        }
        break;
      default:  // 675 magnitudes and phases
        signature::detail::to_polar(re.data(), im.data(), re.size(), 1.0f / width, magnitude.data(),
                                    phase.data());
        break;
    }
    benchmark::ClobberMemory();
  }
}
BENCHMARK_CAPTURE(signature_stage, 360x45_luminance_rows, 0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_stage, 360x45_fold, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_stage, 360x45_first_15_components, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(signature_stage, 360x45_magnitudes_and_phases, 3)->Unit(benchmark::kMicrosecond);

// N synthetic places on a 30 cm grid (synthetic_signatures.hpp), 45 rows, m = 15, built once
// per (N, channels).
struct Places {
  std::unique_ptr<signature::testing::SyntheticPlaces> field;
  std::unique_ptr<signature::SignatureIndex> index;
  double side_m = 0.0;
};

const Places& places(std::size_t n, int channels) {
  static std::map<std::pair<std::size_t, int>, Places> cache;
  Places& p = cache[{n, channels}];
  if (!p.index) {
    const int per_side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    p.side_m = 0.3 * per_side;
    p.field = std::make_unique<signature::testing::SyntheticPlaces>(p.side_m, 45, channels, 15, 7);
    p.index = std::make_unique<signature::SignatureIndex>(45, channels, std::vector<int>{2, 5, 15});
    p.index->reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      p.index->add(p.field->at(0.3 * (i % per_side), 0.3 * (i / per_side)));
    }
  }
  return p;
}

// One query (noisy signature at a random position between places), coarse to fine, with the
// default threshold (memory.yaml: 800). Counters: candidates kept per level.
void query_time(benchmark::State& state, bool exhaustive, int channels) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const Places& p = places(n, channels);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(0.0, p.side_m - 0.3);
  std::vector<signature::Signature> queries;
  for (int i = 0; i < 64; ++i) {
    queries.push_back(p.field->at(coordinate(random), coordinate(random), &random, 1.0));
  }
  std::size_t q = 0;
  double level0 = 0, level1 = 0, level2 = 0;
  for (auto _ : state) {
    const signature::SearchResult r =
        exhaustive ? p.index->search_exhaustive(queries[q % queries.size()], 800.0, 5)
                   : p.index->search(queries[q % queries.size()], 800.0, 5);
    level0 += r.levels[0].candidates.size();
    level1 += r.levels[1].candidates.size();
    level2 += r.levels[2].candidates.size();
    benchmark::DoNotOptimize(r);
    ++q;
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["candidates_m2"] = level0 / iterations;
  state.counters["candidates_m5"] = level1 / iterations;
  state.counters["candidates_m15"] = level2 / iterations;
  state.counters["index_bytes_per_place"] = static_cast<double>(p.index->bytes()) / n;
}
BENCHMARK_CAPTURE(query_time, pruned_luminance, false, 1)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(query_time, exhaustive_luminance, true, 1)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(query_time, pruned_per_channel, false, 3)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);

// A query through memory::Localiser on a map of N synthetic places (as query_time's), as the
// papers (`papers`: memory.yaml's defaults, no fine level) or with the fine level over the best
// 10 (fine_candidates 10): the cost of the fine level per query, in one run. The map (magnitudes
// and phases) and both localisers are built once per (N, papers).
void localiser_query_time(benchmark::State& state, bool papers) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  static std::map<std::size_t, std::unique_ptr<memory::VisualMemory>> maps;
  static std::map<std::pair<std::size_t, bool>, std::unique_ptr<memory::Localiser>> localisers;
  const int per_side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const signature::testing::SyntheticPlaces field(0.3 * per_side, 45, 1, 15, 7);
  std::unique_ptr<memory::VisualMemory>& map = maps[n];
  if (!map) {
    map = std::make_unique<memory::VisualMemory>();
    for (std::size_t i = 0; i < n; ++i) {
      memory::Place place;
      place.signature = field.at(0.3 * (i % per_side), 0.3 * (i / per_side));
      map->add_place(std::move(place));
    }
  }
  std::unique_ptr<memory::Localiser>& localiser = localisers[{n, papers}];
  if (!localiser) {
    memory::LocalisationParams params;
    params.fine_candidates = papers ? 0 : 10;
    localiser = std::make_unique<memory::Localiser>(*map, params);
  }
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(0.0, 0.3 * (per_side - 1));
  std::vector<signature::Signature> queries;
  for (int i = 0; i < 64; ++i) {
    queries.push_back(field.at(coordinate(random), coordinate(random), &random, 1.0));
  }
  std::size_t q = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(localiser->localise(queries[q++ % queries.size()]));
  }
}
BENCHMARK_CAPTURE(localiser_query_time, papers, true)
    ->Arg(1000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(localiser_query_time, fine_level, false)
    ->Arg(1000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);

// The motion between two places (motion.hpp) on 16 pairs of rendered 360×45 places 5-45 cm
// apart with turns, m = 15: estimate_motion() and, as its baseline in the same run, the same
// fit evaluated line by line (the tests' oracle, as estimate_motion() was before
// warp_fit.hpp's identity); one evaluation of the m = 15 fit each way; and the phase heading
// that estimate_motion() starts from, the part of it that is not the fit.
const std::vector<std::pair<signature::Signature, signature::Signature>>& motion_pairs() {
  static const auto pairs = [] {
    std::vector<std::pair<signature::Signature, signature::Signature>> made;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> x(1.0, 5.0), y(1.0, 4.0), angle(-180.0, 180.0),
        turn(-30.0, 30.0), step(0.05, 0.45);
    signature::SignatureExtractor extractor({15, ColourMode::kLuminance});
    while (made.size() < 16) {
      const double x0 = x(random), y0 = y(random), direction = deg_to_rad(angle(random));
      const double d = step(random), h0 = angle(random);
      const double x1 = x0 + d * std::cos(direction), y1 = y0 + d * std::sin(direction);
      if (!signature::testing::room().is_free(x0, y0, 0.2) ||
          !signature::testing::room().is_free(x1, y1, 0.2)) {
        continue;
      }
      made.emplace_back(extractor.compute(signature::testing::render(x0, y0, h0)),
                        extractor.compute(signature::testing::render(x1, y1, h0 + turn(random))));
    }
    return made;
  }();
  return pairs;
}

void motion_estimate(benchmark::State& state, bool line_by_line) {
  const auto& pairs = motion_pairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [from, to] = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(line_by_line ? signature::testing::direct_estimate_motion(from, to, 15)
                                          : signature::estimate_motion(from, to));
  }
}
BENCHMARK_CAPTURE(motion_estimate, fast, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(motion_estimate, line_by_line, true)->Unit(benchmark::kMicrosecond);

void motion_evaluation(benchmark::State& state, bool line_by_line) {
  const auto& [from, to] = motion_pairs().front();
  const signature::detail::LineSums sums(from, to, 15);
  const signature::detail::WarpFit fast(sums, 15);
  const signature::testing::DirectWarpFit direct(from, to, 15);
  const signature::detail::WarpObjective& objective =
      line_by_line ? static_cast<const signature::detail::WarpObjective&>(direct) : fast;
  const Eigen::Vector3d p(signature::relative_heading(from, to).turn_rad, -0.05, 0.03);
  for (auto _ : state) benchmark::DoNotOptimize(objective.evaluate(p));
}
BENCHMARK_CAPTURE(motion_evaluation, fast, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(motion_evaluation, line_by_line, true)->Unit(benchmark::kMicrosecond);

// The phase heading and, as its baseline in the same run, the computation it replaced (one
// std::polar per coefficient and per term of the correlation; the tests' oracle).
void motion_phase_heading(benchmark::State& state, bool direct) {
  const auto& pairs = motion_pairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [from, to] = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(direct ? signature::testing::direct_relative_heading(from, to)
                                    : signature::relative_heading(from, to));
  }
}
BENCHMARK_CAPTURE(motion_phase_heading, fast, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(motion_phase_heading, direct, true)->Unit(benchmark::kMicrosecond);

// Bytes per place in memory (VisualMemory: signature, thumbnail, graph; plus the search index)
// and on disk (the .vmem file), for a map of rendered places.
void bytes_per_place(benchmark::State& state, ColourMode mode) {
  static const sim::World world = sim::make_room({});
  sim::RenderParams params;
  const sim::Renderer renderer(world, params);
  memory::MapParameters parameters;
  parameters.signature.colour = mode;
  memory::VisualMemory map(parameters);
  memory::Explorer explorer(map, {}, "bench", "signature_bench");
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    io::Frame frame;
    frame.index = i;
    frame.image = renderer.render(CameraPose{1.0 + 0.01 * i, 2.0, 1.0, 0.02 * i, 0, 0});
    frame.truth = CameraPose{1.0 + 0.01 * i, 2.0, 1.0, 0.02 * i, 0, 0};
    frame.source = "/some/folder/image_" + std::to_string(i) + ".png";
    explorer.add_place(frame);
  }
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("signature_bench_" + std::to_string(::getpid()) + ".vmem");
  for (auto _ : state) {
    std::filesystem::remove(file);
    memory::MapStore(file).save(map, {.overwrite = true, .after_place = {}});
  }
  signature::SignatureIndex index(45, mode == ColourMode::kLuminance ? 1 : 3, {2, 5, 15});
  for (int i = 0; i < n; ++i) index.add(map.place(static_cast<std::size_t>(i)).signature);
  std::size_t thumbnails = 0;
  for (int i = 0; i < n; ++i)
    thumbnails += map.place(static_cast<std::size_t>(i)).thumbnail_png.size();
  state.counters["memory_bytes_per_place"] = static_cast<double>(map.bytes()) / n;
  state.counters["index_bytes_per_place"] = static_cast<double>(index.bytes()) / n;
  state.counters["thumbnail_bytes_per_place"] = static_cast<double>(thumbnails) / n;
  state.counters["disk_bytes_per_place"] =
      static_cast<double>(std::filesystem::file_size(file)) / n;
  std::filesystem::remove(file);
}
BENCHMARK_CAPTURE(bytes_per_place, luminance, ColourMode::kLuminance)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(bytes_per_place, per_channel, ColourMode::kPerChannel)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
