#include "omninav/navigation/navigator.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/navigation/memory_places.hpp"

namespace omninav::navigation {
namespace {

constexpr int kEscapeSteps = 3;

// What homing compares its first view with: a goal infinitely far.
constexpr GoalCue kNoCue{std::numeric_limits<double>::infinity(), 0.0, true};

// The turn from the planned direction of the `sidestep`th try after a block (0: none), in the
// unit of `step`: left by one step, right by one, left by two, right by two, ... (sidesteps
// and escapes)
double sidestep_turn(int sidestep, double step) {
  return (sidestep % 2 == 1 ? 1.0 : -1.0) * ((sidestep + 1) / 2) * step;
}

// Drops the link from `place` to its next place from `plan`'s graph and plans again from the
// goal; keeps the new plan when `place` still reaches the goal (returns true), else leaves
// `plan` as it was.
bool replan_without_link(const std::vector<PlaceNode>& places, int place, RoutePlan& plan) {
  const int next = plan.next[place];
  if (next < 0) return false;
  RoutePlan replanned = plan_without_link(places, plan, place, next);
  if (!replanned.reaches_goal(place)) return false;
  plan = std::move(replanned);
  return true;
}

// The place of a step's match, -1 when nothing was recognised.
int place_of(const NavigationStep& step) {
  return step.match ? static_cast<int>(step.match->place) : -1;
}

// The diagonal of the bounding box of the places on the lattice: how far apart two places of
// the map can be.
double lattice_extent_m(const std::vector<PlaceNode>& places) {
  if (places.empty()) return 0.0;
  Eigen::Vector2d low = places.front().position_m, high = low;
  for (const PlaceNode& place : places) {
    low = low.cwiseMin(place.position_m);
    high = high.cwiseMax(place.position_m);
  }
  return (high - low).norm();
}

// How far apart two places of the map can be: the lattice's extent, or over measured links (the
// lattice not trusted: it may be shrunk or folded) twice the longest route to the goal, at
// least.
double map_extent_m(const std::vector<PlaceNode>& places, const RoutePlan& plan) {
  const double lattice_m = lattice_extent_m(places);
  if (plan.measured.empty()) return lattice_m;
  double longest_m = 0.0;
  for (const double cost_m : plan.cost_m) {
    if (std::isfinite(cost_m)) longest_m = std::max(longest_m, cost_m);
  }
  return std::max(lattice_m, 2.0 * longest_m);
}

// The distance between neighbouring places as a plan tells it: the median length of its
// measured links (the map's spacing, by the organiser's calibration of the dissimilarity), or
// over the lattice the lattice spacing. A folded lattice's spacing is not the map's (places lie
// on top of each other there).
double spacing_of(const std::vector<PlaceNode>& places, const RoutePlan& plan) {
  if (plan.measured.empty()) return lattice_spacing(places);
  std::vector<double> lengths_m;
  for (const MeasuredLink& link : plan.measured) lengths_m.push_back(link.length_m);
  return median(lengths_m);
}

// Each place's neighbours over `links`.
std::vector<std::vector<int>> neighbours_over(const std::vector<MeasuredLink>& links,
                                              std::size_t count) {
  std::vector<std::vector<int>> neighbours(count);
  for (const MeasuredLink& link : links) {
    neighbours[link.places.first].push_back(link.places.second);
    neighbours[link.places.second].push_back(link.places.first);
  }
  return neighbours;
}

// Whether `a` and `b` are at most two links apart.
bool within_two_links(const std::vector<std::vector<int>>& neighbours, int a, int b) {
  if (a == b) return true;
  for (const int c : neighbours[a]) {
    if (c == b) return true;
    for (const int d : neighbours[c]) {
      if (d == b) return true;
    }
  }
  return false;
}

// Where the localiser puts the robot between places on the lattice, when it can tell (the best
// places' positions weighted by similarity, memory::PositionEstimate).
std::optional<Eigen::Vector2d> lattice_position(const memory::Localisation& localisation) {
  if (!localisation.position || localisation.position->frame != memory::PositionFrame::kLattice)
    return std::nullopt;
  return localisation.position->interpolated_position;
}

}  // namespace

const char* phase_name(NavigationPhase phase) {
  switch (phase) {
    case NavigationPhase::kFollowingRoute:
      return "route";
    case NavigationPhase::kHoming:
      return "homing";
    case NavigationPhase::kReturning:
      return "returning";
  }
  return "?";
}

void load_navigator_params(const ConfigReader& section, NavigatorParams& params) {
  section.read("step_m", params.step_m, 0.01, 5.0);
  section.read("max_steps", params.max_steps, 1, 100000);
  section.read("goal_similarity", params.goal_similarity, 0.0, 1000.0);
  section.read("goal_confirmations", params.goal_confirmations, 1, 100);
  section.read("unstick_turn_deg", params.unstick_turn_deg, 0.0, 180.0);
  section.read("look_ahead_links", params.look_ahead_links, 0, 1000);
  section.read("look_ahead_tolerance_spacings", params.look_ahead_tolerance_spacings, 0.0, 10.0);
  section.read("sidesteps", params.sidesteps, 0, 16);
  section.read("sidestep_deg", params.sidestep_deg, 1.0, 90.0);
  section.read("loop_entries", params.loop_entries, 0, 100000);
  section.read("home_on_goal_image", params.home_on_goal_image);
  section.read("homing_step_m", params.homing_step_m, 0.01, 5.0);
  section.read("homing_stop_m", params.homing_stop_m, 0.0, 5.0);
  section.read("homing_step_spacings", params.homing_step_spacings, 0.0, 10.0);
  section.read("homing_stop_spacings", params.homing_stop_spacings, 0.0, 10.0);
  section.read("homing_max_steps", params.homing_max_steps, 0, 100000);
  section.read("recognition_link_ratio", params.recognition_link_ratio, 0.1, 100.0);
  section.read("recognition_place_link_ratio", params.recognition_place_link_ratio, 0.0, 100.0);
  section.read("lost_views", params.lost_views, 0, 100000);
  section.read("lost_jumps", params.lost_jumps, 0, 100000);
  section.read("lost_jump_window", params.lost_jump_window, 1, 100000);
  section.read("recoveries", params.recoveries, 0, 100000);
  section.read("return_max_steps", params.return_max_steps, 0, 100000);
  section.read("stay_within_map_extent", params.stay_within_map_extent);
  section.read("stay_within_lattice_box", params.stay_within_lattice_box);
  section.read("lattice_box_margin_spacings", params.lattice_box_margin_spacings, 0.0, 100.0);
  section.read("stall_spacings", params.stall_spacings, 0.0, 1000.0);
  section.read("stall_other_links", params.stall_other_links);
  // The last sidestep turns farthest: past 180° it would repeat an earlier direction.
  const double widest_deg = std::abs(sidestep_turn(params.sidesteps, params.sidestep_deg));
  if (widest_deg > 180.0) {
    throw ConfigError(fmt::format(
        "{}: keys 'navigator.sidesteps' ({}) and 'navigator.sidestep_deg' ({}) turn the last "
        "sidestep {} degrees from the plan, more than 180: give fewer sidesteps or smaller ones",
        section.source_name(), params.sidesteps, general(params.sidestep_deg),
        general(widest_deg)));
  }
}

namespace {

// One run of the navigator, a small state machine. Each view of the robot is one step:
//   - following the route (§3.5): recognise the place, turn to its direction towards the goal,
//     step. Nothing recognised: drive on straight ahead. The goal's place recognised
//     (goal_confirmations times in a row): arrive, or start homing on the goal image. Views not
//     recognised (beyond the recognition limit) params.lost_views times in a row, or
//     params.lost_jumps jumps within lost_jump_window views: lost, start returning;
//   - homing (homing.hpp): step towards the goal image while it seems nearer; arrive when it
//     seems near enough, farther than at the last view, or when blocked every way;
//   - returning (lost): drive back by dead reckoning to the anchor, where the robot last
//     recognised a place without a jump (or its start). A view recognised on the way, or the
//     anchor reached: follow the route again, planned without the link that led off. When the
//     robot was lost more than params.recoveries times, the anchor reached ends the run: gave up;
//   - arrived: the run ends, the goal reached.
// The run also ends when max_steps views are spent: the goal counts as reached only while
// homing (its place was recognised, as the paper's robot asks).
//
// A blocked move (less than half the step driven) is recovered from in turn by: sidesteps
// (params.sidesteps turns alternately left and right of the planned direction, wider each
// time), then dropping the link to the place's next place and planning again without it, and
// when no route is left round it, escaping: a few steps at an angle from the planned direction.
// Blocked again while escaping, the robot tries the next escape turn: the other side, then
// wider (a robot in a corner between two boxes is blocked both ways at unstick_turn_deg),
// round to the first after 180°. Returning, a blocked move sidesteps wider each time, round
// to straight back; blocked every way, the return ends there.
class NavigationRun {
 public:
  NavigationRun(NavigationWorld& world, const std::vector<PlaceNode>& places, const RoutePlan& plan,
                const RoutePlan& fallback, const PanoramaLocaliser& localise,
                const NavigatorParams& params, const GoalHoming& homing, double recognition_limit,
                const std::vector<double>& place_recognition_limits)
      : world_(world),
        places_(places),
        localise_(localise),
        params_(params),
        homing_(homing),
        recognition_limit_(recognition_limit),
        place_recognition_limits_(place_recognition_limits),
        plan_(plan),
        fallback_(fallback),
        look_ahead_tolerance_m_(params.look_ahead_links > 1
                                    ? params.look_ahead_tolerance_spacings * lattice_spacing(places)
                                    : 0.0),
        entries_(places.size(), 0),
        link_neighbours_(neighbours_over(plan.measured.empty() ? fallback.measured : plan.measured,
                                         places.size())),
        extent_m_(params.stay_within_map_extent ? map_extent_m(places, plan)
                                                : std::numeric_limits<double>::infinity()),
        spacing_m_(params.stall_m > 0.0 && params.stall_spacings > 0.0
                       ? params.stall_m / params.stall_spacings
                       : spacing_of(places, plan.measured.empty() ? fallback : plan)),
        stall_m_(params.stall_spacings * spacing_m_) {
    if (!places.empty()) {
      box_low_ = box_high_ = places.front().position_m;
      for (const PlaceNode& node : places) {
        box_low_ = box_low_.cwiseMin(node.position_m);
        box_high_ = box_high_.cwiseMax(node.position_m);
      }
      const double margin_m = params.lattice_box_margin_spacings * lattice_spacing(places);
      box_low_ -= Eigen::Vector2d::Constant(margin_m);
      box_high_ += Eigen::Vector2d::Constant(margin_m);
    }
  }

