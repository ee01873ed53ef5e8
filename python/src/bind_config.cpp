// Parameters as objects whose fields are the YAML keys of config/*.yaml, loaded by the library's
// own readers (config/config_folder.hpp), so that a file means the same from Python as from
// the command line. Sections are attributes (config.sampling.threshold_norm_amp is compass.yaml's
// sampling: threshold_norm_amp); keys given in degrees in YAML are radians in C++ and are
// offered under both names.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bind.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::python {
namespace {

constexpr auto section = py::return_value_policy::reference_internal;

void bind_compass_config(py::module_& m) {
  using compass::SamplingParams;
  py::class_<SamplingParams>(m, "SamplingParams", "compass.yaml's sampling section.")
      .def_property(
          "policy",
          [](const SamplingParams& p) {
            return p.policy == compass::SamplingPolicy::kThreshold ? "threshold" : "fixed_skip";
          },
          [](SamplingParams& p, const std::string& policy) {
            if (policy != "threshold" && policy != "fixed_skip") {
              throw UsageError("sampling.policy " + policy + ": expected threshold or fixed_skip");
            }
            p.policy = policy == "threshold" ? compass::SamplingPolicy::kThreshold
                                             : compass::SamplingPolicy::kFixedSkip;
          },
          "threshold (Algorithm 1) or fixed_skip (\"Fx n\").")
      .def_readwrite("threshold_norm_amp", &SamplingParams::threshold_norm_amp,
                     "t of Algorithm 1 (Table 2: 0.6055).")
      .def_readwrite("fixed_skip_frames", &SamplingParams::fixed_skip_frames,
                     "n of \"Fx n\": frames skipped between references.")
      .def_readwrite("max_reference_rotation_rad", &SamplingParams::max_reference_rotation_rad,
                     "The rotation cap (0: the paper's Algorithm 1).")
      .def_property(
          "max_reference_rotation_deg",
          [](const SamplingParams& p) { return rad_to_deg(p.max_reference_rotation_rad); },
          [](SamplingParams& p, double deg) { p.max_reference_rotation_rad = deg_to_rad(deg); },
          "The same cap in degrees, as the YAML key.")
      .def_readwrite("parallax_step_ratio", &SamplingParams::parallax_step_ratio,
                     "The pair shows parallax when its minimum is above this times the "
                     "reference's distance to itself rolled by one column.");

  py::class_<compass::MinimiserParams>(m, "MinimiserParams", "compass.yaml's minimiser section.")
      .def_property(
          "kind", [](const compass::MinimiserParams& p) { return compass::to_string(p.kind); },
          [](compass::MinimiserParams& p, const std::string& kind) {
            p.kind = compass::minimiser_kind_of(kind);
          },
          "local_scan, exhaustive, fft or phase.");

  py::class_<compass::CompassConfig>(
      m, "CompassConfig",
      "config/compass.yaml: the visual compass's parameters. CompassConfig.load(config_dir) "
      "reads the file as `omninav compass` does; CompassConfig() has the defaults of Table 2.")
      .def(py::init<>())
      .def_static(
          "load",
          [](const std::optional<std::filesystem::path>& config_dir) {
            return config::load_compass_config(config_dir_or_default(config_dir));
          },
          py::arg("config_dir") = py::none(),
          "Reads <config_dir>/compass.yaml. Raises ConfigError "
          "naming the file and key.")
      .def_property_readonly(
          "sampling", [](compass::CompassConfig & c) -> auto& { return c.compass.sampling; },
          section)
      .def_property_readonly(
          "minimiser",
          [](compass::CompassConfig & c) -> auto& { return c.compass.matcher.minimiser; }, section)
      .def_property(
          "global_fallback",
          [](const compass::CompassConfig& c) { return c.compass.fast_turns.global_fallback; },
          [](compass::CompassConfig& c, bool on) { c.compass.fast_turns.global_fallback = on; },
          "minimiser.global_fallback: search every shift where the local scan's match is "
          "below t (fast turns); False: the local scan alone, as Algorithm 1.")
      .def_readwrite("width_px", &compass::CompassConfig::width_px,
                     "input.width_px: resample every panorama to this many columns first; None: "
                     "the input's own width.");
}

void bind_memory_config(py::module_& m) {
  using signature::SignatureParams;
  py::class_<SignatureParams>(m, "SignatureParams", "memory.yaml's signature section.")
      .def(py::init<>())
      .def_readwrite("components", &SignatureParams::components,
                     "m, Fourier components kept per line.")
      .def_property(
          "colour", [](const SignatureParams& p) { return signature::to_string(p.colour); },
          [](SignatureParams& p, const std::string& colour) {
            p.colour = signature::colour_mode_from_string(colour);
          },
          "luminance or per_channel.")
      .def_readwrite("normalise_brightness", &SignatureParams::normalise_brightness);

  using memory::ExplorationParams;
  py::class_<ExplorationParams>(m, "ExplorationParams", "memory.yaml's exploration section.")
      .def_readwrite("new_place_dissimilarity", &ExplorationParams::new_place_dissimilarity)
      .def_readwrite("new_place_plateau_share", &ExplorationParams::new_place_plateau_share)
      .def_readwrite("every_n_frames", &ExplorationParams::every_n_frames)
      .def_readwrite("every_m", &ExplorationParams::every_m)
      .def_readwrite("thumbnail_width_px", &ExplorationParams::thumbnail_width_px)
      .def_property(
          "heading_source",
          [](const ExplorationParams& p) { return memory::to_string(p.heading_source); },
          [](ExplorationParams& p, const std::string& source) {
            p.heading_source = memory::heading_policy_from_string(source);
          },
          "auto, compass, truth or none.")
      .def_readwrite("motion_components", &ExplorationParams::motion_components);

  using memory::LocalisationParams;
  py::class_<LocalisationParams>(m, "LocalisationParams", "memory.yaml's localisation section.")
      .def_property(
          "levels", [](const LocalisationParams& p) { return p.hierarchy.levels; },
          [](LocalisationParams& p, const std::vector<int>& levels) {
            p.hierarchy.levels = levels;
          },
          "Components compared at each level, coarse to fine, e.g. [2, 5, 15].")
      .def_property(
          "candidate_similarity",
          [](const LocalisationParams& p) { return p.hierarchy.candidate_similarity; },
          [](LocalisationParams& p, double v) { p.hierarchy.candidate_similarity = v; })
      .def_property(
          "max_probes", [](const LocalisationParams& p) { return p.hierarchy.max_probes; },
          [](LocalisationParams& p, int v) { p.hierarchy.max_probes = v; })
      .def_readwrite("top_k", &LocalisationParams::top_k)
      .def_readwrite("fine_candidates", &LocalisationParams::fine_candidates,
                     "Best places re-ranked by the fine level (0 = off).")
      .def_readwrite("fine_rotational_weight", &LocalisationParams::fine_rotational_weight,
                     "The rotational term's weight in the fine level's score.");

  py::class_<memory::MemoryConfig>(
      m, "MemoryConfig",
      "config/memory.yaml: signature, exploration and localisation parameters. "
      "MemoryConfig.load(config_dir) reads it as `omninav explore` and `omninav localise` do "
      "(exploration's compass from compass.yaml).")
      .def(py::init<>())
      .def_static(
          "load",
          [](const std::optional<std::filesystem::path>& config_dir) {
            const std::filesystem::path dir = config_dir_or_default(config_dir);
            memory::MemoryConfig config = config::load_memory_config(dir);
            config::use_compass_config(dir, config.exploration);
            return config;
          },
          py::arg("config_dir") = py::none(),
          "Reads <config_dir>/memory.yaml (and compass.yaml for the exploration's compass). "
          "Raises ConfigError naming the file and key.")
      .def_property_readonly(
          "signature", [](memory::MemoryConfig & c) -> auto& { return c.map.signature; }, section)
      .def_property(
          "weights", [](const memory::MemoryConfig& c) { return c.map.weights.alpha; },
          [](memory::MemoryConfig& c, const std::vector<double>& alpha) {
            c.map.weights.alpha = alpha;
          },
          "signature.weights: alpha_k of Eq. 6, the last repeating.")
      .def_readwrite("exploration", &memory::MemoryConfig::exploration)
      .def_readwrite("localisation", &memory::MemoryConfig::localisation);
}

void bind_navigation_config(py::module_& m) {
  using navigation::RouteParams;
  py::class_<RouteParams>(m, "RouteParams", "navigation.yaml's route section.")
      .def_readwrite("match_dissimilarity_ratio", &RouteParams::match_dissimilarity_ratio)
      .def_readwrite("goal_shortlist_ratio", &RouteParams::goal_shortlist_ratio);

  using navigation::LinkParams;
  py::class_<LinkParams>(
      m, "LinkParams",
      "lattice.yaml's links section: the confirmed links of the lattice and the plan.")
      .def_readwrite("grid_agreement_ratio", &LinkParams::grid_agreement_ratio)
      .def_readwrite("grid_direction_deg", &LinkParams::grid_direction_deg)
      .def_readwrite("revisit_run", &LinkParams::revisit_run)
      .def_readwrite("revisit_ratio", &LinkParams::revisit_ratio)
      .def_readwrite("revisit_image_ratio", &LinkParams::revisit_image_ratio)
      .def_readwrite("revisit_disagreement_deg", &LinkParams::revisit_disagreement_deg)
      .def_readwrite("revisits_per_place", &LinkParams::revisits_per_place)
      .def_readwrite("revisit_candidates", &LinkParams::revisit_candidates)
      .def_readwrite("odometry_noise", &LinkParams::odometry_noise)
      .def_readwrite("neighbour_spacings", &LinkParams::neighbour_spacings);

  using navigation::BeliefParams;
  py::class_<BeliefParams>(m, "BeliefParams", "navigation.yaml's belief section.")
      .def_readwrite("view_scale", &BeliefParams::view_scale)
      .def_readwrite("direction_sigma_deg", &BeliefParams::direction_sigma_deg)
      .def_readwrite("uniform_share", &BeliefParams::uniform_share)
      .def_readwrite("confident_share", &BeliefParams::confident_share);

  using navigation::NavigatorParams;
  py::class_<NavigatorParams>(m, "NavigatorParams", "navigation.yaml's navigator section.")
      .def_readwrite("step_m", &NavigatorParams::step_m)
      .def_readwrite("max_steps", &NavigatorParams::max_steps)
      .def_readwrite("home_on_goal_image", &NavigatorParams::home_on_goal_image)
      .def_readwrite("homing_step_m", &NavigatorParams::homing_step_m)
      .def_readwrite("homing_stop_m", &NavigatorParams::homing_stop_m)
      .def_readwrite("homing_step_spacings", &NavigatorParams::homing_step_spacings)
      .def_readwrite("homing_stop_spacings", &NavigatorParams::homing_stop_spacings)
      .def_readwrite("homing_max_steps", &NavigatorParams::homing_max_steps);

  using evaluation::NavigationConfig;
  py::class_<NavigationConfig>(
      m, "NavigationConfig",
      "config/navigation.yaml's route, belief and navigator sections and lattice.yaml's links, "
      "read as `omninav route` and "
      "`omninav navigate` read them (its robot and trials sections are the simulator's).")
      .def(py::init<>())
      .def_static(
          "load",
          [](const std::optional<std::filesystem::path>& config_dir) {
            return config::load_navigation_config(config_dir_or_default(config_dir));
          },
          py::arg("config_dir") = py::none(),
          "Reads <config_dir>/navigation.yaml and lattice.yaml's links. Raises ConfigError naming "
          "the "
          "file and key.")
      .def_readwrite("route", &NavigationConfig::route)
      .def_readwrite("links", &NavigationConfig::links)
      .def_readwrite("belief", &NavigationConfig::belief)
      .def_readwrite("navigator", &NavigationConfig::navigator);
}

}  // namespace

evaluation::NavigationConfig navigation_config(
    const std::optional<evaluation::NavigationConfig>& config,
    const std::optional<std::filesystem::path>& config_dir) {
  return config ? *config : config::load_navigation_config(config_dir_or_default(config_dir));
}

void bind_config(py::module_& m) {
  bind_compass_config(m);
  bind_memory_config(m);
  bind_navigation_config(m);
}

}  // namespace omninav::python
