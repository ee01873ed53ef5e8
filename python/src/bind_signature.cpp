// Fourier signatures of panoramas and their dissimilarities (Menegatti et al. 2004, §2): the
// magnitudes and phases are numpy views of the signature's own storage (no copy).
#include <pybind11/stl.h>

#include <memory>

#include "bind.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::python {
namespace {

using signature::Signature;

// lines x components float32 view of `values`, kept alive by the Python Signature `self`.
py::array values_view(py::object self, std::vector<float> Signature::*values) {
  Signature& s = self.cast<Signature&>();
  const auto components = static_cast<py::ssize_t>(s.components);
  return py::array_t<float>({static_cast<py::ssize_t>(s.lines()), components},
                            {components * static_cast<py::ssize_t>(sizeof(float)),
                             static_cast<py::ssize_t>(sizeof(float))},
                            (s.*values).data(), self);
}

}  // namespace

void bind_signature(py::module_& m) {
  py::class_<Signature>(
      m, "Signature",
      "A panorama's Fourier signature: per line (a row of one channel) the magnitudes and "
      "phases of its first `components` Fourier components. magnitude and phase_rad are "
      "lines x components float32 arrays viewing the signature's storage.")
      .def_readonly("rows", &Signature::rows)
      .def_readonly("channels", &Signature::channels)
      .def_readonly("components", &Signature::components)
      .def_readonly("width_px", &Signature::width_px)
      .def_property_readonly("lines", &Signature::lines)
      .def_property_readonly(
          "magnitude", [](py::object self) { return values_view(self, &Signature::magnitude); },
          "|F_y(k)|, grey levels, lines x components.")
      .def_property_readonly(
          "phase_rad", [](py::object self) { return values_view(self, &Signature::phase_rad); },
          "arg F_y(k), radians in (-pi, pi], lines x components.")
      .def("truncated", &Signature::truncated, py::arg("components"),
           "The same signature with only its first `components` components.")
      .def("__repr__", [](const Signature& s) {
        return py::str("Signature(rows={}, channels={}, components={}, width_px={})")
            .format(s.rows, s.channels, s.components, s.width_px);
      });

  py::class_<signature::SignatureExtractor>(
      m, "SignatureExtractor",
      "Computes signatures of panoramas with the given SignatureParams (memory.yaml's signature "
      "section; a map's own are map.signature_params).")
      .def(py::init([](std::optional<signature::SignatureParams> params) {
             return std::make_unique<signature::SignatureExtractor>(
                 params.value_or(signature::SignatureParams{}));
           }),
           py::arg("params") = py::none())
      .def(
          "compute",
          [](signature::SignatureExtractor& extractor, const py::array& panorama,
             const std::string& what) {
            py::object keep;
            const cv::Mat image = array_to_mat(panorama, what, keep);
            py::gil_scoped_release release;
            return extractor.compute(image, what);
          },
          py::arg("panorama"), py::arg("what") = "panorama",
          "The signature of an H x W x 3 BGR or H x W grey panorama. Raises InputError naming "
          "`what` for a bad image.")
      .def_property_readonly("params", &signature::SignatureExtractor::params);

  m.def(
      "dissimilarity",
      [](const Signature& a, const Signature& b, int components,
         std::optional<std::vector<double>> weights) {
        signature::ComponentWeights alpha;
        if (weights) alpha.alpha = *weights;
        return signature::dissimilarity(a, b, components, alpha);
      },
      py::arg("a"), py::arg("b"), py::arg("components") = -1, py::arg("weights") = py::none(),
      "Eq. 2 (Eq. 6 with weights alpha_k): the L1 distance between the magnitudes of the first "
      "`components` components (-1: all). Raises UsageError when the layouts differ.");
  m.def(
      "similarities",
      [](const std::vector<double>& dissimilarities) {
        return signature::rescale_similarities(dissimilarities);
      },
      py::arg("dissimilarities"),
      "Eq. 3 over a query's dissimilarities to a reference set: 1000 for the best, 0 for the "
      "worst.");
}

}  // namespace omninav::python
