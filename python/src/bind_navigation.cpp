// The reactive navigator (Menegatti et al. 2004, §3.5, with omninav's additions) driving a robot
// of the caller's: any Python object with view(step) -> panorama, move(turn_rad, distance_m) ->
// metres driven, and truth() -> CameraPose (for the step log only). So a user drives their own
// robot or simulator from Python, the navigator deciding each turn and step from the panoramas.
// And the live session (navigation/live_session.hpp), as the ROS node runs it: a robot's frames
// pushed as they come, each answered with its heading, place, new place and, navigating to a
// goal image, the command toward it.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bind.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/live_session.hpp"
#include "omninav/navigation/memory_places.hpp"

namespace omninav::python {
namespace {

namespace fs = std::filesystem;

// The navigator's world, calling the Python robot with the GIL held (the navigator runs
// without it).
class PythonRobot : public navigation::NavigationWorld {
 public:
  explicit PythonRobot(py::object robot) : robot_(std::move(robot)) {}

  cv::Mat view(int step) override {
    py::gil_scoped_acquire acquire;
    py::object keep;
    const py::array panorama = robot_.attr("view")(step);
    return array_to_mat(panorama, "robot.view(" + std::to_string(step) + ")", keep).clone();
  }
  double move(double turn_rad, double distance_m) override {
    py::gil_scoped_acquire acquire;
    const double driven_m = robot_.attr("move")(turn_rad, distance_m).cast<double>();
    if (!std::isfinite(driven_m) || std::abs(driven_m) > kMaxCoordinateM) {
      throw InputError("robot.move() returned " + general(driven_m) +
                       ", not the metres driven (a finite distance)");
    }
    return driven_m;
  }
  CameraPose truth() const override {
    py::gil_scoped_acquire acquire;
    return check_pose(robot_.attr("truth")().cast<CameraPose>(), "robot.truth()");
  }

