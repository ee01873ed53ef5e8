// numpy <-> cv::Mat, poses, and the panorama's column convention.
#include <dlfcn.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <cstdlib>
#include <map>
#include <mutex>
#include <unordered_set>
#include <vector>

#include "bind.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/pose.hpp"

namespace omninav::python {
namespace {

py::dtype dtype_of_depth(int depth) {
  switch (depth) {
    case CV_8U:
      return py::dtype::of<std::uint8_t>();
    case CV_8S:
      return py::dtype::of<std::int8_t>();
    case CV_16U:
      return py::dtype::of<std::uint16_t>();
    case CV_16S:
      return py::dtype::of<std::int16_t>();
    case CV_32S:
      return py::dtype::of<std::int32_t>();
    case CV_32F:
      return py::dtype::of<float>();
    case CV_64F:
      return py::dtype::of<double>();
    default:
      throw UsageError("an image of OpenCV depth " + std::to_string(depth) + " for numpy");
  }
}

std::string shape_text(const py::array& array) {
  std::string text;
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text += (i ? " x " : "") + std::to_string(array.shape(i));
  }
  return text.empty() ? "a scalar" : text;
}

}  // namespace

py::array mat_to_array(const cv::Mat& mat) {
  if (mat.empty()) return py::array(py::dtype::of<std::uint8_t>(), std::vector<py::ssize_t>{0, 0});
  auto* owner = new cv::Mat(mat);  // shares the pixels: their reference count keeps them
  py::capsule base(owner, [](void* header) { delete static_cast<cv::Mat*>(header); });
  const auto element = static_cast<py::ssize_t>(mat.elemSize());
  const auto component = static_cast<py::ssize_t>(mat.elemSize1());
  std::vector<py::ssize_t> shape{mat.rows, mat.cols};
  std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(mat.step[0]), element};
  if (mat.channels() > 1) {
    shape.push_back(mat.channels());
    strides.push_back(component);
  }
  return py::array(dtype_of_depth(mat.depth()), shape, strides, owner->data, base);
}

namespace {

// The order of the channels of the colour arrays Python hands in (set_channel_order).
std::atomic<ChannelOrder> g_channel_order{ChannelOrder::kBgr};

}  // namespace

cv::Mat array_to_mat(const py::array& array, const std::string& what, py::object& keep) {
  const bool shape_ok =
      array.ndim() == 2 || (array.ndim() == 3 && (array.shape(2) == 1 || array.shape(2) == 3));
  if (!shape_ok || !array.dtype().is(py::dtype::of<std::uint8_t>()) || array.size() == 0) {
    throw InputError(what + ": expected an H x W (grey) or H x W x 3 (BGR) uint8 array, got " +
                     shape_text(array) + " of " + py::str(array.dtype()).cast<std::string>());
  }
  const int channels = array.ndim() == 3 ? static_cast<int>(array.shape(2)) : 1;
  const bool packed = array.strides(1) == channels &&
                      (array.ndim() == 2 || array.strides(2) == 1) && array.strides(0) > 0;
  py::array pixels = array;
  if (!packed) {
    pixels = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(array);
    // ensure() gives a null array (its Python error cleared) when the packed copy cannot be
    // made: numpy could not allocate it.
    if (!pixels) throw std::bad_alloc();  // MemoryError in Python
    keep = pixels;
  }
  const cv::Mat view(static_cast<int>(pixels.shape(0)), static_cast<int>(pixels.shape(1)),
                     CV_8UC(channels), const_cast<void*>(pixels.data()),
                     static_cast<std::size_t>(pixels.strides(0)));
  return to_bgr(view, g_channel_order.load());  // RGB: a BGR copy that owns its pixels
}

namespace {

// The objects inside a call now, under their mutex.
std::mutex g_busy_mutex;
std::unordered_set<const void*> g_busy_objects;

}  // namespace

Busy::Busy(const void* object, const char* what) : object_(object) {
  const std::lock_guard<std::mutex> lock(g_busy_mutex);
  if (!g_busy_objects.insert(object).second) {
    throw UsageError(std::string(what) +
                     " is in use by another thread: an object is for one thread at a time "
                     "(give each thread its own, or share it under a lock)");
  }
}

Busy::~Busy() {
  const std::lock_guard<std::mutex> lock(g_busy_mutex);
  g_busy_objects.erase(object_);
}

// The configuration folder inside the package: omninav/config beside the compiled module, as
// `pip install` and `cmake --install` lay it out and as the build tree links it (python/
// CMakeLists.txt). Found from the module's own file at run time (dladdr), so that the module
// holds no path of the machine it was built on and works wherever it is copied.
std::filesystem::path package_config_dir() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&package_config_dir), &info) == 0 ||
      info.dli_fname == nullptr) {
    throw ConfigError(
        "cannot find the omninav module's own file to locate its configuration folder; set "
        "OMNINAV_CONFIG_DIR");
  }
  return std::filesystem::path(info.dli_fname).parent_path() / "config";
}