  NavigationResult run() {
    for (int index = 0;
         index < params_.max_steps && state_ != State::kArrived && state_ != State::kGaveUp;
         ++index) {
      take_step(index);
    }
    result_.reached = state_ == State::kArrived || state_ == State::kHoming;
    result_.gave_up = state_ == State::kGaveUp;
    return std::move(result_);
  }

 private:
  enum class State { kFollowingRoute, kHoming, kReturning, kArrived, kGaveUp };

  void take_step(int index) {
    NavigationStep step;
    step.index = index;
    step.truth = world_.truth();
    const cv::Mat view = world_.view(index);
    const memory::Localisation localisation = localise_(view);
    if (!localisation.best.empty()) step.match = localisation.best.front();
    step.recognised =
        step.match && is_recognised(*step.match, recognition_limit_, place_recognition_limits_);
    const int place = place_of(step);
    if (place >= 0) {
      step.heading_estimate_rad =
          wrap_angle(places_[place].heading_rad + step.match->relative_heading_rad);
    }
    if (state_ == State::kReturning) {
      step.phase = NavigationPhase::kReturning;
      go_back(step, place, localisation);
      return;
    }
    if (state_ == State::kFollowingRoute) {
      if (place >= 0) note_jump(step, place);
      const bool at_goal = place >= 0 && goal_confirmed(step, place);
      if (!at_goal && (lost(step) || beyond_extent())) {
        lose_way(step);
        go_back(step, place, localisation);
        return;
      }
      if (!at_goal && budget_only_lasts_the_way_back(index)) {
        give_up(step);
        go_back(step, place, localisation);
        return;
      }
      if (step.recognised && !step.jump) {
        correct_heading(step, place);
        note_recognised(place);
      }
      if (step.recognised && !step.jump && within_map(position_)) set_anchor(place);
      if (place < 0) {
        drive_blind(step);
        return;
      }
      if (at_goal) {
        if (!homing_ || !params_.home_on_goal_image || params_.homing_max_steps == 0) {
          result_.steps.push_back(step);
          state_ = State::kArrived;
          return;
        }
        start_homing();
      }
    }
    if (state_ == State::kHoming) {
      step.phase = NavigationPhase::kHoming;
      home(step, view);
    } else {
      check_progress(step, place);
      follow_route(step, place, localisation);
    }
  }

