// config/compass.yaml: the shipped defaults are Table 2's, and the loader is strict.
#include "omninav/compass/compass_config.hpp"

#include <gtest/gtest.h>

#include "omninav/compass/compass_run.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "support/shared_data.hpp"

namespace omninav::compass {
namespace {

CompassConfig load(const ConfigReader& config) {
  CompassConfig out;
  load_compass_config(config, out);
  config.require_all_known();
  return out;
}

// The shipped file gives exactly the defaults of the Params structs, which are Table 2's.
TEST(CompassConfig, ShippedFileHoldsTheTable2Defaults) {
  const CompassConfig shipped =
      load(ConfigReader::from_file(omninav::testing::config_dir() / "compass.yaml"));
  const PairMatcherParams& matcher = shipped.compass.matcher;
  EXPECT_EQ(matcher.distance.metric, Metric::kL2);
  EXPECT_TRUE(matcher.distance.field_of_view.front_back);
  EXPECT_NEAR(rad_to_deg(matcher.distance.field_of_view.band_width_rad), 60.0, 1e-12);
  EXPECT_EQ(matcher.minimiser.kind, MinimiserKind::kLocalScan);
  EXPECT_EQ(matcher.minimiser.scan_values, 8);
  EXPECT_NEAR(rad_to_deg(matcher.minimiser.scan_span_rad), 20.0, 1e-12);
  EXPECT_EQ(matcher.subpixel.mode, SubpixelMode::kMixture);
  EXPECT_EQ(shipped.compass.sampling.policy, SamplingPolicy::kThreshold);
  EXPECT_EQ(shipped.compass.sampling.threshold_norm_amp, 0.6055);
  EXPECT_FALSE(shipped.width_px.has_value());

  const CompassConfig defaults;
  EXPECT_EQ(matcher.minimiser.phase.components,
            defaults.compass.matcher.minimiser.phase.components);
  EXPECT_EQ(shipped.compass.sampling.fixed_skip_frames,
            defaults.compass.sampling.fixed_skip_frames);
  EXPECT_NEAR(shipped.compass.sampling.max_reference_rotation_rad,
              defaults.compass.sampling.max_reference_rotation_rad, 1e-12);
  EXPECT_EQ(shipped.compass.sampling.parallax_step_ratio,
            defaults.compass.sampling.parallax_step_ratio);
  EXPECT_EQ(shipped.compass.fast_turns.global_fallback,
            defaults.compass.fast_turns.global_fallback);
  EXPECT_EQ(matcher.confidence.flat_below_grey,
            defaults.compass.matcher.confidence.flat_below_grey);
  EXPECT_NEAR(matcher.confidence.competing_separation_rad,
              defaults.compass.matcher.confidence.competing_separation_rad, 1e-12);
  EXPECT_EQ(matcher.confidence.competing_depth_ratio,
            defaults.compass.matcher.confidence.competing_depth_ratio);
  EXPECT_EQ(matcher.subpixel.parabolic_up_to_norm_amp,
            defaults.compass.matcher.subpixel.parabolic_up_to_norm_amp);
  EXPECT_EQ(matcher.subpixel.linear_from_norm_amp,
            defaults.compass.matcher.subpixel.linear_from_norm_amp);
}

TEST(CompassConfig, ReadsEveryKey) {
  const CompassConfig read = load(ConfigReader::from_string(
      "distance: {metric: l2, field_of_view: whole, band_width_deg: 90}\n"
      "minimiser: {kind: fft, scan_values: 6, scan_span_deg: 30, "
      "fft_planning: measure, global_fallback: false}\n"
      "phase: {components: 4}\n"
      "subpixel: {mode: parabolic, parabolic_up_to_norm_amp: 0.4, linear_from_norm_amp: 0.9}\n"
      "sampling: {policy: fixed_skip, threshold_norm_amp: 0.7, fixed_skip_frames: 5, "
      "max_reference_rotation_deg: 4, parallax_step_ratio: 0.1}\n"
      "confidence: {flat_below_grey: 2, competing_separation_deg: 5, competing_depth_ratio: 0.2}\n"
      "input: {width_px: 1080}\n",
      "compass.yaml"));
  EXPECT_FALSE(read.compass.matcher.distance.field_of_view.front_back);
  EXPECT_EQ(read.compass.matcher.minimiser.kind, MinimiserKind::kFft);
  EXPECT_EQ(read.compass.matcher.minimiser.fft_planning, FftPlanning::kMeasure);
  EXPECT_FALSE(read.compass.fast_turns.global_fallback);
  EXPECT_EQ(read.compass.matcher.minimiser.phase.components, 4);
  EXPECT_EQ(read.compass.matcher.subpixel.mode, SubpixelMode::kParabolic);
  EXPECT_EQ(read.compass.sampling.policy, SamplingPolicy::kFixedSkip);
  EXPECT_EQ(read.compass.sampling.fixed_skip_frames, 5);
  EXPECT_NEAR(read.compass.sampling.max_reference_rotation_rad, 4.0 * kPi / 180.0, 1e-12);
  EXPECT_EQ(read.compass.sampling.parallax_step_ratio, 0.1);
  EXPECT_EQ(read.width_px, 1080);
}

TEST(CompassConfig, RejectsUnknownKeysBadValuesAndImpossibleCombinations) {
  const auto message_of = [](const std::string& yaml) -> std::string {
    try {
      load(ConfigReader::from_string(yaml, "compass.yaml"));
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(message_of("sampling: {threshold: 0.6}\n").find("sampling.threshold"),
            std::string::npos);
  EXPECT_NE(message_of("sampling: {threshold_norm_amp: 1.6}\n").find("threshold_norm_amp"),
            std::string::npos);
  EXPECT_NE(message_of("minimiser: {kind: newton}\n").find("minimiser.kind"), std::string::npos);
  // A removed rule's key (the much deeper minimum, docs/evaluation.md "The rules between minima,
  // re-chosen with the joint rotation") is refused, not silently ignored.
  EXPECT_NE(message_of("minimiser: {global_deeper_ratio: 0.6}\n").find("global_deeper_ratio"),
            std::string::npos);
  EXPECT_NE(
      message_of("sampling: {max_reference_rotation_deg: -1}\n").find("max_reference_rotation_deg"),
      std::string::npos);
  EXPECT_NE(message_of("distance: {metric: l1}\nminimiser: {kind: fft}\n").find("l2"),
            std::string::npos);
  EXPECT_NE(message_of("input: {width_px: 360.5}\n").find("width_px"), std::string::npos);
  EXPECT_NE(message_of("input: {width_px: 360.5}\n").find("compass.yaml"), std::string::npos);
  EXPECT_FALSE(load(ConfigReader::from_string("input: {width_px: ~}\n", "c.yaml")).width_px);
}

// The ranges live in the Params structs' check(), which the algorithms call too: a value set in
// code, as Python's writable fields set it, is refused by the compass as the YAML loader refuses
// it in a file, naming the same key (the loader adds the file).
TEST(CompassConfig, AValueSetInCodeIsRefusedAsTheLoaderRefusesIt) {
  const auto refusal = [](const auto& make) -> std::string {
    try {
      make();
    } catch (const UsageError& error) {
      return error.what();
    }
    return "";
  };
  CompassParams sampling;
  sampling.sampling.threshold_norm_amp = 1.6;
  EXPECT_NE(refusal([&] { VisualCompass compass(sampling); }).find("sampling.threshold_norm_amp"),
            std::string::npos);
  EXPECT_NE(refusal([&] { CompassRun run(sampling, std::nullopt); }).find("threshold_norm_amp"),
            std::string::npos);
  PairMatcherParams matcher;
  matcher.confidence.competing_separation_rad = deg_to_rad(200.0);
  EXPECT_NE(refusal([&] { PairMatcher pairs(matcher); }).find("competing_separation_deg"),
            std::string::npos);
  matcher = {};
  matcher.minimiser.kind = MinimiserKind::kFft;
  matcher.distance.metric = Metric::kL1;
  EXPECT_NE(refusal([&] { PairMatcher pairs(matcher); }).find("l2"), std::string::npos);
  MinWarpingParams warping;
  warping.scale_planes = 8;
  EXPECT_NE(refusal([&] { MinWarping w(warping, PanoramaGeometry{}); }).find("scale_planes"),
            std::string::npos);
  // The same value in a file: a ConfigError naming the file and the key.
  try {
    load(ConfigReader::from_string("sampling: {threshold_norm_amp: 1.6}\n", "compass.yaml"));
    ADD_FAILURE() << "1.6 was accepted";
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("compass.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find("sampling.threshold_norm_amp"), std::string::npos) << message;
  }
  // The bounds themselves pass, degrees through radians included.
  CompassParams bounds;
  bounds.sampling.max_reference_rotation_rad = deg_to_rad(180.0);
  bounds.matcher.minimiser.scan_span_rad = deg_to_rad(0.1);
  EXPECT_NO_THROW(bounds.check());
}

}  // namespace
}  // namespace omninav::compass
