// Reading sequences (a folder of images, a video, a BoB database, a CSV of images with poses)
// as iterables of frames with poses, and unwrapping raw omnidirectional images.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>

#include "bind.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/io/image_file.hpp"
#include "omninav/io/panorama_input.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/omni/unwrap.hpp"

namespace omninav::python {
namespace {

// The next frame of `reader` (decoding without the GIL), or StopIteration.
template <typename Reader>
io::Frame next_frame(Reader& reader) {
  const Busy busy(&reader, "this sequence");
  std::optional<io::Frame> frame;
  {
    py::gil_scoped_release release;
    frame = reader.next();
  }
  if (!frame) throw py::stop_iteration();
  return std::move(*frame);
}

// camera.yaml's unwrap section of `config_dir` (or the default folder).
omni::UnwrapParams unwrap_params(const std::optional<std::filesystem::path>& config_dir) {
  return config::load_camera_config(config_dir_or_default(config_dir)).unwrap;
}

void bind_frame(py::module_& m) {
  py::class_<io::Frame>(m, "Frame",
                        "One image of a sequence: index, capture time (s) when known, the image "
                        "(numpy, BGR or grey, sharing the frame's pixels), the ground-truth "
                        "CameraPose when known, and the file (or video#frame n) it came from.")
      .def(py::init([](const py::array& image, int index, std::optional<CameraPose> truth,
                       std::optional<double> time_s, std::string source) {
             py::object keep;
             if (truth) check_pose(*truth, source.empty() ? "Frame truth" : source);
             return io::Frame{index,
                              time_s,
                              array_to_mat(image, "Frame image", keep).clone(),
                              truth,
                              std::move(source),
                              std::nullopt};
           }),
           py::arg("image"), py::arg("index") = 0, py::arg("truth") = py::none(),
           py::arg("time_s") = py::none(), py::arg("source") = "",
           "A frame of your own (e.g. from your robot or simulator); the image is copied.")
      .def_readwrite("index", &io::Frame::index)
      .def_readwrite("time_s", &io::Frame::time_s)
      .def_property(
          "truth", [](const io::Frame& f) { return f.truth; },
          [](io::Frame& f, const std::optional<CameraPose>& truth) {
            // The bound every pose source passes (core/parse.hpp), as the readers of files do.
            if (truth) check_pose(*truth, f.source.empty() ? "Frame truth" : f.source);
            f.truth = truth;
          },
          "The ground-truth CameraPose, or None. InputError for a position beyond ±1e7 m or a "
          "value that is not finite.")
      .def_readwrite("source", &io::Frame::source)
      .def_readwrite("odometry", &io::Frame::odometry,
                     "What the robot's own odometry measured (a CameraPose), when the source "
                     "records it (a rendered database with odometry_noise, a CSV's odometry_* "
                     "columns, a bag's pose topic)")
      .def_property(
          "image", [](const io::Frame& f) { return mat_to_array(f.image); },
          [](io::Frame& f, const py::array& image) {
            py::object keep;
            f.image =
                array_to_mat(image, f.source.empty() ? "Frame image" : f.source, keep).clone();
          },
          "The pixels as a numpy array (H x W x 3 uint8 BGR or H x W), without a copy.")
      .def("__repr__", [](const io::Frame& f) {
        return py::str("Frame(index={}, source='{}', {}x{}x{}{})")
            .format(f.index, f.source, f.image.rows, f.image.cols, f.image.channels(),
                    f.truth ? ", with truth" : "");
      });
}

}  // namespace

std::unique_ptr<io::PanoramaInput> open_panoramas(const std::filesystem::path& input, bool unwrap,
                                                  const std::optional<std::filesystem::path>& dir,
                                                  bool absolute_sources) {
  return std::make_unique<io::PanoramaInput>(
      input, [dir] { return unwrap_params(dir); },
      io::PanoramaInputOptions{.force_unwrap = unwrap, .absolute_sources = absolute_sources});
}

void bind_io(py::module_& m) {
  bind_frame(m);

  py::class_<io::SequenceReader>(
      m, "Sequence",
      "The frames of an input as read, one at a time: `for frame in omninav.open_sequence(path)`.")
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", [](io::SequenceReader& reader) { return next_frame(reader); })
      .def("__len__", &io::SequenceReader::size,
           "How many frames the sequence holds (for a video, what its container says).")
      .def("describe", &io::SequenceReader::describe)
      .def_property_readonly("needs_unwrapping", &io::SequenceReader::needs_unwrapping)
      .def_property_readonly("is_grid", &io::SequenceReader::is_grid)
      .def_property_readonly("is_video", &io::SequenceReader::is_video);

  m.def("open_sequence", &io::open_sequence, py::arg("path"),
        "Opens a folder of images (natural order), a BoB robotics database folder, a CSV of "
        "file,x_m,y_m,heading_deg or a video, as a Sequence of Frames. Raises InputError naming "
        "the file.");

  py::class_<io::PanoramaInput>(
      m, "Panoramas",
      "The frames of an input as panoramas, as every omninav command reads them: raw "
      "omnidirectional images are unwrapped with camera.yaml's unwrap section when the input "
      "says so (a BoB database with needsUnwrapping) or unwrap=True.")
      .def(py::init(&open_panoramas), py::arg("input"), py::arg("unwrap") = false,
           py::arg("config_dir") = py::none(), py::arg("absolute_sources") = true)
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", [](io::PanoramaInput& input) { return next_frame(input); })
      .def("__len__", &io::PanoramaInput::size)
      .def("describe", &io::PanoramaInput::describe)
      .def_property_readonly("is_grid", &io::PanoramaInput::is_grid)
      .def_property_readonly("unwraps", &io::PanoramaInput::unwraps);

  m.def(
      "read_image",
      [](const std::filesystem::path& file) {
        cv::Mat image;
        {
          py::gil_scoped_release release;
          image = io::read_image(file);
        }
        return mat_to_array(image);
      },
      py::arg("file"),
      "Reads an image file as H x W x 3 uint8 BGR, as every omninav reader does. Raises "
      "InputError naming the file.");

  py::class_<omni::Unwrapper>(
      m, "Unwrapper",
      "Unwraps raw omnidirectional images into panoramas with camera.yaml's unwrap section; the "
      "mirror is found in the first raw image when the section does not place it.")
      .def(py::init([](const py::array& first_raw, std::optional<std::filesystem::path> dir) {
             py::object keep;
             const cv::Mat raw = array_to_mat(first_raw, "raw image", keep);
             const omni::UnwrapParams params = unwrap_params(dir);
             py::gil_scoped_release release;
             return omni::make_unwrapper(params, raw);
           }),
           py::arg("first_raw"), py::arg("config_dir") = py::none())
      .def(
          "unwrap",
          [](const omni::Unwrapper& unwrapper, const py::array& raw) {
            py::object keep;
            const cv::Mat image = array_to_mat(raw, "raw image", keep);
            cv::Mat panorama;
            {
              py::gil_scoped_release release;
              panorama = unwrapper.unwrap(image);
            }
            return mat_to_array(panorama);
          },
          py::arg("raw"), "The panorama of a raw image of the same size as the first.")
      .def_property_readonly("panorama_size", [](const omni::Unwrapper& u) {
        return py::make_tuple(u.panorama_size().height, u.panorama_size().width);
      });
}

}  // namespace omninav::python
