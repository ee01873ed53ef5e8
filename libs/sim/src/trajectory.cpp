#include "omninav/sim/trajectory.hpp"

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <set>

#include "free_space.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/sim/tour.hpp"
#include "saccade.hpp"

namespace omninav::sim {
namespace {

// The key=value pairs of a spec; every key must be asked for, so that a typo is an error.
class SpecArguments {
 public:
  SpecArguments(const std::string& spec, std::string kind, const std::string& text)
      : spec_(spec), kind_(std::move(kind)) {
    if (trim(text).empty()) return;
    for (const std::string& pair : split(text, ',')) {
      const std::size_t equals = pair.find('=');
      if (equals == std::string::npos) {
        throw UsageError("trajectory '" + spec_ + "': expected key=value, got '" + pair + "'");
      }
      const std::string key(trim(pair.substr(0, equals)));
      if (!values_.emplace(key, trim(pair.substr(equals + 1))).second) {
        throw UsageError("trajectory '" + spec_ + "': key '" + key + "' is given twice");
      }
    }
  }

  // Any number of a spec is a position, length, speed, rate, angle or count: beyond
  // ±kMaxCoordinateM (10,000 km) it is a mistake, and would overflow the frame counts.
  double number(const std::string& key, double fallback) {
    asked_.insert(key);
    const auto found = values_.find(key);
    if (found == values_.end()) return fallback;
    const std::string where = "trajectory '" + spec_ + "', key " + key;
    const double value = parse_double_argument(found->second, where);
    if (std::abs(value) > kMaxCoordinateM) {
      throw UsageError(where + ": " + found->second + " is beyond ±1e7");
    }
    return value;
  }

  // A count or seed: a whole number.
  int whole(const std::string& key, int fallback) {
    asked_.insert(key);
    const auto found = values_.find(key);
    if (found == values_.end()) return fallback;
    return parse_int_argument(found->second, "trajectory '" + spec_ + "', key " + key);
  }

  std::string text(const std::string& key, const std::string& fallback) {
    asked_.insert(key);
    const auto found = values_.find(key);
    return found == values_.end() ? fallback : found->second;
  }

  void require_all_known() const {
    for (const auto& [key, value] : values_) {
      if (asked_.contains(key)) continue;
      std::string known;
      for (const std::string& name : asked_) known += (known.empty() ? "" : ", ") + name;
      throw UsageError("trajectory '" + spec_ + "': unknown key '" + key + "' for " + kind_ +
                       " (known: " + known + ")");
    }
  }