  // Following the route: a recognised view (without a jump) of a place nearer the goal by the
  // plan than every place before is progress; stall_m driven without progress is a stall.
  void check_progress(NavigationStep& step, int place) {
    if (stall_m_ <= 0.0) return;
    // Against the lowest cost when it was reached, not in the plan as it is now: a replan round
    // a blocked link raises the cost of the places before it, and a robot blocked between two
    // places would see each in turn come nearer by the other's replan.
    if (step.recognised && !step.jump && plan_.cost_m[place] < nearest_cost_m_) {
      nearest_cost_m_ = plan_.cost_m[place];
      nearest_place_ = place;
      since_progress_m_ = 0.0;
      return;
    }
    if (nearest_place_ < 0) return;
    since_progress_m_ += params_.step_m;
    if (since_progress_m_ > stall_m_) stall(step);
  }

  // Stalled: distrust the link from the nearest place reached to its next (the robot kept
  // missing where it leads), plan again without it, and (stall_other_links) go on over the
  // plan of the other link set when the robot's own motion says that set is the better here:
  // the lattice when it explains the robot's motion (lattice_follows_motion), the motions when
  // it does not.
  void stall(NavigationStep& step) {
    step.stalled = true;
    ++result_.stalls;
    if (replan_without_link(places_, nearest_place_, plan_)) ++result_.replans;
    if (params_.stall_other_links && fallback_.goal >= 0) {
      const std::optional<bool> lattice_fits = lattice_follows_motion();
      const bool over_lattice = plan_.measured.empty();
      if (lattice_fits && *lattice_fits != over_lattice) {
        std::swap(plan_, fallback_);
        ++result_.link_switches;
      }
    }
    forget_progress();
  }

