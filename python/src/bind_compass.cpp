// The visual compass (Labrosse 2006): the rotation between two panoramas (PairMatcher), and
// Algorithm 1 as a stateful object fed one frame at a time (Compass), as `omninav compass` runs
// it (compass/compass_run.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <memory>

#include "bind.hpp"
#include "omninav/compass/compass_run.hpp"
#include "omninav/compass/min_warping.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/frame.hpp"

namespace omninav::python {
namespace {

compass::CompassConfig config_or_load(const std::optional<compass::CompassConfig>& config,
                                      const std::optional<std::filesystem::path>& config_dir) {
  return config ? *config : config::load_compass_config(config_dir_or_default(config_dir));
}

// Algorithm 1 over frames pushed one at a time, numbering them when the caller does not.
struct Compass {
  compass::CompassRun run;
  int next_index = 0;

  compass::CompassEstimate push(const py::array& panorama, std::optional<int> index,
                                const std::string& source, std::optional<double> truth_rad) {
    const Busy busy(this, "this Compass");
    if (truth_rad && !std::isfinite(*truth_rad)) {
      throw InputError(source + ": true heading " + std::to_string(*truth_rad) +
                       " rad is not a finite angle");
    }
    const int frame_index = index.value_or(next_index);
    const std::string what = source.empty() ? "frame " + std::to_string(frame_index) : source;
    py::object keep;
    const cv::Mat image = array_to_mat(panorama, what, keep);
    py::gil_scoped_release release;
    compass::CompassEstimate estimate = run.push(image, frame_index, source, truth_rad);
    next_index = frame_index + 1;
    return estimate;
  }
};

template <typename T>
void def_flags(py::class_<T>& c) {
  c.def_property_readonly(
       "confidence", [](const T& r) { return r.flags.describe(); },
       "\"ok\", or the flags joined by '+', e.g. \"featureless+low_amplitude\".")
      .def_property_readonly("featureless", [](const T& r) { return r.flags.featureless; })
      .def_property_readonly("competing_minima",
                             [](const T& r) { return r.flags.competing_minima; })
      .def_property_readonly("low_amplitude", [](const T& r) { return r.flags.low_amplitude; })
      .def_property_readonly("ok", [](const T& r) { return r.flags.ok(); });
}

}  // namespace

void bind_compass(py::module_& m) {
  using compass::CompassEstimate;
  py::class_<CompassEstimate> estimate(
      m, "CompassEstimate",
      "What the compass says about one frame: heading_rad (unwrapped: turns accumulate), "
      "rotation_rad since the previous frame, amplitude_norm (the normalised amplitude of the "
      "pair, 1 for the first frame), the reference frame used, and the confidence.");
  estimate.def_readonly("frame_index", &CompassEstimate::frame_index)
      .def_readonly("heading_rad", &CompassEstimate::heading_rad)
      .def_readonly("rotation_rad", &CompassEstimate::rotation_rad)
      .def_readonly("amplitude_norm", &CompassEstimate::amplitude_norm)
      .def_readonly("reference_index", &CompassEstimate::reference_index)
      .def_readonly("new_reference", &CompassEstimate::new_reference)
      .def_readonly("shift_px", &CompassEstimate::shift_px)
      .def_readonly("evaluations", &CompassEstimate::evaluations)
      .def_readonly("heading_sigma_rad", &CompassEstimate::heading_sigma_rad)
      .def_readonly("realigned", &CompassEstimate::realigned)
      .def("__repr__", [](const CompassEstimate& e) {
        return py::str(
                   "CompassEstimate(frame_index={}, heading_rad={}, amplitude_norm={}, "
                   "confidence='{}')")
            .format(e.frame_index, e.heading_rad, e.amplitude_norm, e.flags.describe());
      });
  def_flags(estimate);

  using compass::PairMatch;
  py::class_<PairMatch> pair(
      m, "PairMatch",
      "The rotation between two panoramas: rotation_rad from the first to the second "
      "(counter-clockwise positive), the integer and sub-pixel shifts, the minimum distance, the "
      "amplitudes (Eqs. 8-12) and the confidence.");
  pair.def_readonly("shift_px", &PairMatch::shift_px)
      .def_readonly("subpixel_shift_px", &PairMatch::subpixel_shift_px)
      .def_readonly("rotation_rad", &PairMatch::rotation_rad)
      .def_readonly("distance_min", &PairMatch::distance_min)
      .def_readonly("amplitude", &PairMatch::amplitude)
      .def_readonly("amplitude_norm", &PairMatch::amplitude_norm)
      .def_readonly("amplitude_norm_px", &PairMatch::amplitude_norm_px)
      .def_readonly("self_amplitude", &PairMatch::self_amplitude)
      .def_readonly("evaluations", &PairMatch::evaluations)
      .def("__repr__", [](const PairMatch& p) {
        return py::str("PairMatch(rotation_rad={}, amplitude_norm={}, confidence='{}')")
            .format(p.rotation_rad, p.amplitude_norm, p.flags.describe());
      });
  def_flags(pair);

  py::class_<compass::PairMatcher>(
      m, "PairMatcher",
      "Measures the rotation between two panoramas of one shape with the distance, minimiser, "
      "sub-pixel fit and confidence of compass.yaml (or of `config`).")
      .def(py::init([](std::optional<compass::CompassConfig> config,
                       std::optional<std::filesystem::path> config_dir) {
             return std::make_unique<compass::PairMatcher>(
                 config_or_load(config, config_dir).compass.matcher);
           }),
           py::arg("config") = py::none(), py::arg("config_dir") = py::none())
      .def(
          "match",
          [](const compass::PairMatcher& matcher, const py::array& first, const py::array& second,
             int start_shift_px) {
            py::object keep_first, keep_second;
            const cv::Mat a = array_to_mat(first, "first panorama", keep_first);
            const cv::Mat b = array_to_mat(second, "second panorama", keep_second);
            py::gil_scoped_release release;
            return matcher.match(compass::CompassFrame(a, 0, "first panorama"),
                                 compass::CompassFrame(b, 1, "second panorama"), start_shift_px);
          },
          py::arg("first"), py::arg("second"), py::arg("start_shift_px") = 0,
          "Matches the second panorama against the first; a local minimiser starts at "
          "start_shift_px. Raises InputError when their shapes differ.");

  using compass::MinWarpingResult;
  py::class_<MinWarpingResult>(
      m, "MinWarpingResult",
      "The joint estimate of min-warping for a pair: rotation_rad (the counter-clockwise turn "
      "from the first panorama to the second), travel_rad (the direction from the first place "
      "to the second in the first panorama's frame), home_rad (from the second place back to "
      "the first, in the second's frame), cost and rotation_only_cost (mean column distances), "
      "featureless (no estimate: the angles are 0).")
      .def_readonly("rotation_rad", &MinWarpingResult::rotation_rad)
      .def_readonly("travel_rad", &MinWarpingResult::travel_rad)
      .def_readonly("home_rad", &MinWarpingResult::home_rad)
      .def_readonly("cost", &MinWarpingResult::cost)
      .def_readonly("rotation_only_cost", &MinWarpingResult::rotation_only_cost)
      .def_readonly("rotation_only_rad", &MinWarpingResult::rotation_only_rad)
      .def_readonly("featureless", &MinWarpingResult::featureless)
      .def("travel_world_rad", &MinWarpingResult::travel_world_rad, py::arg("first_heading_rad"),
           "The direction from the first place to the second in the world, given the first "
           "panorama's heading.")
      .def("__repr__", [](const MinWarpingResult& r) {
        return py::str(
                   "MinWarpingResult(rotation_rad={}, travel_rad={}, home_rad={}, "
                   "featureless={})")
            .format(r.rotation_rad, r.travel_rad, r.home_rad, r.featureless);
      });

  py::class_<compass::MinWarping>(
      m, "MinWarping",
      "Min-warping (Möller 2009; Möller, Krzykawski & Gerstmayr 2010) with compass.yaml's "
      "min_warping section and camera.yaml's row elevations (of config_dir):\n\n"
      "    warping = omninav.MinWarping()\n"
      "    result = warping.estimate(snapshot, current)\n"
      "    print(result.home_rad, result.rotation_rad)")
      .def(py::init([](std::optional<std::filesystem::path> config_dir) {
             const std::filesystem::path dir = config_dir_or_default(config_dir);
             return std::make_unique<compass::MinWarping>(
                 config::load_compass_config(dir).min_warping,
                 config::load_camera_config(dir).panorama);
           }),
           py::arg("config_dir") = py::none())
      .def(
          "estimate",
          [](const compass::MinWarping& warping, const py::array& first, const py::array& second) {
            py::object keep_first, keep_second;
            const cv::Mat a = array_to_mat(first, "first panorama", keep_first);
            const cv::Mat b = array_to_mat(second, "second panorama", keep_second);
            py::gil_scoped_release release;
            return warping.estimate(a, b);
          },
          py::arg("first"), py::arg("second"),
          "The rotation and the travel direction from the first panorama's place to the "
          "second's. Raises InputError when their sizes differ or a pixel is not finite.");

  py::class_<Compass>(
      m, "Compass",
      "Algorithm 1 of Labrosse 2006 (with compass.yaml's sampling policy and rotation cap) fed "
      "one panorama at a time, exactly as `omninav compass` runs it: each panorama resampled to "
      "config.width_px first when set, the compass started at the first frame's true heading "
      "when given, else at 0.\n\n"
      "    compass = omninav.Compass()\n"
      "    for frame in omninav.Panoramas('route_db'):\n"
      "        estimate = compass.push(frame)\n"
      "        print(estimate.heading_rad, estimate.amplitude_norm, estimate.confidence)")
      .def(py::init([](std::optional<compass::CompassConfig> config,
                       std::optional<std::filesystem::path> config_dir) {
             const compass::CompassConfig c = config_or_load(config, config_dir);
             return std::make_unique<Compass>(Compass{compass::CompassRun(c.compass, c.width_px)});
           }),
           py::arg("config") = py::none(), py::arg("config_dir") = py::none(),
           "config: a CompassConfig; None reads compass.yaml from config_dir (None: "
           "omninav.default_config_dir()).")
      .def(
          "push",
          [](Compass& c, const io::Frame& frame) {
            return c.push(
                mat_to_array(frame.image), frame.index, frame.source,
                frame.truth ? std::optional<double>(frame.truth->heading_rad) : std::nullopt);
          },
          py::arg("frame"),
          "Feeds a Frame (its true heading, if any, starts the compass at the first frame).")
      .def("push", &Compass::push, py::arg("panorama"), py::arg("index") = py::none(),
           py::arg("source") = "", py::arg("truth_heading_rad") = py::none(),
           "Feeds the next panorama (numpy, H x W x 3 BGR or H x W) and returns its "
           "CompassEstimate. Raises InputError when its shape differs from the first one's.")
      .def_property_readonly("started",
                             [](const Compass& c) {
                               const Busy busy(&c, "this Compass");
                               return c.run.started();
                             })
      .def_property_readonly(
          "reference_count",
          [](const Compass& c) {
            const Busy busy(&c, "this Compass");
            return c.run.reference_count();
          },
          "How many frames served as a reference (the Nb of Tables 3-4).");
}

}  // namespace omninav::python