std::filesystem::path config_dir_or_default(const std::optional<std::filesystem::path>& dir) {
  if (dir) return *dir;
  if (const char* env = std::getenv("OMNINAV_CONFIG_DIR"); env && *env) return env;
  return package_config_dir();
}

void bind_core(py::module_& m) {
  py::class_<Pose2>(m, "Pose2",
                    "A robot's pose on the floor: metres, heading counter-clockwise "
                    "from +x (REP 103), radians.")
      .def(py::init([](double x_m, double y_m, double heading_rad) {
             return Pose2{x_m, y_m, heading_rad};
           }),
           py::arg("x_m") = 0.0, py::arg("y_m") = 0.0, py::arg("heading_rad") = 0.0)
      .def_readwrite("x_m", &Pose2::x_m)
      .def_readwrite("y_m", &Pose2::y_m)
      .def_readwrite("heading_rad", &Pose2::heading_rad)
      .def("__repr__", [](const Pose2& p) {
        return py::str("Pose2(x_m={}, y_m={}, heading_rad={})").format(p.x_m, p.y_m, p.heading_rad);
      });

  py::class_<CameraPose>(m, "CameraPose",
                         "A camera's full pose in the world: x, y on the floor, z up (metres); "
                         "heading (yaw about +z), pitch and roll in radians, REP 103.")
      .def(py::init([](double x_m, double y_m, double z_m, double heading_rad, double pitch_rad,
                       double roll_rad) {
             return CameraPose{x_m, y_m, z_m, heading_rad, pitch_rad, roll_rad};
           }),
           py::arg("x_m") = 0.0, py::arg("y_m") = 0.0, py::arg("z_m") = 0.0,
           py::arg("heading_rad") = 0.0, py::arg("pitch_rad") = 0.0, py::arg("roll_rad") = 0.0)
      .def_readwrite("x_m", &CameraPose::x_m)
      .def_readwrite("y_m", &CameraPose::y_m)
      .def_readwrite("z_m", &CameraPose::z_m)
      .def_readwrite("heading_rad", &CameraPose::heading_rad)
      .def_readwrite("pitch_rad", &CameraPose::pitch_rad)
      .def_readwrite("roll_rad", &CameraPose::roll_rad)
      .def("on_floor", &CameraPose::on_floor, "The Pose2 on the floor (x, y, heading).")
      .def("__repr__", [](const CameraPose& p) {
        return py::str(
                   "CameraPose(x_m={}, y_m={}, z_m={}, heading_rad={}, pitch_rad={}, "
                   "roll_rad={})")
            .format(p.x_m, p.y_m, p.z_m, p.heading_rad, p.pitch_rad, p.roll_rad);
      });

  m.def("azimuth_of_column", &azimuth_of_column, py::arg("column"), py::arg("width_px"),
        "Azimuth relative to the robot (counter-clockwise, 0 ahead) of a panorama column, in "
        "(-pi, pi]: the front is at column 0.25*W.");
  m.def("column_of_azimuth", &column_of_azimuth, py::arg("azimuth_rad"), py::arg("width_px"),
        "The column, in [0, W), that looks along azimuth_rad relative to the robot.");
  m.def(
      "roll_columns",
      [](const py::array& panorama, int shift_px) {
        py::object keep;
        const cv::Mat image = array_to_mat(panorama, "panorama", keep);
        return mat_to_array(roll_columns(image, shift_px));
      },
      py::arg("panorama"), py::arg("shift_px"),
      "The panorama the robot sees after turning counter-clockwise by shift_px*2*pi/W on the "
      "spot: columns rolled circularly by shift_px.");
  m.def(
      "set_log_level",
      [](const std::string& level) {
        static const std::map<std::string, LogLevel> levels{{"error", LogLevel::kError},
                                                            {"warning", LogLevel::kWarning},
                                                            {"info", LogLevel::kInfo},
                                                            {"debug", LogLevel::kDebug}};
        const auto found = levels.find(level);
        if (found == levels.end()) {
          throw UsageError("log level " + level + ": expected error, warning, info or debug");
        }
        set_log_level(found->second);
      },
      py::arg("level"),
      "How much the library writes to stderr: error, warning, info (the default) or debug "
      "(the command line's --quiet is error).");
  m.def(
      "set_channel_order",
      [](const std::string& order) { g_channel_order = channel_order_of(order, "channel order"); },
      py::arg("order"),
      "The order of the channels of the colour images you hand omninav: \"bgr\" (the default, "
      "OpenCV's) or \"rgb\" (PIL, imageio, matplotlib). Images omninav returns stay BGR.");
  m.def(
      "channel_order", [] { return std::string(to_string(g_channel_order.load())); },
      "The order set by set_channel_order: \"bgr\" or \"rgb\".");
  m.def(
      "default_config_dir", [] { return config_dir_or_default(std::nullopt); },
      "The configuration folder used when none is given: $OMNINAV_CONFIG_DIR, else the "
      "package's own config/ folder (installed with it).");
}

}  // namespace omninav::python