 private:
  std::string spec_;
  std::string kind_;
  std::map<std::string, std::string> values_;
  std::set<std::string> asked_;
};

// The most poses a trajectory may have: more than a day at 10 frames per second.
constexpr double kMaxPoses = 1e6;

// `count` frames (or poses, steps) as an int, 0 when negative; throws UsageError when a spec
// asks for more than kMaxPoses.
int pose_count(double count, const std::string& spec) {
  if (!(count <= kMaxPoses)) {
    throw UsageError("trajectory '" + spec + "': more than " +
                     std::to_string(static_cast<int>(kMaxPoses)) + " poses");
  }
  return count > 0.0 ? static_cast<int>(count) : 0;
}

void require_positive(double value, const std::string& key, const std::string& spec) {
  if (!(value > 0.0)) throw UsageError("trajectory '" + spec + "': " + key + " must be positive");
}

// Along the polyline at speed_m_s, facing along each leg; at each corner the robot turns on the
// spot at turn_rate_rad_s at most (frames keep coming while it turns, so that a visual compass
// can follow), or at once when the rate is 0.
void walk_polyline(const std::vector<Eigen::Vector2d>& points, double speed_m_s, double fps,
                   double turn_rate_rad_s, const std::string& spec, std::vector<TimedPose>& poses) {
  const double step_m = speed_m_s / fps;
  double time_s = 0.0;
  const auto add = [&](const Eigen::Vector2d& at, double heading) {
    TimedPose pose;
    pose.time_s = time_s;
    pose.pose.x_m = at.x();
    pose.pose.y_m = at.y();
    pose.pose.heading_rad = heading;
    poses.push_back(pose);
    time_s += 1.0 / fps;
  };
  for (std::size_t leg = 0; leg + 1 < points.size(); ++leg) {
    const Eigen::Vector2d from = points[leg], to = points[leg + 1];
    const double length = (to - from).norm();
    const double heading = std::atan2(to.y() - from.y(), to.x() - from.x());
    if (leg > 0 && turn_rate_rad_s > 0.0) {
      const double previous = poses.back().pose.heading_rad;
      const double turn = signed_difference(heading, previous);
      const int frames =
          pose_count(std::ceil(std::abs(turn) / (turn_rate_rad_s / fps) - 1e-9), spec);
      for (int k = 0; k < frames; ++k) add(from, wrap_angle(previous + turn * k / frames));
    }
    // Frames every step_m from the leg's start. Before a corner the last comes within a step of
    // it (the next leg's first frame is the corner), so that no step is longer than step_m: a
    // robot slows to turn, it does not leap. The last leg stops at its last whole step.
    const bool last_leg = leg + 2 == points.size();
    const double whole_steps = length / step_m;
    const int steps = std::max(
        1, pose_count(last_leg ? std::floor(whole_steps + 1e-9) : std::ceil(whole_steps - 1e-9),
                      spec));
    pose_count(static_cast<double>(poses.size()) + steps, spec);
    for (int i = 0; i < steps + (last_leg ? 1 : 0); ++i) {
      add(from + (to - from) * (std::min(length, i * step_m) / length), heading);
    }
  }
}

std::vector<TimedPose> read_csv_poses(const std::string& path) {
  const CsvTable table = CsvTable::read(path);
  const std::size_t x = table.require_column("x_m"), y = table.require_column("y_m");
  const std::size_t heading = table.require_column("heading_deg");
  const std::optional<std::size_t> time = table.find_column("time_s"), z = table.find_column("z_m");
  const std::optional<std::size_t> pitch = table.find_column("pitch_deg"),
                                   roll = table.find_column("roll_deg");
  std::vector<TimedPose> poses;
  for (const CsvTable::Row& row : table.rows()) {
    const std::string where = table.where(row);
    const auto number = [&](std::size_t column) { return parse_double(row.fields[column], where); };
    const auto position_m = [&](std::size_t column) {
      return check_coordinate_m(number(column), where);
    };
    TimedPose pose;
    pose.pose.x_m = position_m(x);
    pose.pose.y_m = position_m(y);
    pose.pose.heading_rad = deg_to_rad(number(heading));
    pose.time_s = time ? number(*time) : -1.0;
    if (z) pose.pose.z_m = position_m(*z);
    if (pitch) pose.pose.pitch_rad = deg_to_rad(number(*pitch));
    if (roll) pose.pose.roll_rad = deg_to_rad(number(*roll));
    poses.push_back(pose);
  }
  if (poses.empty()) throw InputError(path + ": no poses in the trajectory CSV");
  return poses;
}

// Smooth random tilt: a first-order autoregressive process with the given stationary
// standard deviation, so that the camera rocks rather than jitters.
void add_tilt_noise(std::vector<TimedPose>& poses, double pitch_sd_rad, double roll_sd_rad,
                    std::uint64_t seed) {
  if (pitch_sd_rad <= 0.0 && roll_sd_rad <= 0.0) return;
  constexpr double kCorrelation = 0.8;
  const double innovation = std::sqrt(1.0 - kCorrelation * kCorrelation);
  cv::RNG rng(seed);
  double pitch = rng.gaussian(pitch_sd_rad > 0 ? pitch_sd_rad : 1e-12);
  double roll = rng.gaussian(roll_sd_rad > 0 ? roll_sd_rad : 1e-12);
  for (TimedPose& pose : poses) {
    pose.pose.pitch_rad += pitch_sd_rad > 0.0 ? pitch : 0.0;
    pose.pose.roll_rad += roll_sd_rad > 0.0 ? roll : 0.0;
    pitch = kCorrelation * pitch + innovation * rng.gaussian(std::max(pitch_sd_rad, 1e-12));
    roll = kCorrelation * roll + innovation * rng.gaussian(std::max(roll_sd_rad, 1e-12));
  }
}

// What every kind's poses are made from: the spec's arguments, the world, and the defaults
// the kinds share (the floor's centre and a margin inside its edges, the frame rate).
// One member function per kind makes its poses.
struct KindContext {
  SpecArguments& args;
  const World& world;
  const std::string& spec;
  double centre_x = 0.0;
  double centre_y = 0.0;
  double fps = 10.0;
  double margin = 0.5;