  // A view recognised without a jump: its place and where the dead reckoning put the robot.
  void note_recognised(int place) {
    recognised_views_.push_back({place, position_});
    if (recognised_views_.size() > kMotionMemory) recognised_views_.pop_front();
  }

  // Whether the lattice explains the robot's own motion where it drove: over the pairs of the
  // recent recognised views at least two spacings apart by dead reckoning, the median
  // difference between the distance of their places on the lattice (in lattice spacings) and
  // the distance driven between them (in the map's spacings) is at most one spacing (each view
  // lies within half a cell's diagonal of its place, so two views of a true lattice differ by
  // less). None without such pairs.
  std::optional<bool> lattice_follows_motion() const {
    const double lattice_spacing_m = lattice_spacing(places_);
    if (lattice_spacing_m <= 0.0 || spacing_m_ <= 0.0) return std::nullopt;
    std::vector<double> differences;
    for (std::size_t i = 0; i < recognised_views_.size(); ++i) {
      for (std::size_t j = i + 1; j < recognised_views_.size(); ++j) {
        const double driven =
            (recognised_views_[i].at_m - recognised_views_[j].at_m).norm() / spacing_m_;
        if (driven < 2.0) continue;
        const double on_lattice = (places_[recognised_views_[i].place].position_m -
                                   places_[recognised_views_[j].place].position_m)
                                      .norm() /
                                  lattice_spacing_m;
        differences.push_back(std::abs(on_lattice - driven));
      }
    }
    if (differences.empty()) return std::nullopt;
    return median(differences) <= 1.0;
  }

  void forget_progress() {
    nearest_cost_m_ = std::numeric_limits<double>::infinity();
    nearest_place_ = -1;
    since_progress_m_ = 0.0;
  }

  // Turns by `turn_rad` and drives up to `distance_m`; keeps the dead reckoning (the robot's
  // own record of its turns and distances, in the frame of its start) and the path length.
  double drive(double turn_rad, double distance_m) {
    heading_rad_ = wrap_angle(heading_rad_ + turn_rad);
    const double driven = world_.move(turn_rad, distance_m);
    position_ += driven * Eigen::Vector2d(std::cos(heading_rad_), std::sin(heading_rad_));
    result_.path_length_m += driven;
    return driven;
  }

  // Nothing recognised (an empty candidate set): go on straight ahead.
  void drive_blind(NavigationStep& step) {
    drive(0.0, params_.step_m);
    result_.steps.push_back(step);
  }

  // A jump: neither where the robot was, nor where it was heading, nor next to either.
  void note_jump(NavigationStep& step, int place) {
    if (expected_ < 0) return;
    const int previous = previous_place();
    if (!plan_.measured.empty()) {
      // Over measured links the lattice is not trusted: near means at most two links away (two
      // steps of the robot are about one link).
      step.jump = !within_two_links(link_neighbours_, place, expected_) &&
                  (previous < 0 || !within_two_links(link_neighbours_, place, previous));
      result_.jumps += step.jump ? 1 : 0;
      return;
    }
    const Eigen::Vector2d here = places_[place].position_m;
    const double near_m = 2.0 * params_.step_m + 1e-9;
    step.jump = (here - places_[expected_].position_m).norm() > near_m &&
                (previous < 0 || (here - places_[previous].position_m).norm() > near_m);
    result_.jumps += step.jump ? 1 : 0;
  }

  // Lost: lost_views views in a row not recognised that do not look more like the map than the
  // others of the row (a robot coming onto the map sees its best place nearer with every view),
  // or twice as many not recognised anyway, or lost_jumps jumps within the last
  // lost_jump_window views.
  bool lost(const NavigationStep& step) {
    if (step.recognised) {
      forget_unrecognised();
    } else {
      const double d = step.match ? step.match->dissimilarity_per_value
                                  : std::numeric_limits<double>::infinity();
      ++unrecognised_;
      if (d < nearest_unrecognised_) {
        nearest_unrecognised_ = d;
      } else {
        ++not_nearer_;
      }
    }
    if (step.jump) jump_views_.push_back(step.index);
    while (!jump_views_.empty() && step.index - jump_views_.front() >= params_.lost_jump_window) {
      jump_views_.pop_front();
    }
    return (params_.lost_views > 0 &&
            (not_nearer_ >= params_.lost_views || unrecognised_ >= 2 * params_.lost_views)) ||
           (params_.lost_jumps > 0 && static_cast<int>(jump_views_.size()) >= params_.lost_jumps);
  }

