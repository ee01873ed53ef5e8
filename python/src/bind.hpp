#pragma once
// What the binding files of the Python module share: the numpy conversions of images and
// matrices, and one function per topic that adds its classes to the module.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "omninav/config/config_folder.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::io {
class PanoramaInput;
}

namespace omninav::python {

namespace py = pybind11;

// An H x W (one channel) or H x W x C numpy array viewing `mat`'s pixels without a copy: a
// capsule owning a copy of the cv::Mat header (which shares and keeps alive the pixels) is the
// array's base. 8-bit, 16-bit, 32-bit integer and floating depths.
py::array mat_to_array(const cv::Mat& mat);

// A cv::Mat header over an H x W or H x W x 3 (or x 1) uint8 array's pixels, without a copy
// when its rows are made of packed pixels (any row stride), else over a packed copy kept in
// `keep`. The array (or `keep`) must outlive the Mat. Throws InputError naming `what` for any
// other dtype or shape.
cv::Mat array_to_mat(const py::array& array, const std::string& what, py::object& keep);

// The configuration folder to read when the caller gives none: the OMNINAV_CONFIG_DIR
// environment variable, else the build's share/omninav/config beside the module.
std::filesystem::path config_dir_or_default(const std::optional<std::filesystem::path>& dir);

// The frames of `input` as panoramas, as the commands read them (apps/omninav/app_config.hpp's
// open_panoramas): raw images unwrapped with camera.yaml of `config_dir` when the input says so
// or `unwrap`.
std::unique_ptr<io::PanoramaInput> open_panoramas(const std::filesystem::path& input, bool unwrap,
                                                  const std::optional<std::filesystem::path>& dir,
                                                  bool absolute_sources);

// An object is for one thread at a time (the module's doc says so); a second thread calling
// into it while the first is inside a call (which releases the GIL) gets a UsageError, not a
// crash. Every method of an object with state (Map, Localiser, Compass, the sequences, the
// navigator's map) holds a Busy on it for the length of the call.
class Busy {
 public:
  // UsageError "<what> is in use by another thread ..." when another call holds `object`.
  Busy(const void* object, const char* what);
  ~Busy();
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  const void* object_;
};

// A map as Python holds it: the visual memory and, once opened or saved, the file that keeps it.
struct Map {
  memory::VisualMemory memory;
  std::optional<memory::MapStore> store;
};

// `config`, else navigation.yaml of `config_dir` (or the default folder).
evaluation::NavigationConfig navigation_config(
    const std::optional<evaluation::NavigationConfig>& config,
    const std::optional<std::filesystem::path>& config_dir);

void bind_errors(py::module_& m);
void bind_core(py::module_& m);
void bind_config(py::module_& m);
void bind_io(py::module_& m);
void bind_compass(py::module_& m);
void bind_signature(py::module_& m);
void bind_memory(py::module_& m);
void bind_sim(py::module_& m);
// Adds the navigator to the module and Map.navigate_to_image (bind_memory calls it).
void bind_navigation(py::module_& m, py::class_<Map>& map);

}  // namespace omninav::python