  std::vector<TimedPose> rotate_poses() const;
  std::vector<TimedPose> polyline_poses(TrajectoryKind kind) const;
  std::vector<TimedPose> circle_poses() const;
  std::vector<TimedPose> walk_poses() const;
  FreeRouteSettings free_route(double wobble_deg, double wobble_period_s) const;
  std::vector<TimedPose> wander_poses() const;
  std::vector<TimedPose> saccade_poses() const;
  std::vector<TimedPose> grid_poses() const;
  std::vector<TimedPose> tour_poses() const;
  std::vector<TimedPose> csv_poses() const;
};

// The settings a route in the free space (kinds wander and saccade) shares, from its spec, with
// the given defaults of its heading's wobble; the start moved to the free point nearest the
// floor's centre unless the spec gives it.
FreeRouteSettings KindContext::free_route(double wobble_deg, double wobble_period_s) const {
  FreeRouteSettings route;
  route.x = args.number("x", centre_x);
  route.y = args.number("y", centre_y);
  route.heading_rad = deg_to_rad(args.number("heading_deg", 0.0));
  route.speed_m_s = args.number("speed_m_s", 0.2);
  require_positive(route.speed_m_s, "speed_m_s", spec);
  route.length_m = args.number("length_m", 0.0);
  route.duration_s = args.number("duration_s", 0.0);
  if (route.length_m < 0.0 || route.duration_s < 0.0 ||
      (route.length_m > 0.0 && route.duration_s > 0.0)) {
    throw UsageError("trajectory '" + spec + "': give length_m or duration_s (positive), not both");
  }
  if (route.duration_s == 0.0 && route.length_m == 0.0) route.length_m = 10.0;
  route.wobble_rad = deg_to_rad(args.number("wobble_deg", wobble_deg));
  route.wobble_period_s = args.number("wobble_period_s", wobble_period_s);
  route.clearance_m = args.number("clearance_m", 0.25);
  route.seed = args.whole("seed", 1);
  if (route.seed < 0) throw UsageError("trajectory '" + spec + "': seed must not be negative");
  if (route.wobble_rad < 0.0 || route.clearance_m < 0.0) {
    throw UsageError("trajectory '" + spec + "': wobble_deg and clearance_m must not be negative");
  }
  require_positive(route.wobble_period_s, "wobble_period_s", spec);
  if (route.x == centre_x && route.y == centre_y) {
    move_to_free_point(world, route.clearance_m, route.x, route.y);
  }
  if (!world.is_free(route.x, route.y, route.clearance_m)) {
    log_warning("trajectory '" + spec + "': the start is closer than clearance_m to an obstacle");
  }
  return route;
}

// An animal's or a small robot's route (kind `wander`): the direction of travel turns at a
// rate that changes at random moments, mostly gently and now and then sharply (the rate's
// magnitude is exponential with mean turn_rate_deg_s), and the body's heading wobbles about
// the direction of travel (a sinusoid of amplitude wobble_deg and period wobble_period_s,
// its amplitude and period jittered by ±30 % per cycle). Looking ahead 0.5 s, the walker turns
// away from walls, obstacles and the floor's edge by the smallest turn that keeps it
// clearance_m clear, so that every pose is in the free space.
std::vector<TimedPose> KindContext::wander_poses() const {
  const FreeRouteSettings route = free_route(15.0, 2.0);
  const double mean_turn_rate = deg_to_rad(args.number("turn_rate_deg_s", 30.0));
  if (mean_turn_rate < 0.0) {
    throw UsageError("trajectory '" + spec + "': turn_rate_deg_s must not be negative");
  }
  cv::RNG rng(static_cast<std::uint64_t>(route.seed) * 2654435761ULL + 7);
  double x = route.x, y = route.y, travel = route.heading_rad;
  const double seconds =
      route.duration_s > 0.0 ? route.duration_s : route.length_m / route.speed_m_s;
  const int frames = pose_count(std::floor(seconds * fps + 1e-9) + 1, spec);
  const double step = route.speed_m_s / fps;
  const double lookahead = lookahead_m(route.speed_m_s, fps);
  double turn_rate = 0.0, next_change_s = 0.0;
  Wobble wobble(route.wobble_rad, route.wobble_period_s, rng);
  std::vector<TimedPose> poses;
  for (int frame = 0; frame < frames; ++frame) {
    const double time = frame / fps;
    if (time >= next_change_s) {  // a new turn: mostly gentle, sometimes sharp
      const double sign = rng.uniform(0, 2) == 0 ? -1.0 : 1.0;
      turn_rate = sign * mean_turn_rate * -std::log(1.0 - rng.uniform(0.0, 1.0));
      next_change_s = time + rng.uniform(0.5, 3.0);
    }
    if (frame > 0) travel = wrap_angle(travel + turn_rate / fps);
    // A walker closer than clearance_m to something, at its start, keeps out of it only.
    const double keep = world.is_free(x, y, route.clearance_m) ? route.clearance_m : 0.0;
    // Steering away from what lies ahead, it turns on the way it turned (it keeps turning away).
    const std::optional<double> turn = turn_to_clear(world, x, y, lookahead, keep, travel);
    if (turn && *turn != 0.0) {
      travel = wrap_angle(travel + *turn);
      turn_rate = std::copysign(turn_rate, *turn);
    }
    // The body faces the direction it is about to travel in, give or take the wobble.
    poses.push_back(
        {time, {x, y, 0.0, wrap_angle(travel + wobble.offset_rad()), 0.0, 0.0}, {}, {}});
    wobble.advance(fps, rng);
    if (turn) {
      x += step * std::cos(travel);
      y += step * std::sin(travel);
    } else {  // no direction is free: it stands and turns
      travel = wrap_angle(travel + kPi / 2.0 / fps);
    }
  }
  return poses;
}

// kind saccade: straight stretches broken by saccades, stops and turns on the spot
// (saccade.hpp).
std::vector<TimedPose> KindContext::saccade_poses() const {
  const FreeRouteSettings route = free_route(10.0, 1.0);
  SaccadeParams params;
  params.stretch_s = args.number("stretch_s", params.stretch_s);
  params.saccade_min_rad = deg_to_rad(args.number("saccade_min_deg", 30.0));
  params.saccade_max_rad = deg_to_rad(args.number("saccade_max_deg", 120.0));
  params.saccade_rate_rad_s = deg_to_rad(args.number("saccade_rate_deg_s", 500.0));
  params.stop_share = args.number("stop_share", params.stop_share);
  params.stop_s = args.number("stop_s", params.stop_s);
  params.spot_turn_rate_rad_s = deg_to_rad(args.number("spot_turn_rate_deg_s", 60.0));
  try {
    return saccade_route(world, route, params, fps, static_cast<std::size_t>(kMaxPoses));
  } catch (const UsageError& error) {
    throw UsageError("trajectory '" + spec + "': " + error.what());
  }
}

// kind rotate: on the spot at a constant rate.
std::vector<TimedPose> KindContext::rotate_poses() const {
  std::vector<TimedPose> poses;
  const double x = args.number("x", centre_x), y = args.number("y", centre_y);
  const double start = deg_to_rad(args.number("heading_deg", 0.0));
  const double turns = args.number("turns", 1.0);
  const double rate = deg_to_rad(args.number("rate_deg_s", 30.0));
  if (rate == 0.0) throw UsageError("trajectory '" + spec + "': rate_deg_s must not be 0");
  const int frames = pose_count(std::floor(turns * kTwoPi / std::abs(rate) * fps + 1e-9) + 1, spec);
  for (int i = 0; i < frames; ++i) {
    poses.push_back({i / fps, {x, y, 0.0, wrap_angle(start + rate * i / fps), 0.0, 0.0}, {}, {}});
  }
  return poses;
}

// kinds line and zigzag: along a polyline at a constant speed, turning on the spot at corners.
std::vector<TimedPose> KindContext::polyline_poses(TrajectoryKind kind) const {
  std::vector<TimedPose> poses;
  const double x0 = args.number("x0", world.floor.min_x_m + margin);
  const double y0 =
      args.number("y0", kind == TrajectoryKind::kLine ? centre_y : world.floor.min_y_m + margin);
  const double x1 = args.number("x1", world.floor.max_x_m - margin);
  const double y1 =
      args.number("y1", kind == TrajectoryKind::kLine ? centre_y : world.floor.max_y_m - margin);
  const double speed = args.number("speed_m_s", 0.2);
  require_positive(speed, "speed_m_s", spec);
  const double turn_rate = deg_to_rad(args.number("turn_rate_deg_s", 90.0));
  if (turn_rate < 0.0)
    throw UsageError("trajectory '" + spec + "': turn_rate_deg_s must not be negative");
  std::vector<Eigen::Vector2d> points{{x0, y0}, {x1, y1}};
  if (kind == TrajectoryKind::kZigzag) {
    const int rows = pose_count(args.whole("rows", 4), spec);
    if (rows < 2) throw UsageError("trajectory '" + spec + "': rows must be at least 2");
    points.clear();
    for (int row = 0; row < rows; ++row) {
      const double y = y0 + (y1 - y0) * row / (rows - 1);
      points.emplace_back(row % 2 == 0 ? x0 : x1, y);
      points.emplace_back(row % 2 == 0 ? x1 : x0, y);
    }
  }
  if ((points.back() - points.front()).norm() == 0.0 && points.size() == 2) {
    throw UsageError("trajectory '" + spec + "': the line has zero length");
  }
  walk_polyline(points, speed, fps, turn_rate, spec, poses);
  return poses;
}

// kind circle: round a centre, facing along the tangent.
std::vector<TimedPose> KindContext::circle_poses() const {
  std::vector<TimedPose> poses;
  const double cx = args.number("cx", centre_x), cy = args.number("cy", centre_y);
  const double radius = args.number("radius_m", 1.0);
  const double turns = args.number("turns", 1.0);
  const double speed = args.number("speed_m_s", 0.2);
  require_positive(radius, "radius_m", spec);
  if (speed == 0.0) throw UsageError("trajectory '" + spec + "': speed_m_s must not be 0");
  const double angular_rate = speed / radius;  // rad/s, signed
  const int frames =
      pose_count(std::floor(turns * kTwoPi / std::abs(angular_rate) * fps + 1e-9) + 1, spec);
  for (int i = 0; i < frames; ++i) {
    const double angle = angular_rate * i / fps;
    const double tangent = angle + (angular_rate > 0 ? kPi / 2 : -kPi / 2);
    poses.push_back({i / fps,
                     {cx + radius * std::cos(angle), cy + radius * std::sin(angle), 0.0,
                      wrap_angle(tangent), 0.0, 0.0},
                     {},
                     {}});
  }
  return poses;
}

// kind walk: a random walk that turns away from walls and furniture.
std::vector<TimedPose> KindContext::walk_poses() const {
  std::vector<TimedPose> poses;
  double x = args.number("x", centre_x), y = args.number("y", centre_y);
  double heading = deg_to_rad(args.number("heading_deg", 0.0));
  const int steps = pose_count(args.whole("steps", 200), spec);
  const double step_m = args.number("step_m", 0.05);
  const double turn_sd = deg_to_rad(args.number("turn_deg", 20.0));
  cv::RNG rng(static_cast<std::uint64_t>(args.whole("seed", 1)));
  require_positive(step_m, "step_m", spec);
  constexpr double kClearance = 0.3;
  for (int i = 0; i < steps; ++i) {
    poses.push_back({i / fps, {x, y, 0.0, heading, 0.0, 0.0}, {}, {}});
    double turn = rng.gaussian(turn_sd);
    // Turn further until the next step is free; give up after a full circle of tries.
    for (int attempt = 0; attempt < 36; ++attempt) {
      const double h = wrap_angle(heading + turn);
      if (world.is_free(x + step_m * std::cos(h), y + step_m * std::sin(h), kClearance)) break;
      turn += deg_to_rad(10.0);
    }
    heading = wrap_angle(heading + turn);
    x += step_m * std::cos(heading);
    y += step_m * std::sin(heading);
  }
  return poses;
}

// kind grid: a sweep over grid points, those inside furniture left out.
std::vector<TimedPose> KindContext::grid_poses() const {
  std::vector<TimedPose> poses;
  const double x0 = args.number("x0", world.floor.min_x_m + margin);
  const double y0 = args.number("y0", world.floor.min_y_m + margin);
  const int nx = args.whole("nx", 10), ny = args.whole("ny", 8);
  pose_count(static_cast<double>(nx) * ny, spec);
  const double spacing = args.number("spacing_m", 0.3);
  const double heading = deg_to_rad(args.number("heading_deg", 0.0));
  if (nx < 1 || ny < 1) throw UsageError("trajectory '" + spec + "': nx and ny must be at least 1");
  require_positive(spacing, "spacing_m", spec);
  int frame = 0;
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      const double x = x0 + ix * spacing, y = y0 + iy * spacing;
      if (!world.is_free(x, y, 0.05)) continue;
      poses.push_back(
          {frame++ / fps, {x, y, 0.0, heading, 0.0, 0.0}, std::array<int, 3>{ix, iy, 0}, {}});
    }
  }
  return poses;
}