  // A recognised view measures the robot's heading against the place's image (Eq. 1's phases),
  // in the lattice frame, whose angle to the dead reckoning's frame the first such view fixes:
  // later ones put the dead reckoning's heading right again (each turn adds turn_noise, and the
  // returns and the map's extent rely on it). A measure far off the dead reckoning's (more than
  // kHeadingOutlierDeg: a look-alike place facing another way) is left out.
  void correct_heading(const NavigationStep& step, int place) {
    if (!lattice_to_dead_reckoning_rad_) {
      lattice_to_dead_reckoning_rad_ = signed_difference(step.heading_estimate_rad, heading_rad_);
      lattice_origin_ = places_[place].position_m;
      dead_reckoning_origin_ = position_;
      return;
    }
    const double measured_rad =
        wrap_angle(step.heading_estimate_rad - *lattice_to_dead_reckoning_rad_);
    if (std::abs(signed_difference(measured_rad, heading_rad_)) <= deg_to_rad(kHeadingOutlierDeg)) {
      heading_rad_ = measured_rad;
    }
  }

  // Farther from its start, by its own dead reckoning, than the map is across: it cannot be on
  // the map any more, whatever it recognises (where the views of the map look as unlike each
  // other as anything off it, a field seen from 10 cm, off-map views still match). The way
  // back is then to the start, or to an anchor set within that reach.
  bool beyond_extent() {
    if (within_map(position_)) return false;
    if (!within_map(anchor_)) {
      anchor_ = Eigen::Vector2d::Zero();
      anchor_place_ = -1;
    }
    return true;
  }

  // Within the map's extent from the start, and (stay_within_lattice_box) with the dead
  // reckoning carried onto the lattice from the first recognised place, within the lattice's
  // bounding box grown by lattice_box_margin_spacings.
  bool within_map(const Eigen::Vector2d& at) const {
    if (at.norm() > extent_m_) return false;
    if (!params_.stay_within_lattice_box || !lattice_to_dead_reckoning_rad_) return true;
    const Eigen::Vector2d on_lattice =
        lattice_origin_ +
        Eigen::Rotation2Dd(*lattice_to_dead_reckoning_rad_) * (at - dead_reckoning_origin_);
    return (on_lattice.array() >= box_low_.array()).all() &&
           (on_lattice.array() <= box_high_.array()).all();
  }

  void forget_unrecognised() {
    unrecognised_ = 0;
    not_nearer_ = 0;
    nearest_unrecognised_ = std::numeric_limits<double>::infinity();
  }

  // Where the robot last knew where it was: this view recognised `place`, without a jump.
  void set_anchor(int place) {
    anchor_ = position_;
    anchor_place_ = place;
    probe_turns_ = 0;
  }

  // Lost: turn back towards the anchor. Past the recoveries' budget, the return is the last.
  void lose_way(NavigationStep& step) {
    step.lost = true;
    ++result_.lost_events;
    turn_back(step, result_.lost_events > params_.recoveries);
  }

  // The steps left only just take the robot back to its start (by its dead reckoning, with two
  // steps to spare): rather than end wherever the budget runs out (where look-alikes led it,
  // an office's desks repeating beyond the map), it gives up and goes back.
  bool budget_only_lasts_the_way_back(int index) const {
    if (!params_.stay_within_map_extent) return false;
    const double left_m = (params_.max_steps - index) * params_.step_m;
    return left_m <= position_.norm() + 2.0 * params_.step_m;
  }

  void give_up(NavigationStep& step) { turn_back(step, true); }

  // Turns back towards the anchor (giving up: the start), as the state says.
  void turn_back(NavigationStep& step, bool giving_up) {
    step.phase = NavigationPhase::kReturning;
    state_ = State::kReturning;
    giving_up_ = giving_up;
    return_steps_ = 0;
    sidestep_ = 0;
    escape_steps_left_ = 0;
    forget_unrecognised();
    jump_views_.clear();
    expected_ = -1;
    // Giving up, the robot goes back to its start, where it was put (on the map, in the
    // trials), rather than to the anchor: where the map's views look alike (a field seen from
    // 10 cm) a view off the map may still have been recognised and anchored. Its dead
    // reckoning's heading is kept right by the recognised views (correct_heading).
    if (giving_up_) {
      anchor_ = Eigen::Vector2d::Zero();
      return;
    }
    // The link followed from the anchor led off the map: plan without it (from the start,
    // without an anchor, the next try turns aside instead).
    if (anchor_place_ >= 0) {
      if (replan_without_link(places_, anchor_place_, plan_)) ++result_.replans;
    } else {
      ++probe_turns_;
    }
  }

