// Maps (the visual memory of Menegatti et al. 2004): create or open, explore frames into,
// localise a query coarse to fine, read places and edges, organise the lattice, plan a route.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "bind.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/evaluation/organised_map.hpp"
#include "omninav/io/panorama_input.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/navigation/memory_places.hpp"
#include "omninav/navigation/route_planner.hpp"

namespace omninav::python {
namespace {

namespace fs = std::filesystem;

memory::MemoryConfig memory_config(const std::optional<memory::MemoryConfig>& config,
                                   const std::optional<fs::path>& config_dir) {
  if (config) return *config;
  const fs::path dir = config_dir_or_default(config_dir);
  memory::MemoryConfig loaded = config::load_memory_config(dir);
  config::use_compass_config(dir, loaded.exploration);
  return loaded;
}

py::object optional_position(const std::optional<Eigen::Vector2d>& p) {
  if (!p) return py::none();
  return py::make_tuple((*p)(0), (*p)(1));
}

void bind_places(py::module_& m) {
  using memory::Place;
  py::class_<Place>(m, "Place",
                    "A place of a map: its signature, its heading (REP 103) and where it came "
                    "from, its ground truth (evaluation only) and lattice position (metres).")
      .def_readonly("signature", &Place::signature)
      .def_readonly("heading_rad", &Place::heading_rad)
      .def_property_readonly("heading_source",
                             [](const Place& p) { return memory::to_string(p.heading_source); })
      .def_readonly("source", &Place::source)
      .def_readonly("frame_index", &Place::frame_index)
      .def_readonly("run", &Place::run)
      .def_readonly("time_s", &Place::time_s)
      .def_readonly("truth", &Place::truth)
      .def_property_readonly(
          "lattice_position", [](const Place& p) { return optional_position(p.lattice_position); },
          "(x_m, y_m) in the lattice's frame, or None before organise().")
      .def_property_readonly(
          "thumbnail",
          [](const Place& p) {
            return mat_to_array(cv::imdecode(p.thumbnail_png, cv::IMREAD_UNCHANGED));
          },
          "The small copy of the panorama stored with the place (BGR).");

  using memory::Edge;
  py::class_<Edge>(m, "Edge",
                   "An edge between places met one after the other: their dissimilarity, "
                   "relative heading and direction of motion from the phases.")
      .def_property_readonly("kind", [](const Edge& e) { return memory::to_string(e.kind); })
      .def_readonly("dissimilarity", &Edge::dissimilarity)
      .def_readonly("relative_heading_rad", &Edge::relative_heading_rad)
      .def_readonly("heading_confidence", &Edge::heading_confidence)
      .def_readonly("motion_bearing_rad", &Edge::motion_bearing_rad)
      .def_readonly("motion_bearing_stddev_rad", &Edge::motion_bearing_stddev_rad)
      .def_readonly("parallax_rad", &Edge::parallax_rad);
}

void bind_localisation(py::module_& m) {
  using memory::PlaceMatch;
  py::class_<PlaceMatch>(m, "PlaceMatch",
                         "One of the best places for a query: its index, the finest level's "
                         "dissimilarity and similarity (0..1000), and the query's heading "
                         "relative to the place.")
      .def_readonly("place", &PlaceMatch::place)
      .def_readonly("dissimilarity", &PlaceMatch::dissimilarity)
      .def_readonly("similarity", &PlaceMatch::similarity)
      .def_readonly("dissimilarity_per_value", &PlaceMatch::dissimilarity_per_value)
      .def_readonly("relative_heading_rad", &PlaceMatch::relative_heading_rad)
      .def_readonly("heading_confidence", &PlaceMatch::heading_confidence)
      .def_readonly("heading_rad", &PlaceMatch::heading_rad)
      .def("__repr__", [](const PlaceMatch& p) {
        return py::str("PlaceMatch(place={}, dissimilarity={}, similarity={})")
            .format(p.place, p.dissimilarity, p.similarity);
      });

  using memory::Localisation;
  py::class_<Localisation>(m, "Localisation",
                           "The result of localising a query: the best places, best first, "
                           "and a position estimate when the places have positions.")
      .def_readonly("best", &Localisation::best)
      .def_property_readonly(
          "candidates_per_level",
          [](const Localisation& l) {
            std::vector<std::vector<std::uint32_t>> levels;
            for (const auto& level : l.search.levels) {
              std::vector<std::uint32_t> places;
              for (const auto& candidate : level.candidates) places.push_back(candidate.place);
              levels.push_back(std::move(places));
            }
            return levels;
          },
          "The candidate places kept at each level, coarse to fine.")
      .def_property_readonly(
          "position_frame",
          [](const Localisation& l) -> py::object {
            if (!l.position) return py::none();
            return py::str(memory::to_string(l.position->frame));
          },
          "\"lattice\" or \"truth\": the frame of position, or None.")
      .def_property_readonly(
          "position",
          [](const Localisation& l) {
            return optional_position(
                l.position ? std::optional<Eigen::Vector2d>(l.position->position) : std::nullopt);
          },
          "The best place's (x_m, y_m), or None.")
      .def_property_readonly(
          "interpolated_position",
          [](const Localisation& l) {
            return optional_position(
                l.position ? std::optional<Eigen::Vector2d>(l.position->interpolated_position)
                           : std::nullopt);
          },
          "The best places' positions weighted by similarity (x_m, y_m), or None.")
      .def_property_readonly(
          "between_places",
          [](const Localisation& l) {
            return optional_position(
                l.position ? std::optional<Eigen::Vector2d>(l.position->between_places)
                           : std::nullopt);
          },
          "The best place and its neighbours among the best, weighted by dissimilarity "
          "(x_m, y_m), or None.");

  // The localiser (which extracts the queries' signatures) and the largest dissimilarity at
  // which a query still matches a place (route, navigate and localise's one criterion).
  struct Localiser {
    memory::Localiser localiser;
    double match_limit;
    const Map* map;  // the map it reads, which must not change meanwhile
  };
  py::class_<Localiser>(m, "Localiser",
                        "Localises queries in a map coarse to fine (memory.yaml's localisation "
                        "section, or `config`). The map must not gain places meanwhile.")
      .def(py::init([](const Map& map, std::optional<memory::MemoryConfig> config,
                       std::optional<fs::path> config_dir,
                       std::optional<evaluation::NavigationConfig> navigation) {
             const Busy busy(&map, "this Map");
             if (map.memory.place_count() == 0) throw InputError("the map has no places");
             const memory::LocalisationParams params =
                 memory_config(config, config_dir).localisation;
             const navigation::RouteParams route = navigation_config(navigation, config_dir).route;
             return std::make_unique<Localiser>(
                 Localiser{memory::Localiser(map.memory, params),
                           navigation::match_limit(map.memory, route), &map});
           }),
           py::arg("map"), py::arg("config") = py::none(), py::arg("config_dir") = py::none(),
           py::arg("navigation") = py::none(), py::keep_alive<1, 2>())
      .def(
          "localise",
          [](Localiser& l, const py::array& panorama, bool exhaustive, const std::string& what) {
            const Busy busy(&l, "this Localiser");
            const Busy map_busy(l.map, "its Map");
            py::object keep;
            const cv::Mat image = array_to_mat(panorama, what, keep);
            py::gil_scoped_release release;
            const signature::Signature query = l.localiser.signature_of(image, what);
            return exhaustive ? l.localiser.localise_exhaustive(query)
                              : l.localiser.localise(query);
          },
          py::arg("panorama"), py::arg("exhaustive") = false, py::arg("what") = "query",
          "Localises a query panorama (numpy): pruned coarse to fine, or every place at every "
          "level when exhaustive.")
      .def(
          "localise_signature",
          [](const Localiser& l, const signature::Signature& query, bool exhaustive) {
            const Busy busy(&l, "this Localiser");
            const Busy map_busy(l.map, "its Map");
            py::gil_scoped_release release;
            return exhaustive ? l.localiser.localise_exhaustive(query)
                              : l.localiser.localise(query);
          },
          py::arg("signature"), py::arg("exhaustive") = false)
      .def_property_readonly(
          "match_limit", [](const Localiser& l) { return l.match_limit; },
          "The largest mean dissimilarity per value at which a query still matches a place: "
          "navigation.yaml's route.match_dissimilarity_ratio x the median of the map's links.")
      .def(
          "no_match_reason",
          [](const Localiser& l, const Localisation& localisation) {
            return navigation::no_match_reason(localisation, l.match_limit);
          },
          py::arg("localisation"),
          "Why the localisation matches no place of the map (as `omninav localise`, `route` "
          "and `navigate` say it), or None when it matches its best place.");
}

void bind_route(py::module_& m) {
  using navigation::RoutePlan;
  py::class_<RoutePlan>(m, "RoutePlan",
                        "Directions from every place to a goal over the map's confirmed links "
                        "(Menegatti et al. 2004, §3.5).")
      .def_readonly("goal", &RoutePlan::goal)
      .def_readonly("next", &RoutePlan::next, "The place to go to next; -1 at the goal or none.")
      .def_readonly("cost_m", &RoutePlan::cost_m)
      .def_readonly("direction_rad", &RoutePlan::direction_rad,
                    "Towards next, in the lattice frame.")
      .def_readonly("direction_in_place_rad", &RoutePlan::direction_in_place_rad,
                    "Towards next, relative to the place's heading.")
      .def("reaches_goal", &RoutePlan::reaches_goal, py::arg("place"))
      .def("route_from", &RoutePlan::route_from, py::arg("start"),
           "The places from start to the goal, both included; empty when none.");
}

}  // namespace

void bind_memory(py::module_& m) {
  bind_places(m);

  py::class_<memory::Run>(m, "Run", "One exploration into a map.")
      .def_readonly("id", &memory::Run::id)
      .def_readonly("input", &memory::Run::input)
      .def_readonly("frames", &memory::Run::frames)
      .def_readonly("places", &memory::Run::places)
      .def_property_readonly("heading_source", [](const memory::Run& r) {
        return memory::to_string(r.heading_source);
      });

  py::class_<Map> map(m, "Map",
                      "A visual memory: places (signatures of reference panoramas) and edges. "
                      "Map(config) makes an empty one with memory.yaml's signature parameters; "
                      "Map.open(file) reads a .vmem map.");
  map.def(py::init(
              [](std::optional<memory::MemoryConfig> config, std::optional<fs::path> config_dir) {
                return std::make_unique<Map>(
                    Map{memory::VisualMemory(memory_config(config, config_dir).map), std::nullopt});
              }),
          py::arg("config") = py::none(), py::arg("config_dir") = py::none())
      .def_static(
          "open",
          [](const fs::path& file) {
            auto map = std::make_unique<Map>(Map{memory::VisualMemory(), memory::MapStore(file)});
            py::gil_scoped_release release;
            map->memory = map->store->load();
            return map;
          },
          py::arg("file"), "Reads a map file. Raises InputError naming it when it is no map.")
      .def(
          "save",
          [](Map& map, std::optional<fs::path> file, bool overwrite) {
            const Busy busy(&map, "this Map");
            if (file && (!map.store || map.store->file() != *file)) map.store.emplace(*file);
            if (!map.store) throw UsageError("save(): the map has no file yet; give one");
            py::gil_scoped_release release;
            map.store->save(map.memory, {.overwrite = overwrite, .after_place = {}});
          },
          py::arg("file") = py::none(), py::arg("overwrite") = false,
          "Writes the map (to `file`, else where it was opened or last saved): a new file "
          "whole, an existing one by appending what changed; overwrite replaces it.")
      .def(
          "explore",
          [](Map& map, py::object input, std::optional<memory::MemoryConfig> config,
             std::optional<fs::path> config_dir, bool all_frames, bool unwrap) {
            const Busy busy(&map, "this Map");
            const memory::ExplorationParams params = memory_config(config, config_dir).exploration;
            if (py::isinstance<py::str>(input) || py::hasattr(input, "__fspath__")) {
              const fs::path path = input.cast<fs::path>();
              py::gil_scoped_release release;
              const std::unique_ptr<io::PanoramaInput> frames =
                  open_panoramas(path, unwrap, config_dir, true);
              return memory::explore_frames(map.memory, params,
                                            {.name = path.string(),
                                             .is_grid = frames->is_grid(),
                                             .all_frames = all_frames,
                                             .frame_count = frames->size(),
                                             .grid_spacing_m = frames->grid_spacing_m(),
                                             .next = [&frames] { return frames->next(); }});
            }
            py::iterator frames = py::iter(input);
            int count = 0;
            py::gil_scoped_release release;
            return memory::explore_frames(
                map.memory, params,
                {.name = "python frames",
                 .is_grid = false,
                 .all_frames = all_frames,
                 .frame_count = 0,
                 .grid_spacing_m = std::nullopt,
                 .next = [&frames, &count]() -> std::optional<io::Frame> {
                   py::gil_scoped_acquire acquire;
                   if (frames == py::iterator::sentinel()) return std::nullopt;
                   py::handle item = *frames;
                   io::Frame frame = py::isinstance<io::Frame>(item)
                                         ? item.cast<io::Frame>()
                                         : io::Frame{count,
                                                     std::nullopt,
                                                     cv::Mat(),
                                                     std::nullopt,
                                                     "frame " + std::to_string(count),
                                                     std::nullopt};
                   if (frame.image.empty()) {
                     py::object keep;
                     frame.image = array_to_mat(item.cast<py::array>(), frame.source, keep).clone();
                   }
                   ++frames;
                   ++count;
                   return frame;
                 }});
          },
          py::arg("input"), py::arg("config") = py::none(), py::arg("config_dir") = py::none(),
          py::arg("all_frames") = false, py::arg("unwrap") = false,
          "Explores frames into a new run of the map, as `omninav explore` does: `input` is a "
          "path (folder, video, BoB database, CSV) or an iterable of Frames or panoramas "
          "(numpy). A frame becomes a place by memory.yaml's exploration rules (all_frames: "
          "every frame). Returns the Run.")
      .def(
          "organise",
          [](Map& map, double step_m, bool motion_constraints, std::optional<fs::path> config_dir) {
            const Busy busy(&map, "this Map");
            lattice::OrganiseParams params =
                config::load_lattice_config(config_dir_or_default(config_dir));
            if (step_m > 0.0) params.step_m = step_m;
            if (!motion_constraints) params.motion_constraints = false;
            py::gil_scoped_release release;
            lattice::organise(map.memory, params);
          },
          py::arg("step_m") = 0.0, py::arg("motion_constraints") = true,
          py::arg("config_dir") = py::none(),
          "Places the places on the spring-model lattice (lattice.yaml), as `omninav organise` "
          "does; their lattice_position is then set. step_m > 0: the distance between "
          "consecutive places (--step-m), needed when the exploration did not measure it.")
      .def(
          "plan_route",
          [](const Map& map, int goal, std::optional<evaluation::NavigationConfig> config,
             std::optional<fs::path> config_dir) {
            const Busy busy(&map, "this Map");
            const navigation::LinkParams params = navigation_config(config, config_dir).links;
            return navigation::plan_route(map.memory, navigation::places_from_memory(map.memory),
                                          params, goal);
          },
          py::arg("goal"), py::arg("config") = py::none(), py::arg("config_dir") = py::none(),
          "Directions from every place to place `goal`, over the map's confirmed links "
          "(travelled, grid neighbours, revisits; navigation.yaml's links section).")
      .def("__len__",
           [](const Map& map) {
             const Busy busy(&map, "this Map");
             return map.memory.place_count();
           })
      .def_property_readonly("place_count",
                             [](const Map& map) {
                               const Busy busy(&map, "this Map");
                               return map.memory.place_count();
                             })
      .def_property_readonly("edge_count",
                             [](const Map& map) {
                               const Busy busy(&map, "this Map");
                               return map.memory.edge_count();
                             })
      .def(
          "place",
          [](const Map& map, std::size_t index) {
            const Busy busy(&map, "this Map");
            return map.memory.place(index);
          },
          py::arg("index"), "A copy of place `index`. Raises UsageError beyond the places.")
      .def(
          "places",
          [](const Map& map) {
            const Busy busy(&map, "this Map");
            std::vector<memory::Place> places;
            for (std::size_t i = 0; i < map.memory.place_count(); ++i)
              places.push_back(map.memory.place(i));
            return places;
          },
          "Copies of every place, in the order they were added.")
      .def(
          "edges",
          [](const Map& map) {
            const Busy busy(&map, "this Map");
            std::vector<std::tuple<std::size_t, std::size_t, memory::Edge>> edges;
            for (const auto& e : map.memory.edges()) edges.emplace_back(e.from, e.to, *e.edge);
            return edges;
          },
          "(from, to, Edge) in the order they were added.")
      .def_property_readonly("runs",
                             [](const Map& map) {
                               const Busy busy(&map, "this Map");
                               return map.memory.runs();
                             })
      .def_property_readonly(
          "signature_params",
          [](const Map& map) {
            const Busy busy(&map, "this Map");
            return map.memory.parameters().signature;
          },
          "The signature parameters every place shares.")
      .def_property_readonly("file", [](const Map& map) -> py::object {
        const Busy busy(&map, "this Map");
        if (!map.store) return py::none();
        return py::cast(map.store->file());
      });

  bind_localisation(m);
  bind_route(m);
  bind_navigation(m, map);
}

}  // namespace omninav::python