// kind tour: a coverage planner's tour of the free space (tour.hpp), driven along its
// waypoints at speed_m_s, turning on the spot at turn_rate_deg_s at every corner.
std::vector<TimedPose> KindContext::tour_poses() const {
  TourParams tour;
  tour.spec = spec;
  tour.area = {args.number("x0", world.floor.min_x_m), args.number("y0", world.floor.min_y_m),
               args.number("x1", world.floor.max_x_m), args.number("y1", world.floor.max_y_m)};
  if (!(tour.area.max_x_m > tour.area.min_x_m && tour.area.max_y_m > tour.area.min_y_m)) {
    throw UsageError("trajectory '" + spec + "': x0, y0, x1, y1 must give x1 > x0 and y1 > y0");
  }
  tour.lane_m = args.number("lane_m", 0.3);
  tour.clearance_m = args.number("clearance_m", 0.25);
  tour.cell_m = std::min(0.05, tour.lane_m / 3.0);
  const double speed = args.number("speed_m_s", 0.2);
  require_positive(speed, "speed_m_s", spec);
  const double turn_rate = deg_to_rad(args.number("turn_rate_deg_s", 45.0));
  if (turn_rate < 0.0) {
    throw UsageError("trajectory '" + spec + "': turn_rate_deg_s must not be negative");
  }
  const int seed = args.whole("seed", 1);
  if (seed < 0) throw UsageError("trajectory '" + spec + "': seed must not be negative");
  cv::RNG rng(static_cast<std::uint64_t>(seed) * 2654435761ULL + 11);
  const double start_x = rng.uniform(tour.area.min_x_m, tour.area.max_x_m);
  const double start_y = rng.uniform(tour.area.min_y_m, tour.area.max_y_m);
  tour.start = {args.number("x", start_x), args.number("y", start_y)};
  std::vector<Eigen::Vector2d> points = plan_tour(world, tour);
  if (points.size() == 1) points.push_back(points.front());  // a single free cell: stand there
  std::vector<TimedPose> poses;
  walk_polyline(points, speed, fps, turn_rate, spec, poses);
  return poses;
}