  // Returning: a view recognised on the way (not the first, which found the robot lost) ends
  // it; so does reaching the anchor, or the return's budget: follow the route again, or, when
  // giving up, stop.
  void go_back(NavigationStep& step, int place, const memory::Localisation& localisation) {
    if (step.recognised && !step.lost && !giving_up_) {
      ++result_.recoveries;
      resume();
      if (within_map(position_)) set_anchor(place);
      step.phase = NavigationPhase::kFollowingRoute;
      follow_route(step, place, localisation);
      return;
    }
    const Eigen::Vector2d to = anchor_ - position_;
    // (Giving up, the way back to the start is bounded by max_steps alone.)
    if (to.norm() <= 0.25 * params_.step_m ||
        (!giving_up_ && return_steps_ >= params_.return_max_steps)) {
      result_.steps.push_back(step);
      if (giving_up_) {
        state_ = State::kGaveUp;
      } else {
        resume();
      }
      return;
    }
    const double distance_m = std::min(to.norm(), params_.step_m);
    step.turn_rad = signed_difference(std::atan2(to.y(), to.x()), heading_rad_) +
                    sidestep_turn(sidestep_, deg_to_rad(params_.sidestep_deg));
    const double driven = drive(step.turn_rad, distance_m);
    ++return_steps_;
    if (driven >= 0.5 * distance_m) {
      sidestep_ = 0;
    } else if (std::abs(sidestep_turn(sidestep_ + 1, params_.sidestep_deg)) <= 180.0 + 1e-9) {
      // Blocked: the way back lies beyond furniture (or the dead reckoning says it lies through
      // a wall). Unlike on the route there is no link to drop: turn wider each time, round to
      // straight back.
      ++sidestep_;
      ++result_.sidesteps;
    } else {
      // Blocked every way round: this is as far back as the robot gets.
      result_.steps.push_back(step);
      sidestep_ = 0;
      if (giving_up_) {
        state_ = State::kGaveUp;
      } else {
        resume();
      }
      return;
    }
    result_.steps.push_back(step);
  }

  // Back on the route (after being lost): following again, with a fresh count of views not
  // recognised; from the start (no anchor) the next moves turn by the probe's angle.
  void resume() {
    state_ = State::kFollowingRoute;
    sidestep_ = 0;
    forget_unrecognised();
    forget_progress();
    probe_turn_rad_ =
        anchor_place_ < 0 ? sidestep_turn(probe_turns_, deg_to_rad(kProbeTurnDeg)) : 0.0;
  }

  // The goal's place recognised (within the recognition limit, with the goal similarity),
  // goal_confirmations views in a row.
  bool goal_confirmed(const NavigationStep& step, int place) {
    if (place != plan_.goal || !step.recognised ||
        step.match->similarity < params_.goal_similarity) {
      goal_matches_ = 0;
      return false;
    }
    return ++goal_matches_ >= params_.goal_confirmations;
  }

  // From here on, home on the goal image (no view to compare this first one with yet).
  void start_homing() {
    state_ = State::kHoming;
    homing_from_ = kNoCue;
    sidestep_ = 0;
  }

  // Step towards the goal image, as far as it seems to be (up to a homing step), while it seems
  // farther than homing_stop_m and nearer than at the last view; arrive when it seems farther
  // (the last step passed the goal), when the phases show no displacement (at the goal), or
  // when the homing budget is spent.
  void home(NavigationStep& step, const cv::Mat& view) {
    const GoalCue cue = homing_(view);
    if (cue.distance_m <= params_.homing_stop_m || cue.distance_m >= homing_from_.distance_m ||
        !cue.valid || result_.homing_steps >= params_.homing_max_steps) {
      result_.steps.push_back(step);
      state_ = State::kArrived;
      return;
    }
    step.turn_rad = cue.bearing_rad + sidestep_turn(sidestep_, deg_to_rad(params_.sidestep_deg));
    const double distance_m = std::min(cue.distance_m, params_.homing_step_m);
    const double driven = drive(step.turn_rad, distance_m);
    ++result_.homing_steps;
    result_.steps.push_back(step);
    if (driven >= 0.5 * distance_m) {
      // After a sidestep the goal may well seem farther: the next view starts afresh.
      homing_from_ = sidestep_ == 0 ? cue : kNoCue;
      sidestep_ = 0;
    } else if (sidestep_ < params_.sidesteps) {
      // Blocked: the goal lies beyond a corner of furniture. Sidestep as on the way, and judge
      // the next view against the last one that moved (this one saw the same).
      ++sidestep_;
      ++result_.sidesteps;
    } else {
      state_ = State::kArrived;  // blocked every way: this is as near as the robot gets
    }
  }

