#include "omninav/sim/trajectory.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <set>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/parse.hpp"

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
      values_[std::string(trim(pair.substr(0, equals)))] =
          std::string(trim(pair.substr(equals + 1)));
    }
  }

  double number(const std::string& key, double fallback) {
    asked_.insert(key);
    const auto found = values_.find(key);
    if (found == values_.end()) return fallback;
    return parse_double(found->second, "trajectory '" + spec_ + "', key " + key);
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

void require_positive(double value, const std::string& key, const std::string& spec) {
  if (!(value > 0.0)) throw UsageError("trajectory '" + spec + "': " + key + " must be positive");
}

// Along the polyline at speed_m_s, facing along each leg; at each corner the robot turns on the
// spot at turn_rate_rad_s at most (frames keep coming while it turns, so that a visual compass
// can follow), or at once when the rate is 0.
void walk_polyline(const std::vector<cv::Point2d>& points, double speed_m_s, double fps,
                   double turn_rate_rad_s, std::vector<TimedPose>& poses) {
  const double step_m = speed_m_s / fps;
  double time_s = 0.0;
  const auto add = [&](const cv::Point2d& at, double heading) {
    TimedPose pose;
    pose.time_s = time_s;
    pose.pose.x_m = at.x;
    pose.pose.y_m = at.y;
    pose.pose.heading_rad = heading;
    poses.push_back(pose);
    time_s += 1.0 / fps;
  };
  for (std::size_t leg = 0; leg + 1 < points.size(); ++leg) {
    const cv::Point2d from = points[leg], to = points[leg + 1];
    const double length = cv::norm(to - from);
    const double heading = std::atan2(to.y - from.y, to.x - from.x);
    if (leg > 0 && turn_rate_rad_s > 0.0) {
      const double previous = poses.back().pose.heading_rad;
      const double turn = signed_difference(heading, previous);
      const int frames =
          static_cast<int>(std::ceil(std::abs(turn) / (turn_rate_rad_s / fps) - 1e-9));
      for (int k = 0; k < frames; ++k) add(from, wrap_angle(previous + turn * k / frames));
    }
    const int steps = std::max(1, static_cast<int>(std::floor(length / step_m + 1e-9)));
    const bool last_leg = leg + 2 == points.size();
    for (int i = 0; i < steps + (last_leg ? 1 : 0); ++i) {
      add(from + (to - from) * (std::min(length, i * step_m) / length), heading);
    }
  }
}

std::vector<TimedPose> read_csv_poses(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open the trajectory CSV");
  std::string line;
  if (!std::getline(file, line)) throw InputError(path + ": empty trajectory CSV");
  const std::vector<std::string> header = split(line, ',');
  auto column = [&](const std::string& name, bool required) -> int {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    if (required) throw InputError(path + ": missing column '" + name + "'");
    return -1;
  };
  const int x = column("x_m", true), y = column("y_m", true), heading = column("heading_deg", true);
  const int time = column("time_s", false), z = column("z_m", false);
  const int pitch = column("pitch_deg", false), roll = column("roll_deg", false);
  std::vector<TimedPose> poses;
  for (int line_number = 2; std::getline(file, line); ++line_number) {
    if (trim(line).empty()) continue;
    const std::vector<std::string> fields = split(line, ',');
    const std::string where = path + ":" + std::to_string(line_number);
    auto field = [&](int index) -> const std::string& {
      if (index >= static_cast<int>(fields.size())) {
        throw InputError(where + ": expected " + std::to_string(header.size()) + " fields");
      }
      return fields[index];
    };
    TimedPose pose;
    pose.pose.x_m = parse_double(field(x), where);
    pose.pose.y_m = parse_double(field(y), where);
    pose.pose.heading_rad = deg_to_rad(parse_double(field(heading), where));
    pose.time_s = time >= 0 ? parse_double(field(time), where) : -1.0;
    if (z >= 0) pose.pose.z_m = parse_double(field(z), where);
    if (pitch >= 0) pose.pose.pitch_rad = deg_to_rad(parse_double(field(pitch), where));
    if (roll >= 0) pose.pose.roll_rad = deg_to_rad(parse_double(field(roll), where));
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

// An animal's or a small robot's route (kind `wander`): the direction of travel turns at a
// rate that changes at random moments, mostly gently and now and then sharply (the rate's
// magnitude is exponential with mean turn_rate_deg_s), and the body's heading wobbles about
// the direction of travel (a sinusoid of amplitude wobble_deg and period wobble_period_s,
// its amplitude and period jittered by ±30 % per cycle). Looking ahead 0.5 s, the walker turns
// away from walls, obstacles and the floor's edge by the smallest turn that keeps it
// clearance_m clear, so that every pose is in the free space.
std::vector<TimedPose> wander(SpecArguments& args, const World& world, const std::string& spec,
                              double centre_x, double centre_y, double fps) {
  double x = args.number("x", centre_x), y = args.number("y", centre_y);
  double travel = deg_to_rad(args.number("heading_deg", 0.0));
  const double speed = args.number("speed_m_s", 0.2);
  require_positive(speed, "speed_m_s", spec);
  const double length = args.number("length_m", 0.0);
  const double duration = args.number("duration_s", 0.0);
  if (length < 0.0 || duration < 0.0 || (length > 0.0 && duration > 0.0)) {
    throw UsageError("trajectory '" + spec + "': give length_m or duration_s (positive), not both");
  }
  const double seconds = duration > 0.0 ? duration : (length > 0.0 ? length : 10.0) / speed;
  const double mean_turn_rate = deg_to_rad(args.number("turn_rate_deg_s", 30.0));
  const double wobble = deg_to_rad(args.number("wobble_deg", 15.0));
  const double wobble_period = args.number("wobble_period_s", 2.0);
  const double clearance = args.number("clearance_m", 0.25);
  const double seed = args.number("seed", 1);
  if (!(seed >= 0.0 && seed <= 1e9 && seed == std::floor(seed))) {
    throw UsageError("trajectory '" + spec + "': seed must be a whole number in [0, 1e9]");
  }
  cv::RNG rng(static_cast<std::uint64_t>(seed) * 2654435761ULL + 7);
  if (mean_turn_rate < 0.0 || wobble < 0.0 || clearance < 0.0) {
    throw UsageError("trajectory '" + spec +
                     "': turn_rate_deg_s, wobble_deg and clearance_m must not be negative");
  }
  require_positive(wobble_period, "wobble_period_s", spec);
  if (x == centre_x && y == centre_y) {  // the default start: the free point nearest the centre
    for (int ring = 1; ring < 400 && !world.is_free(x, y, clearance); ++ring) {
      for (int k = 0; k < 8 * ring && !world.is_free(x, y, clearance); ++k) {
        const double angle = kTwoPi * k / (8 * ring);
        x = centre_x + 0.05 * ring * std::cos(angle);
        y = centre_y + 0.05 * ring * std::sin(angle);
      }
    }
  }
  if (!world.is_free(x, y, clearance)) {
    log_warning("trajectory '" + spec + "': the start is closer than clearance_m to an obstacle");
  }

  constexpr double kMaxFrames = 1e6;  // more than a day at 10 frames per second
  if (!(seconds * fps < kMaxFrames)) {
    throw UsageError("trajectory '" + spec + "': more than 1000000 poses");
  }
  const int frames = static_cast<int>(std::floor(seconds * fps + 1e-9)) + 1;
  const double step = speed / fps;
  const double lookahead = std::max(0.5 * speed, 2.0 * step);
  double turn_rate = 0.0, next_change_s = 0.0;
  double wobble_phase = rng.uniform(0.0, kTwoPi);
  double wobble_amplitude = wobble, wobble_rate = kTwoPi / wobble_period;
  std::vector<TimedPose> poses;
  for (int frame = 0; frame < frames; ++frame) {
    const double time = frame / fps;
    if (time >= next_change_s) {  // a new turn: mostly gentle, sometimes sharp
      const double sign = rng.uniform(0, 2) == 0 ? -1.0 : 1.0;
      turn_rate = sign * mean_turn_rate * -std::log(1.0 - rng.uniform(0.0, 1.0));
      next_change_s = time + rng.uniform(0.5, 3.0);
    }
    if (frame > 0) travel = wrap_angle(travel + turn_rate / fps);
    // Steer away from what lies ahead: the smallest turn, either way, that leaves the path
    // ahead free; stand and turn when none does.
    // (A walker closer than clearance_m to something, at its start, keeps out of it only.)
    const double keep = world.is_free(x, y, clearance) ? clearance : 0.0;
    const auto clear = [&](double direction) {
      return world.segment_is_free(x, y, x + lookahead * std::cos(direction),
                                   y + lookahead * std::sin(direction), keep);
    };
    bool moving = clear(travel);
    for (int k = 1; !moving && k <= 18; ++k) {
      for (const double side : {1.0, -1.0}) {
        const double direction = wrap_angle(travel + side * k * deg_to_rad(10.0));
        if (clear(direction)) {
          travel = direction;
          turn_rate = side * std::abs(turn_rate);  // keep turning away
          moving = true;
          break;
        }
      }
    }
    // The body faces the direction it is about to travel in, give or take the wobble.
    poses.push_back(
        {time,
         {x, y, 0.0, wrap_angle(travel + wobble_amplitude * std::sin(wobble_phase)), 0.0, 0.0},
         {}});
    const double previous_phase = wobble_phase;
    wobble_phase += wobble_rate / fps;
    if (std::floor(wobble_phase / kTwoPi) != std::floor(previous_phase / kTwoPi)) {
      wobble_amplitude = wobble * rng.uniform(0.7, 1.3);  // each cycle a little different
      wobble_rate = kTwoPi / (wobble_period * rng.uniform(0.7, 1.3));
    }
    if (moving) {
      x += step * std::cos(travel);
      y += step * std::sin(travel);
    } else {
      travel = wrap_angle(travel + kPi / 2.0 / fps);
    }
  }
  return poses;
}

}  // namespace

double Trajectory::length_m() const {
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    length += std::hypot(poses[i].pose.x_m - poses[i - 1].pose.x_m,
                         poses[i].pose.y_m - poses[i - 1].pose.y_m);
  }
  return length;
}

Trajectory make_trajectory(const std::string& spec, const World& world) {
  const std::size_t colon = spec.find(':');
  Trajectory trajectory;
  trajectory.kind = std::string(trim(spec.substr(0, colon)));
  SpecArguments args(spec, trajectory.kind,
                     colon == std::string::npos ? "" : spec.substr(colon + 1));

  const double centre_x = (world.floor.min_x_m + world.floor.max_x_m) / 2.0;
  const double centre_y = (world.floor.min_y_m + world.floor.max_y_m) / 2.0;
  const double margin = 0.5;
  const double fps = args.number("fps", 10.0);
  require_positive(fps, "fps", spec);
  std::vector<TimedPose>& poses = trajectory.poses;

  if (trajectory.kind == "rotate") {
    const double x = args.number("x", centre_x), y = args.number("y", centre_y);
    const double start = deg_to_rad(args.number("heading_deg", 0.0));
    const double turns = args.number("turns", 1.0);
    const double rate = deg_to_rad(args.number("rate_deg_s", 30.0));
    if (rate == 0.0) throw UsageError("trajectory '" + spec + "': rate_deg_s must not be 0");
    const int frames =
        static_cast<int>(std::floor(turns * kTwoPi / std::abs(rate) * fps + 1e-9)) + 1;
    for (int i = 0; i < frames; ++i) {
      poses.push_back({i / fps, {x, y, 0.0, wrap_angle(start + rate * i / fps), 0.0, 0.0}, {}});
    }
  } else if (trajectory.kind == "line" || trajectory.kind == "zigzag") {
    const double x0 = args.number("x0", world.floor.min_x_m + margin);
    const double y0 =
        args.number("y0", trajectory.kind == "line" ? centre_y : world.floor.min_y_m + margin);
    const double x1 = args.number("x1", world.floor.max_x_m - margin);
    const double y1 =
        args.number("y1", trajectory.kind == "line" ? centre_y : world.floor.max_y_m - margin);
    const double speed = args.number("speed_m_s", 0.2);
    require_positive(speed, "speed_m_s", spec);
    const double turn_rate = deg_to_rad(args.number("turn_rate_deg_s", 90.0));
    if (turn_rate < 0.0)
      throw UsageError("trajectory '" + spec + "': turn_rate_deg_s must not be negative");
    std::vector<cv::Point2d> points{{x0, y0}, {x1, y1}};
    if (trajectory.kind == "zigzag") {
      const int rows = static_cast<int>(args.number("rows", 4));
      if (rows < 2) throw UsageError("trajectory '" + spec + "': rows must be at least 2");
      points.clear();
      for (int row = 0; row < rows; ++row) {
        const double y = y0 + (y1 - y0) * row / (rows - 1);
        points.emplace_back(row % 2 == 0 ? x0 : x1, y);
        points.emplace_back(row % 2 == 0 ? x1 : x0, y);
      }
    }
    if (cv::norm(points.back() - points.front()) == 0.0 && points.size() == 2) {
      throw UsageError("trajectory '" + spec + "': the line has zero length");
    }
    walk_polyline(points, speed, fps, turn_rate, poses);
  } else if (trajectory.kind == "circle") {
    const double cx = args.number("cx", centre_x), cy = args.number("cy", centre_y);
    const double radius = args.number("radius_m", 1.0);
    const double turns = args.number("turns", 1.0);
    const double speed = args.number("speed_m_s", 0.2);
    require_positive(radius, "radius_m", spec);
    if (speed == 0.0) throw UsageError("trajectory '" + spec + "': speed_m_s must not be 0");
    const double angular_rate = speed / radius;  // rad/s, signed
    const int frames =
        static_cast<int>(std::floor(turns * kTwoPi / std::abs(angular_rate) * fps + 1e-9)) + 1;
    for (int i = 0; i < frames; ++i) {
      const double angle = angular_rate * i / fps;
      const double tangent = angle + (angular_rate > 0 ? kPi / 2 : -kPi / 2);
      poses.push_back({i / fps,
                       {cx + radius * std::cos(angle), cy + radius * std::sin(angle), 0.0,
                        wrap_angle(tangent), 0.0, 0.0},
                       {}});
    }
  } else if (trajectory.kind == "walk") {
    double x = args.number("x", centre_x), y = args.number("y", centre_y);
    double heading = deg_to_rad(args.number("heading_deg", 0.0));
    const int steps = static_cast<int>(args.number("steps", 200));
    const double step_m = args.number("step_m", 0.05);
    const double turn_sd = deg_to_rad(args.number("turn_deg", 20.0));
    cv::RNG rng(static_cast<std::uint64_t>(args.number("seed", 1)));
    require_positive(step_m, "step_m", spec);
    constexpr double kClearance = 0.3;
    for (int i = 0; i < steps; ++i) {
      poses.push_back({i / fps, {x, y, 0.0, heading, 0.0, 0.0}, {}});
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
  } else if (trajectory.kind == "wander") {
    poses = wander(args, world, spec, centre_x, centre_y, fps);
  } else if (trajectory.kind == "grid") {
    const double x0 = args.number("x0", world.floor.min_x_m + margin);
    const double y0 = args.number("y0", world.floor.min_y_m + margin);
    const int nx = static_cast<int>(args.number("nx", 10)),
              ny = static_cast<int>(args.number("ny", 8));
    const double spacing = args.number("spacing_m", 0.3);
    const double heading = deg_to_rad(args.number("heading_deg", 0.0));
    if (nx < 1 || ny < 1)
      throw UsageError("trajectory '" + spec + "': nx and ny must be at least 1");
    require_positive(spacing, "spacing_m", spec);
    int frame = 0;
    for (int iy = 0; iy < ny; ++iy) {
      for (int ix = 0; ix < nx; ++ix) {
        const double x = x0 + ix * spacing, y = y0 + iy * spacing;
        if (!world.is_free(x, y, 0.05)) continue;
        poses.push_back(
            {frame++ / fps, {x, y, 0.0, heading, 0.0, 0.0}, std::array<int, 3>{ix, iy, 0}});
      }
    }
  } else if (trajectory.kind == "csv") {
    const std::string path = args.text("path", "");
    if (path.empty()) throw UsageError("trajectory '" + spec + "': csv needs path=<file>");
    poses = read_csv_poses(path);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (poses[i].time_s < 0.0) poses[i].time_s = i / fps;
    }
  } else {
    throw UsageError("trajectory '" + spec + "': unknown kind '" + trajectory.kind +
                     "' (rotate, line, circle, walk, wander, grid, zigzag, csv)");
  }

  const double z = args.number("z_m", 1.0);
  const double pitch_sd = deg_to_rad(args.number("pitch_noise_deg", 0.0));
  const double roll_sd = deg_to_rad(args.number("roll_noise_deg", 0.0));
  const auto noise_seed = static_cast<std::uint64_t>(args.number("noise_seed", 1));
  args.require_all_known();
  for (TimedPose& pose : poses) {
    if (trajectory.kind != "csv" || pose.pose.z_m == 0.0) pose.pose.z_m = z;
  }
  add_tilt_noise(poses, pitch_sd, roll_sd, noise_seed);
  if (poses.empty()) throw UsageError("trajectory '" + spec + "' has no poses");

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