// kind csv: the poses of a file, timed by the frame rate when it has no times.
std::vector<TimedPose> KindContext::csv_poses() const {
  std::vector<TimedPose> poses;
  const std::string path = args.text("path", "");
  if (path.empty()) throw UsageError("trajectory '" + spec + "': csv needs path=<file>");
  poses = read_csv_poses(path);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (poses[i].time_s < 0.0) poses[i].time_s = i / fps;
  }
  return poses;
}

std::vector<TimedPose> kind_poses(TrajectoryKind kind, const KindContext& context) {
  switch (kind) {
    case TrajectoryKind::kRotate:
      return context.rotate_poses();
    case TrajectoryKind::kLine:
    case TrajectoryKind::kZigzag:
      return context.polyline_poses(kind);
    case TrajectoryKind::kCircle:
      return context.circle_poses();
    case TrajectoryKind::kWalk:
      return context.walk_poses();
    case TrajectoryKind::kWander:
      return context.wander_poses();
    case TrajectoryKind::kSaccade:
      return context.saccade_poses();
    case TrajectoryKind::kGrid:
      return context.grid_poses();
    case TrajectoryKind::kTour:
      return context.tour_poses();
    case TrajectoryKind::kCsv:
      return context.csv_poses();
  }
  return {};
}

// The kinds in the order the spec's help lists them.
constexpr std::array<TrajectoryKind, 10> kKinds = {
    TrajectoryKind::kRotate, TrajectoryKind::kLine,   TrajectoryKind::kCircle,
    TrajectoryKind::kWalk,   TrajectoryKind::kWander, TrajectoryKind::kSaccade,
    TrajectoryKind::kGrid,   TrajectoryKind::kZigzag, TrajectoryKind::kTour,
    TrajectoryKind::kCsv};

}  // namespace