  // Turn to the place's direction (recovering from a block as the state says), step, and
  // recover from a block this step met.
  void follow_route(NavigationStep& step, int place, const memory::Localisation& localisation) {
    leave_loop(place);
    double direction_in_place = route_direction(step, place, localisation);
    const bool escaping = escape_steps_left_ > 0;
    if (escaping) {
      direction_in_place += sidestep_turn(escape_turn_, deg_to_rad(params_.unstick_turn_deg));
      --escape_steps_left_;
    } else {
      direction_in_place += sidestep_turn(sidestep_, deg_to_rad(params_.sidestep_deg));
      result_.sidesteps += sidestep_ > 0 ? 1 : 0;
    }
    // Looking for the map from the start: the probe's turn until a view is recognised.
    if (anchor_place_ < 0) direction_in_place += probe_turn_rad_;
    step.turn_rad = signed_difference(direction_in_place, step.match->relative_heading_rad);
    const double driven = drive(step.turn_rad, params_.step_m);
    if (driven >= 0.5 * params_.step_m) {
      sidestep_ = 0;
    } else if (!escaping && sidestep_ < params_.sidesteps) {
      ++sidestep_;
    } else {
      drop_link_or_escape(place, escaping);
    }
    expected_ = plan_.next[place] >= 0 ? plan_.next[place] : place;
    result_.steps.push_back(step);
  }

  // Going round in circles: entering the same place again and again. Its direction leads into
  // places whose directions lead back; plan again without the link it follows.
  void leave_loop(int place) {
    if (place != previous_place() && params_.loop_entries > 0 &&
        ++entries_[place] >= params_.loop_entries && place != plan_.goal) {
      entries_[place] = 0;
      if (replan_without_link(places_, place, plan_)) ++result_.loops;
    }
  }

  // The direction to turn to, relative to the place's own heading: the robot's heading relative
  // to the place is what the image tells, whatever the lattice. The place's direction towards
  // its next place; at the goal or without a route, straight on.
  double route_direction(const NavigationStep& step, int place,
                         const memory::Localisation& localisation) const {
    if (place == plan_.goal || !plan_.reaches_goal(place)) return step.match->relative_heading_rad;
    const std::optional<Eigen::Vector2d> position = lattice_position(localisation);
    if (params_.look_ahead_links > 0 && position && sidestep_ == 0 && plan_.measured.empty()) {
      // Sidesteps turn from the place's own direction instead: the line ahead led into the
      // obstacle, and turning from the place's next link measured better. A plan over measured
      // links does not trust the lattice: the look-ahead's line is drawn on it.
      const int target = look_ahead_place(places_, plan_, place, params_.look_ahead_links,
                                          look_ahead_tolerance_m_, blocked_);
      const Eigen::Vector2d to = places_[target].position_m - *position;
      if (to.norm() > 1e-9) {
        return signed_difference(std::atan2(to.y(), to.x()), places_[place].heading_rad);
      }
    }
    return plan_.direction_in_place_rad[place];
  }

  // The sidesteps are spent (or the robot was escaping): drop the place's link to its next
  // place and plan again without it; when no route is left round it (or escaping), escape with
  // the next escape turn.
  void drop_link_or_escape(int place, bool escaping) {
    sidestep_ = 0;
    if (!escaping && plan_.next[place] >= 0) blocked_.emplace_back(place, plan_.next[place]);
    if (escaping || !replan_without_link(places_, place, plan_)) {
      escape_turn_ = escaping ? escape_turn_ + 1 : 1;
      if (std::abs(sidestep_turn(escape_turn_, params_.unstick_turn_deg)) > 180.0) escape_turn_ = 1;
      escape_steps_left_ = kEscapeSteps;
    } else {
      ++result_.replans;
    }
  }

  int previous_place() const { return result_.steps.empty() ? -1 : place_of(result_.steps.back()); }

  // Looking for the map from its start, the robot turns this far from the plan's direction
  // after each time it found itself lost (sidestep_turn's units: 90°, -90°, 180°, ...).
  static constexpr double kProbeTurnDeg = 90.0;
  static constexpr double kHeadingOutlierDeg = 30.0;

  NavigationWorld& world_;
  const std::vector<PlaceNode>& places_;
  const PanoramaLocaliser& localise_;
  const NavigatorParams& params_;
  const GoalHoming& homing_;
  const double recognition_limit_;
  const std::vector<double>& place_recognition_limits_;  // per place; empty: recognition_limit_

