// The renderer (world, pose -> panorama) for ground-truth experiments: the generated world
// families of worlds.yaml or a Wavefront .obj file, and the trajectories `omninav render` takes.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>

#include "bind.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::python {
namespace {

// A world and the rendering parameters it was loaded with (worlds.yaml's render section, with
// camera.yaml's panorama geometry).
struct World {
  sim::World world;
  sim::RenderParams render;
};

}  // namespace

void bind_sim(py::module_& m) {
  py::class_<World>(m, "World",
                    "A world to render: a family of worlds.yaml with optional keys "
                    "(\"room\", \"room:seed=3,boxes=12\", \"house:seed=2\", \"field\", "
                    "\"office\") or a .obj file, with camera.yaml's panorama size unless "
                    "width_px/height_px say otherwise.")
      .def(py::init([](const std::string& spec, std::optional<std::filesystem::path> config_dir,
                       int width_px, int height_px, int rays_per_pixel) {
             const std::filesystem::path dir = config_dir_or_default(config_dir);
             PanoramaGeometry panorama = config::load_camera_config(dir).panorama;
             if (width_px > 0) panorama.width_px = width_px;
             if (height_px > 0) panorama.height_px = height_px;
             sim::WorldsConfig worlds = config::load_worlds_config(dir, panorama);
             if (rays_per_pixel > 0) worlds.render.rays_per_pixel = rays_per_pixel;
             py::gil_scoped_release release;
             return std::make_unique<World>(World{sim::load_world(spec, worlds), worlds.render});
           }),
           py::arg("spec") = "room", py::arg("config_dir") = py::none(), py::arg("width_px") = 0,
           py::arg("height_px") = 0, py::arg("rays_per_pixel") = 0)
      .def_property_readonly("name", [](const World& w) { return w.world.name; })
      .def(
          "trajectory",
          [](const World& w, const std::string& spec) {
            std::vector<std::pair<double, CameraPose>> poses;
            for (const sim::TimedPose& p : sim::make_trajectory(spec, w.world).poses)
              poses.emplace_back(p.time_s, p.pose);
            return poses;
          },
          py::arg("spec"),
          "The (time_s, CameraPose) of a trajectory spec as `omninav render --trajectory` "
          "takes it, e.g. \"line:x0=1,y0=1,x1=4,y1=1\", \"circle:radius_m=1\", "
          "\"grid:nx=5,ny=4\", \"tour:lane_m=0.3\" (a coverage planner's tour of the free "
          "space, every room through its doorways).");

  py::class_<sim::Renderer>(m, "Renderer",
                            "Renders panoramas of a World (Embree ray casting): "
                            "render(CameraPose) -> H x W x 3 uint8 BGR.")
      .def(py::init([](const World& world) {
             py::gil_scoped_release release;
             return std::make_unique<sim::Renderer>(world.world, world.render);
           }),
           py::arg("world"))
      .def(
          "render",
          [](const sim::Renderer& renderer, const CameraPose& pose, double time_s,
             int frame_index) {
            cv::Mat panorama;
            {
              py::gil_scoped_release release;
              panorama = renderer.render(pose, time_s, frame_index);
            }
            return mat_to_array(panorama);
          },
          py::arg("pose"), py::arg("time_s") = 0.0, py::arg("frame_index") = 0,
          "The panorama seen from `pose` (time_s places the moving occluder, frame_index seeds "
          "the noise, when worlds.yaml enables them).");
}

}  // namespace omninav::python