std::string to_string(TrajectoryKind kind) {
  switch (kind) {
    case TrajectoryKind::kRotate:
      return "rotate";
    case TrajectoryKind::kLine:
      return "line";
    case TrajectoryKind::kCircle:
      return "circle";
    case TrajectoryKind::kWalk:
      return "walk";
    case TrajectoryKind::kWander:
      return "wander";
    case TrajectoryKind::kSaccade:
      return "saccade";
    case TrajectoryKind::kGrid:
      return "grid";
    case TrajectoryKind::kZigzag:
      return "zigzag";
    case TrajectoryKind::kTour:
      return "tour";
    case TrajectoryKind::kCsv:
      return "csv";
  }
  return "?";
}

std::optional<TrajectoryKind> trajectory_kind_from_string(std::string_view text) {
  for (const TrajectoryKind kind : kKinds) {
    if (to_string(kind) == text) return kind;
  }
  return std::nullopt;
}

double Trajectory::length_m() const {
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    length += std::hypot(poses[i].pose.x_m - poses[i - 1].pose.x_m,
                         poses[i].pose.y_m - poses[i - 1].pose.y_m);
  }
  return length;
}

void add_odometry(std::vector<TimedPose>& poses, double noise, std::uint64_t seed) {
  if (poses.empty()) return;
  // SplitMix64 (Steele et al. 2014) of the seed as the generator's state: neighbouring seeds
  // give unrelated streams, which a plain multiple of the seed does not.
  std::uint64_t state = seed + 0x9E3779B97F4A7C15ULL;
  state = (state ^ (state >> 30)) * 0xBF58476D1CE4E5B9ULL;
  state = (state ^ (state >> 27)) * 0x94D049BB133111EBULL;
  cv::RNG rng(state ^ (state >> 31));
  const auto draw = [&] { return noise > 0.0 ? rng.gaussian(noise) : 0.0; };
  double distance_error = draw(), turn_error = draw();
  double metres_to_redraw = 1.0;
  CameraPose odometry = poses.front().pose;
  poses.front().odometry = odometry;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const CameraPose& from = poses[i - 1].pose;
    const CameraPose& to = poses[i].pose;
    // The true step in the robot's frame at `from`: forward, left, turn.
    const double dx = to.x_m - from.x_m, dy = to.y_m - from.y_m;
    const double c = std::cos(from.heading_rad), s = std::sin(from.heading_rad);
    const double forward = c * dx + s * dy, left = -s * dx + c * dy;
    const double turn = signed_difference(to.heading_rad, from.heading_rad);
    const double gain = 1.0 + distance_error;
    const double oc = std::cos(odometry.heading_rad), os = std::sin(odometry.heading_rad);
    odometry.x_m += gain * (oc * forward - os * left);
    odometry.y_m += gain * (os * forward + oc * left);
    odometry.heading_rad = wrap_angle(odometry.heading_rad + turn * (1.0 + turn_error));
    odometry.z_m = to.z_m;
    odometry.pitch_rad = to.pitch_rad;
    odometry.roll_rad = to.roll_rad;
    poses[i].odometry = odometry;
    metres_to_redraw -= std::hypot(dx, dy);
    if (metres_to_redraw <= 0.0) {
      distance_error = draw();
      turn_error = draw();
      metres_to_redraw = 1.0;
    }
  }
}