  State state_ = State::kFollowingRoute;
  NavigationResult result_;
  RoutePlan plan_;             // made again without the links found blocked
  RoutePlan fallback_;         // over the other link set (goal -1: none); swapped in on a stall
  int expected_ = -1;          // the place the plan said the robot would reach next
  int goal_matches_ = 0;       // consecutive views of the goal's place
  int sidestep_ = 0;           // sidesteps tried since the last move that was not blocked
  int escape_steps_left_ = 0;  // > 0: escaping
  int escape_turn_ = 0;        // the escape turn in use (sidestep_turn's count)
  std::vector<Edge> blocked_;  // links found blocked: the look-ahead keeps away from them
  const double look_ahead_tolerance_m_;
  std::vector<int> entries_;  // times each place was entered (loops)
  // Each place's neighbours over the plan's measured links, as planned (none over the lattice).
  const std::vector<std::vector<int>> link_neighbours_;
  const double extent_m_;  // the diagonal of the lattice's bounding box (or ∞)
  // The map's spacing: from stall_m when given, else as the plan tells it (spacing_of).
  const double spacing_m_;
  const double stall_m_;  // driven without progress: stalled (0: never)
  // The recent views recognised without a jump (at most kMotionMemory), for
  // lattice_follows_motion.
  struct RecognisedView {
    int place;
    Eigen::Vector2d at_m;  // dead reckoning
  };
  static constexpr std::size_t kMotionMemory = 60;
  std::deque<RecognisedView> recognised_views_;
  // Progress: the place nearest the goal by the plan recognised since the last stall or return
  // (-1: none yet), its cost then, and the distance driven since.
  int nearest_place_ = -1;
  double nearest_cost_m_ = std::numeric_limits<double>::infinity();
  double since_progress_m_ = 0.0;  // step_m a step, blocked or not
  GoalCue homing_from_ = kNoCue;   // homing: the cue of the last view that moved

  // Dead reckoning, in the frame of the robot's start (the robot at the origin facing +x).
  Eigen::Vector2d position_ = Eigen::Vector2d::Zero();
  double heading_rad_ = 0.0;
  std::optional<double> lattice_to_dead_reckoning_rad_;       // set by the first recognised view
  Eigen::Vector2d lattice_origin_ = Eigen::Vector2d::Zero();  // that view's place on the lattice
  Eigen::Vector2d dead_reckoning_origin_ = Eigen::Vector2d::Zero();  // ... and by dead reckoning
  Eigen::Vector2d box_low_ = Eigen::Vector2d::Zero();   // the lattice's bounding box, grown
  Eigen::Vector2d box_high_ = Eigen::Vector2d::Zero();  // by lattice_box_margin_spacings
  // Lost and found.
  int unrecognised_ = 0;  // views in a row whose best place lies beyond the limit
  int not_nearer_ = 0;    // ... of them no nearer to the map than the nearest before
  double nearest_unrecognised_ = std::numeric_limits<double>::infinity();  // its dissimilarity
  std::deque<int> jump_views_;  // the views of the last jumps (within lost_jump_window)
  Eigen::Vector2d anchor_ = Eigen::Vector2d::Zero();  // where a place was last recognised
  int anchor_place_ = -1;        // that place; -1: none since the start (the anchor is the start)
  bool giving_up_ = false;       // the return under way is the last
  int return_steps_ = 0;         // steps of the return under way
  int probe_turns_ = 0;          // times lost without an anchor
  double probe_turn_rad_ = 0.0;  // the turn from the plan while looking for the map from the start
};

}  // namespace

NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const PanoramaLocaliser& localise,
                          const NavigatorParams& params, const GoalHoming& homing,
                          double recognition_limit) {
  return navigate(world, places, plan, localise, params, homing, recognition_limit, {});
}

NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const PanoramaLocaliser& localise,
                          const NavigatorParams& params, const GoalHoming& homing,
                          double recognition_limit,
                          const std::vector<double>& place_recognition_limits) {
  return navigate(world, places, plan, RoutePlan{}, localise, params, homing, recognition_limit,
                  place_recognition_limits);
}

NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const RoutePlan& fallback,
                          const PanoramaLocaliser& localise, const NavigatorParams& params,
                          const GoalHoming& homing, double recognition_limit,
                          const std::vector<double>& place_recognition_limits) {
  if (!place_recognition_limits.empty() && place_recognition_limits.size() != places.size()) {
    throw UsageError("navigate: " + std::to_string(place_recognition_limits.size()) +
                     " recognition limits for " + std::to_string(places.size()) + " places");
  }
  if (fallback.goal >= 0 && fallback.goal != plan.goal) {
    throw UsageError("navigate: the fallback plan leads to place " + std::to_string(fallback.goal) +
                     ", the plan to place " + std::to_string(plan.goal));
  }
  return NavigationRun(world, places, plan, fallback, localise, params, homing, recognition_limit,
                       place_recognition_limits)
      .run();
}

}  // namespace omninav::navigation
