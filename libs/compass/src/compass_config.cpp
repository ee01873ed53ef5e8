#include "omninav/compass/compass_config.hpp"

#include <cmath>
#include <string>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::compass {

void load_compass_config(const ConfigReader& config, CompassConfig& out) {
  PairMatcherParams& matcher = out.compass.matcher;

  const ConfigReader distance = config.section("distance");
  std::string metric = to_string(matcher.distance.metric);
  distance.read("metric", metric, {"l2", "l1"});
  matcher.distance.metric = metric == "l1" ? Metric::kL1 : Metric::kL2;
  std::string field_of_view = matcher.distance.field_of_view.front_back ? "front_back" : "whole";
  distance.read("field_of_view", field_of_view, {"front_back", "whole"});
  matcher.distance.field_of_view.front_back = field_of_view == "front_back";
  distance.read_deg("band_width_deg", matcher.distance.field_of_view.band_width_rad);

  const ConfigReader minimiser = config.section("minimiser");
  std::string kind = to_string(matcher.minimiser.kind);
  minimiser.read("kind", kind, {"local_scan", "exhaustive", "fft", "phase"});
  matcher.minimiser.kind = minimiser_kind_of(kind);
  minimiser.read("scan_values", matcher.minimiser.scan_values);
  minimiser.read_deg("scan_span_deg", matcher.minimiser.scan_span_rad);
  std::string planning =
      matcher.minimiser.fft_planning == FftPlanning::kMeasure ? "measure" : "estimate";
  minimiser.read("fft_planning", planning, {"estimate", "measure"});
  matcher.minimiser.fft_planning =
      planning == "measure" ? FftPlanning::kMeasure : FftPlanning::kEstimate;

  minimiser.read("global_fallback", out.compass.fast_turns.global_fallback);

  const ConfigReader phase = config.section("phase");
  phase.read("components", matcher.minimiser.phase.components);

  const ConfigReader subpixel = config.section("subpixel");
  std::string mode = to_string(matcher.subpixel.mode);
  subpixel.read("mode", mode, {"mixture", "parabolic", "linear", "none"});
  matcher.subpixel.mode = subpixel_mode_of(mode);
  subpixel.read("parabolic_up_to_norm_amp", matcher.subpixel.parabolic_up_to_norm_amp);
  subpixel.read("linear_from_norm_amp", matcher.subpixel.linear_from_norm_amp);

  const ConfigReader sampling = config.section("sampling");
  SamplingParams& sampling_params = out.compass.sampling;
  std::string policy =
      sampling_params.policy == SamplingPolicy::kFixedSkip ? "fixed_skip" : "threshold";
  sampling.read("policy", policy, {"threshold", "fixed_skip"});
  sampling_params.policy =
      policy == "fixed_skip" ? SamplingPolicy::kFixedSkip : SamplingPolicy::kThreshold;
  sampling.read("threshold_norm_amp", sampling_params.threshold_norm_amp);
  sampling.read("fixed_skip_frames", sampling_params.fixed_skip_frames);
  sampling.read_deg("max_reference_rotation_deg", sampling_params.max_reference_rotation_rad);
  sampling.read("parallax_step_ratio", sampling_params.parallax_step_ratio);

  const ConfigReader confidence = config.section("confidence");
  ConfidenceParams& confidence_params = matcher.confidence;
  confidence.read("flat_below_grey", confidence_params.flat_below_grey);
  confidence.read_deg("competing_separation_deg", confidence_params.competing_separation_rad);
  confidence.read("competing_depth_ratio", confidence_params.competing_depth_ratio);

  const ConfigReader uncertainty = config.section("uncertainty");
  uncertainty.read("scale", out.compass.uncertainty.scale);

  const ConfigReader warping = config.section("min_warping");
  MinWarpingParams& mw = out.min_warping;
  warping.read("search_width_px", mw.search_width_px);
  warping.read("search_height_px", mw.search_height_px);
  warping.read("max_relative_distance", mw.max_relative_distance);
  warping.read("max_scale", mw.max_scale);
  warping.read("scale_planes", mw.scale_planes);
  warping.read("distance_samples", mw.distance_samples);
  warping.read("featureless_below_grey", mw.featureless_below_grey);
  warping.read("in_compass", out.compass.joint.enabled);
  out.compass.joint.warping = mw;

  const ConfigReader input = config.section("input");
  std::optional<double> width = out.width_px ? std::optional<double>(*out.width_px) : std::nullopt;
  input.read("width_px", width, 8, 16384);
  if (width && *width != std::floor(*width)) {
    throw ConfigError(config.source_name() + ": key 'input.width_px' = " + std::to_string(*width) +
                      " must be a whole number of columns");
  }
  out.width_px = width ? std::optional<int>(static_cast<int>(*width)) : std::nullopt;

  // The ranges, and the combinations that cannot work, fail here, naming the file.
  check_loaded(config.source_name(), [&] { out.compass.check(); });
  check_loaded(config.source_name(), [&] { out.min_warping.check(); });
}

}  // namespace omninav::compass