Trajectory make_trajectory(const std::string& spec, const World& world) {
  const std::size_t colon = spec.find(':');
  const std::string kind_text(trim(spec.substr(0, colon)));
  SpecArguments args(spec, kind_text, colon == std::string::npos ? "" : spec.substr(colon + 1));
  KindContext context{args, world, spec};
  context.centre_x = (world.floor.min_x_m + world.floor.max_x_m) / 2.0;
  context.centre_y = (world.floor.min_y_m + world.floor.max_y_m) / 2.0;
  context.fps = args.number("fps", 10.0);
  require_positive(context.fps, "fps", spec);
  const std::optional<TrajectoryKind> kind = trajectory_kind_from_string(kind_text);
  if (!kind) {
    throw UsageError("trajectory '" + spec + "': unknown kind '" + kind_text +
                     "' (rotate, line, circle, walk, wander, saccade, grid, zigzag, tour, csv)");
  }
  Trajectory trajectory;
  trajectory.kind = *kind;
  std::vector<TimedPose>& poses = trajectory.poses;
  poses = kind_poses(*kind, context);
  const double z = args.number("z_m", 1.0);
  const double pitch_sd = deg_to_rad(args.number("pitch_noise_deg", 0.0));
  const double roll_sd = deg_to_rad(args.number("roll_noise_deg", 0.0));
  const auto noise_seed = static_cast<std::uint64_t>(args.whole("noise_seed", 1));
  const double odometry_noise = args.number("odometry_noise", -1.0);
  const int odometry_seed = args.whole("odometry_seed", 1);
  args.require_all_known();
  if (odometry_seed < 0) {
    throw UsageError("trajectory '" + spec + "': odometry_seed must not be negative");
  }
  for (TimedPose& pose : poses) {
    if (*kind != TrajectoryKind::kCsv || pose.pose.z_m == 0.0) pose.pose.z_m = z;
  }
  add_tilt_noise(poses, pitch_sd, roll_sd, noise_seed);
  if (poses.empty()) throw UsageError("trajectory '" + spec + "' has no poses");
  if (odometry_noise != -1.0) {
    if (!(odometry_noise >= 0.0 && odometry_noise <= 1.0)) {
      throw UsageError("trajectory '" + spec +
                       "': odometry_noise is out of range (valid: [0, 1], a relative standard "
                       "deviation of distance and turn)");
    }
    add_odometry(poses, odometry_noise, static_cast<std::uint64_t>(odometry_seed));
  }

  std::size_t blocked = 0;
  for (const TimedPose& pose : poses)
    blocked += world.is_free(pose.pose.x_m, pose.pose.y_m) ? 0 : 1;
  if (blocked > 0) {
    log_warning("trajectory '" + spec + "': " + std::to_string(blocked) + " of " +
                std::to_string(poses.size()) + " poses are inside furniture or outside the floor");
  }
  return trajectory;
}

}  // namespace omninav::sim