 private:
  py::object robot_;
};

void bind_live_session(py::module_& m) {
  using navigation::LiveOutput;
  using navigation::LivePlace;
  using navigation::LiveSession;
  py::class_<LivePlace>(m, "LivePlace",
                        "The place the belief recognises in a frame (LiveSession.push).")
      .def_readonly("place", &LivePlace::place, "The most probable place's index.")
      .def_readonly("similarity", &LivePlace::similarity,
                    "Eq. 3 over the map's places, 0..1000 (1000: the most similar).")
      .def_readonly("dissimilarity_per_value", &LivePlace::dissimilarity_per_value)
      .def_readonly("probability", &LivePlace::probability, "The belief's on the place.")
      .def_readonly("confidence", &LivePlace::confidence,
                    "The belief's on the place and the places linked to it.")
      .def_readonly("lost", &LivePlace::lost, "confidence below belief.confident_share.");
  using navigation::LiveCommand;
  py::class_<LiveCommand>(
      m, "LiveCommand",
      "What the robot is to do after a frame while navigating (LiveSession.navigate_to): what "
      "is left of the navigator's command, turn on the spot first, then drive forwards.")
      .def_property_readonly(
          "state", [](const LiveCommand& c) { return std::string(navigation::to_string(c.state)); },
          "'driving' (a command under way), 'reached' (stopped at the goal) or 'failed' "
          "(navigator.max_steps views spent): stand still unless driving.")
      .def_readonly("turn_rad", &LiveCommand::turn_rad,
                    "Still to turn, counter-clockwise positive (0 once turned).")
      .def_readonly("distance_m", &LiveCommand::distance_m, "Still to drive after the turn.")
      .def_readonly("step", &LiveCommand::step, "The navigator's step (view) the command is of.")
      .def_readonly("new_step", &LiveCommand::new_step, "This frame was that step's view.")
      .def_property_readonly(
          "phase",
          [](const LiveCommand& c) { return std::string(navigation::phase_name(c.phase)); },
          "'route' or 'homing'.")
      .def_readonly("place", &LiveCommand::place, "The place the navigator acted on.")
      .def_readonly("lost", &LiveCommand::lost, "The navigator's belief was spread then.");
  py::class_<LiveOutput>(m, "LiveOutput", "A frame's outputs (LiveSession.push).")
      .def_readonly("frame", &LiveOutput::frame, "Frames accepted before this one.")
      .def_readonly("stamp_s", &LiveOutput::stamp_s)
      .def_readonly("compass", &LiveOutput::compass, "The compass's CompassEstimate.")
      .def_readonly("place", &LiveOutput::place,
                    "The recognised LivePlace; None without a map "
                    "that has a lattice.")
      .def_readonly("new_place", &LiveOutput::new_place,
                    "Exploring: the index of the place the frame became, else None.")
      .def_readonly("command", &LiveOutput::command,
                    "Navigating (navigate_to): the LiveCommand toward the goal, else None.");
  py::class_<LiveSession>(
      m, "LiveSession",
      "A robot's frames pushed one at a time, each answered at once, as the ROS node omninav_ros "
      "runs it (docs/ros.md): the compass's heading (as `omninav compass`), with a map that "
      "has a lattice the place the belief over places recognises, while exploring the place "
      "the frame became, and after navigate_to(goal_image) the command toward the goal. Bad "
      "frames (an empty or non-8-bit image, a size change, a stamp not "
      "after the last) are skipped and counted: push returns None.\n\n"
      "    session = omninav.LiveSession('maps/lab.vmem')\n"
      "    output = session.push(panorama, stamp_s=0.1, odometry=omninav.Pose2(0, 0, 0))")
      .def(py::init([](std::optional<fs::path> map, std::optional<fs::path> config_dir) {
             return std::make_unique<LiveSession>(
                 config::load_live_session_params(config_dir_or_default(config_dir)), map);
           }),
           py::arg("map") = py::none(), py::arg("config_dir") = py::none(),
           "map: the map file to recognise places in and explore into (loaded when it exists); "
           "None: the compass only. The parameters are compass.yaml, memory.yaml and "
           "navigation.yaml of config_dir (None: omninav.default_config_dir()).")
      .def(
          "push",
          [](LiveSession& session, const py::array& panorama, double stamp_s,
             std::optional<Pose2> odometry) {
            const Busy busy(&session, "this LiveSession");
            py::object keep;
            const cv::Mat image = array_to_mat(panorama, "live frame", keep);
            py::gil_scoped_release release;
            return session.push({image, stamp_s, odometry});
          },
          py::arg("panorama"), py::arg("stamp_s"), py::arg("odometry") = py::none(),
          "The frame's LiveOutput, or None when it was skipped (last_skip says why). The stamps "
          "must grow; odometry: the robot's Pose2 at the stamp.")
      .def(
          "navigate_to",
          [](LiveSession& session, const py::array& goal_image) {
            const Busy busy(&session, "this LiveSession");
            py::object keep;
            const cv::Mat image = array_to_mat(goal_image, "goal image", keep);
            py::gil_scoped_release release;
            return session.navigate_to(image, "goal image");
          },
          py::arg("goal_image"),
          "Navigates to where goal_image was taken: returns the goal's PlaceMatch, and each "
          "frame pushed from now on gets a LiveCommand in its output (`omninav navigate`'s "
          "navigator, a frame at a time: docs/navigation.md). With odometry, the frames between "
          "two of the navigator's views get what is left of its command; without, each frame "
          "is a view and the last command counts as carried out before it.")
      .def("stop_navigating",
           [](LiveSession& session) {
             const Busy busy(&session, "this LiveSession");
             session.stop_navigating();
           })
      .def_property_readonly("navigating",
                             [](const LiveSession& session) {
                               const Busy busy(&session, "this LiveSession");
                               return session.navigating();
                             })
      .def(
          "start_exploring",
          [](LiveSession& session) {
            const Busy busy(&session, "this LiveSession");
            session.start_exploring();
          },
          "The frames pushed from now on go into a new run of the map.")
      .def("stop_exploring",
           [](LiveSession& session) {
             const Busy busy(&session, "this LiveSession");
             session.stop_exploring();
           })
      .def(
          "save",
          [](LiveSession& session) {
            const Busy busy(&session, "this LiveSession");
            py::gil_scoped_release release;
            session.save();
          },
          "Writes the map to its file (what changed, in one transaction). UsageError without "
          "a map file.")
      .def_property_readonly("exploring",
                             [](const LiveSession& session) {
                               const Busy busy(&session, "this LiveSession");
                               return session.exploring();
                             })
      .def_property_readonly("place_count",
                             [](const LiveSession& session) {
                               const Busy busy(&session, "this LiveSession");
                               return session.place_count();
                             })
      .def_property_readonly(
          "no_belief_reason",
          [](const LiveSession& session) {
            const Busy busy(&session, "this LiveSession");
            return session.no_belief_reason();
          },
          "Why no places are recognised (no map, no places, no lattice); None when they are.")
      .def_property_readonly(
          "skipped",
          [](const LiveSession& session) {
            const Busy busy(&session, "this LiveSession");
            py::dict counts;
            for (int reason = 0; reason < navigation::kSkipReasons; ++reason) {
              const auto kind = static_cast<navigation::SkipReason>(reason);
              counts[navigation::to_string(kind)] = session.skipped(kind);
            }
            return counts;
          },
          "The frames skipped so far by reason: 'bad image', 'size change', 'stamp not "
          "increasing'.")
      .def_property_readonly(
          "last_skip",
          [](const LiveSession& session) -> std::optional<std::pair<std::string, std::string>> {
            const Busy busy(&session, "this LiveSession");
            if (!session.last_skip()) return std::nullopt;
            return std::make_pair(std::string(navigation::to_string(session.last_skip()->first)),
                                  session.last_skip()->second);
          },
          "The last skip's (reason, message), None before any.");
}

}  // namespace

void bind_navigation(py::module_& m, py::class_<Map>& map) {
  bind_live_session(m);
  using navigation::NavigationStep;
  py::class_<NavigationStep>(m, "NavigationStep",
                             "One step of a navigation: the best place matched (None when "
                             "nothing was recognised), the heading estimate in the lattice "
                             "frame, the turn commanded, and whether localisation jumped.")
      .def_readonly("index", &NavigationStep::index)
      .def_readonly("truth", &NavigationStep::truth)
      .def_readonly("match", &NavigationStep::match)
      .def_readonly("heading_estimate_rad", &NavigationStep::heading_estimate_rad)
      .def_readonly("turn_rad", &NavigationStep::turn_rad)
      .def_readonly("jump", &NavigationStep::jump);

  using navigation::GoalRun;
  py::class_<GoalRun>(m, "GoalRun",
                      "A navigation to a goal image: the goal's place, the route plan, and the "
                      "run (reached, steps, path_length_m, jumps, sidesteps, replans, "
                      "homing_steps, lost_events).")
      .def_readonly("goal", &GoalRun::goal)
      .def_readonly("plan", &GoalRun::plan)
      .def_property_readonly("reached", [](const GoalRun& r) { return r.result.reached; })
      .def_property_readonly("steps", [](const GoalRun& r) { return r.result.steps; })
      .def_property_readonly("path_length_m",
                             [](const GoalRun& r) { return r.result.path_length_m; })
      .def_property_readonly("jumps", [](const GoalRun& r) { return r.result.jumps; })
      .def_property_readonly("sidesteps", [](const GoalRun& r) { return r.result.sidesteps; })
      .def_property_readonly("replans", [](const GoalRun& r) { return r.result.replans; })
      .def_property_readonly("homing_steps", [](const GoalRun& r) { return r.result.homing_steps; })
      .def_property_readonly("lost_events", [](const GoalRun& r) { return r.result.lost_events; });

  map.def(
      "navigate_to_image",
      [](const Map& map, py::object robot, const py::array& goal_image,
         std::optional<evaluation::NavigationConfig> config, std::optional<fs::path> config_dir,
         int max_steps) {
        const Busy busy(&map, "this Map");
        const memory::VisualMemory& memory = map.memory;
        const fs::path dir = config_dir_or_default(config_dir);
        const memory::MemoryConfig memory_config = config::load_memory_config(dir);
        const navigation::SteeringParams steering{config::load_compass_config(dir).min_warping,
                                                  config::load_camera_config(dir).panorama};
        evaluation::NavigationConfig navigation = navigation_config(config, config_dir);
        if (max_steps > 0) navigation.navigator.max_steps = max_steps;
        py::object keep;
        const cv::Mat goal = array_to_mat(goal_image, "goal image", keep);
        PythonRobot body(std::move(robot));  // released after the GIL is taken back
        py::gil_scoped_release release;
        const memory::Localiser localiser(memory, memory_config.localisation);
        signature::SignatureExtractor extractor(memory.parameters().signature);
        const navigation::GoalNavigationSetup setup = navigation::goal_navigation_setup(
            memory, navigation::memory_localiser(localiser, extractor), navigation.route,
            navigation.navigator, navigation.links, navigation.belief, steering);
        return navigation::navigate_to_image(body, goal, "goal image", setup);
      },
      py::arg("robot"), py::arg("goal_image"), py::arg("config") = py::none(),
      py::arg("config_dir") = py::none(), py::arg("max_steps") = 0,
      "Drives `robot` to where `goal_image` was taken, as `omninav navigate` does: the goal "
      "matched to a place, the route planned over the lattice (needs organise()), then view, "
      "localise, turn and step until the goal's place is recognised, homing on the goal image "
      "at the end (`config`, a NavigationConfig, else navigation.yaml; max_steps > 0 overrides "
      "navigator.max_steps). `robot` has "
      "view(step) -> panorama, move(turn_rad, distance_m) -> metres driven, truth() -> "
      "CameraPose (for the step log only: the navigator never reads it).");
}

}  // namespace omninav::python
