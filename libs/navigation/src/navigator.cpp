#include "omninav/navigation/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::navigation {

const char* phase_name(NavigationPhase phase) {
  switch (phase) {
    case NavigationPhase::kFollowingRoute:
      return "route";
    case NavigationPhase::kHoming:
      return "homing";
  }
  return "?";
}

void NavigatorParams::check() const {
  check_range("navigator.step_m", step_m, 0.01, 5.0);
  check_range("navigator.max_steps", max_steps, 1, 100000);
  check_range("navigator.homing_step_m", homing_step_m, 0.01, 5.0);
  check_range("navigator.homing_stop_m", homing_stop_m, 0.0, 5.0);
  check_range("navigator.homing_step_spacings", homing_step_spacings, 0.0, 10.0);
  check_range("navigator.homing_stop_spacings", homing_stop_spacings, 0.0, 10.0);
  check_range("navigator.homing_max_steps", homing_max_steps, 0, 100000);
}

void load_navigator_params(const ConfigReader& section, NavigatorParams& params) {
  section.read("step_m", params.step_m);
  section.read("max_steps", params.max_steps);
  section.read("home_on_goal_image", params.home_on_goal_image);
  section.read("homing_step_m", params.homing_step_m);
  section.read("homing_stop_m", params.homing_stop_m);
  section.read("homing_step_spacings", params.homing_step_spacings);
  section.read("homing_stop_spacings", params.homing_stop_spacings);
  section.read("homing_max_steps", params.homing_max_steps);
  check_loaded(section.source_name(), [&] { params.check(); });
}

namespace {

// A place whose probability is below this share of the most probable one's is not worth the
// phases' heading: its prediction keeps its (negligible) probability in place.
constexpr double kNegligibleShare = 1e-4;
// Blocked, the robot turns aside by this, then twice, ... alternately left and right, this many
// times, before it drops the link it was following.
constexpr double kSidestepDeg = 30.0;
constexpr int kSidesteps = 4;
// The goal's place must hold at least this much of the belief for the robot to home.
constexpr double kArrivalShare = 0.25;
// The robot changes the place it acts on when another is this many times as probable (or is
// the one it was heading for).
constexpr double kSwitchRatio = 2.0;
// A link the robot drove this many times its length along without arriving is dropped.
constexpr double kUnfollowedLinks = 3.0;

double sidestep_turn(int sidestep) {
  if (sidestep == 0) return 0.0;
  const int size = (sidestep + 1) / 2;
  return (sidestep % 2 == 1 ? 1.0 : -1.0) * size * deg_to_rad(kSidestepDeg);
}

class NavigationRun {
 public:
  NavigationRun(NavigationWorld& world, const GoalNavigationSetup& setup, int goal,
                const GoalHoming& homing)
      : world_(world),
        setup_(setup),
        params_(setup.navigator),
        homing_(homing),
        links_(setup.links),
        plan_(plan_to_goal(setup.places, links_, goal)),
        belief_(setup.places.size(), links_, setup.belief.view_scale * setup.link_dissimilarity,
                setup.belief),
        motion_(setup.places.size(), std::numeric_limits<double>::quiet_NaN()),
        in_place_(setup.places.size(), std::numeric_limits<double>::quiet_NaN()),
        dissimilarity_(setup.places.size(), 0.0) {}

  NavigationResult run() {
    for (int index = 0; index < params_.max_steps && !arrived_; ++index) step(index);
    result_.reached = arrived_ || homing_started_;
    return std::move(result_);
  }

 private:
  void step(int index) {
    NavigationStep step;
    step.index = index;
    step.truth = world_.truth();
    const cv::Mat view = world_.view(index);
    const signature::Signature signature = setup_.signature_of(view);
    for (std::size_t p = 0; p < dissimilarity_.size(); ++p) {
      dissimilarity_[p] =
          signature::dissimilarity(signature, setup_.signatures[p], -1, setup_.weights) /
          static_cast<double>(signature.size());
    }
    if (index > 0) belief_.predict(motion_, driven_);
    // A robot that did not move sees what it saw: the same evidence again, not new evidence
    // (counted twice, a view's look-alike would win by repetition).
    if (index == 0 || driven_ > 0.0) belief_.update(dissimilarity_);
    const int place = acting_place();
    measure_headings(signature, place);
    const double in_place = in_place_[place];
    memory::PlaceMatch match;
    match.place = static_cast<memory::PlaceIndex>(place);
    match.dissimilarity_per_value = dissimilarity_[place];
    match.similarity = 1000.0 * belief_.probability(place);
    match.relative_heading_rad = in_place;
    step.match = match;
    step.heading_estimate_rad = wrap_angle(setup_.places[place].heading_rad + in_place);
    step.lost = belief_.lost();
    step.recognised = !step.lost;
    if (step.lost && !was_lost_) ++result_.lost_events;
    was_lost_ = step.lost;
    if (previous_place_ >= 0 && place != previous_place_ && !linked(previous_place_, place)) {
      step.jump = true;
      ++result_.jumps;
    }
    previous_place_ = place;

    // Arrived at the goal's place: the belief is on it (the most probable place, holding at
    // least the confident share of the belief with its linked places, and at least
    // kArrivalShare itself: on a small map a place's linked places are much of the map).
    const bool at_goal = belief_.most_likely() == plan_.goal && !step.lost &&
                         belief_.probability(plan_.goal) >= kArrivalShare;
    if (!homing_started_ && at_goal) {
      if (!homing_ || !params_.home_on_goal_image || params_.homing_max_steps == 0) {
        result_.steps.push_back(step);
        arrived_ = true;
        return;
      }
      homing_started_ = true;
      homing_from_ = std::numeric_limits<double>::infinity();
      sidestep_ = 0;
    }
    if (homing_started_) {
      step.phase = NavigationPhase::kHoming;
      home(step, view);
      return;
    }
    follow_route(step, place, in_place, view);
  }

  // The view's heading relative to every place that holds some of the belief (and to `place`),
  // from the phases; NaN for the others.
  void measure_headings(const signature::Signature& signature, int place) {
    const std::vector<double>& probability = belief_.probabilities();
    const double most = *std::max_element(probability.begin(), probability.end());
    for (std::size_t p = 0; p < in_place_.size(); ++p) {
      in_place_[p] = probability[p] >= kNegligibleShare * most || static_cast<int>(p) == place
                         ? signature::relative_heading(setup_.signatures[p], signature).turn_rad
                         : std::numeric_limits<double>::quiet_NaN();
    }
  }

  // The place the robot acts on: the most probable place that has a route to the goal (the
  // most probable of all when none has).
  // A robot between two places keeps acting on the one it acted on (and so drives on along its
  // link) until the belief reaches that link's far end or clearly prefers another place: the
  // most probable place changing back and forth would turn it to and fro.
  int acting_place() const {
    const std::vector<double>& probability = belief_.probabilities();
    int best = belief_.most_likely();
    const int kept = previous_place_;
    if (kept >= 0 && best != kept && plan_.reaches_goal(kept) && best != plan_.next[kept] &&
        probability[best] < kSwitchRatio * probability[kept]) {
      return kept;
    }
    if (plan_.reaches_goal(best)) return best;
    double best_probability = -1.0;
    for (std::size_t p = 0; p < probability.size(); ++p) {
      if (plan_.reaches_goal(static_cast<int>(p)) && probability[p] > best_probability) {
        best_probability = probability[p];
        best = static_cast<int>(p);
      }
    }
    return best;
  }

  // Turns to the plan's direction at the belief's place and steps. Blocked, the robot has met
  // what the map's links do not show (furniture, a wall between grid neighbours): the links
  // that lead the way it tried, from every place the belief holds, are dropped and the plan is
  // made again without them.
  void follow_route(NavigationStep& step, int place, double in_place, const cv::Mat& view) {
    const double direction =
        plan_.reaches_goal(place) ? plan_.direction_in_place_rad[place] : in_place;
    step.turn_rad = signed_difference(direction + sidestep_turn(sidestep_), in_place);
    // At the goal's place by the belief, not yet sure enough to home: the goal image says
    // which way the goal lies (the goal's place has no direction of its own).
    if (place == plan_.goal && homing_) {
      const GoalCue cue = homing_(view);
      step.turn_rad = wrap_angle((cue.valid ? cue.bearing_rad : 0.0) + sidestep_turn(sidestep_));
    }
    check_progress(place);
    drive(step.turn_rad, params_.step_m);
    since_progress_m_ += driven_;
    if (driven_ >= 0.5 * params_.step_m) {
      sidestep_ = 0;
    } else if (sidestep_ < kSidesteps) {
      // Most blocks graze furniture beside the link: turning a little aside slides past it.
      ++sidestep_;
      ++result_.sidesteps;
    } else {
      sidestep_ = 0;
      if (!belief_.lost()) drop_link(place, plan_.next[place]);
    }
    result_.steps.push_back(step);
  }

  // The link between a and b cannot be driven: the plan is made again without it.
  void drop_link(int a, int b) {
    if (a < 0 || b < 0) return;
    std::erase_if(links_, [&](const MeasuredLink& link) {
      return link.places == PlacePair(a, b) || link.places == PlacePair(b, a);
    });
    belief_.remove_link(a, b);
    plan_ = plan_to_goal(setup_.places, links_, plan_.goal);
    ++result_.replans;
  }

  // A link the robot cannot follow: it drove kUnfollowedLinks times the link's length (and a
  // step) since the belief last came to a place nearer the goal, and is not there yet. The
  // link from that place is dropped (a revisit whose direction misleads, a passage too narrow)
  // and the plan made again without it.
  void check_progress(int place) {
    const double cost = plan_.cost_m[place];
    if (cost < progress_cost_ - 1e-9) {
      progress_cost_ = cost;
      progress_place_ = place;
      since_progress_m_ = 0.0;
      return;
    }
    if (progress_place_ < 0 || plan_.next[progress_place_] < 0) return;
    const int next = plan_.next[progress_place_];
    const double length = plan_.cost_m[progress_place_] - plan_.cost_m[next];
    if (since_progress_m_ <= kUnfollowedLinks * length + params_.step_m) return;
    drop_link(progress_place_, next);
    progress_cost_ = plan_.cost_m[place];
    progress_place_ = place;
    since_progress_m_ = 0.0;
  }

  // Homing on the goal image (homing.hpp): step towards it while it seems nearer than at the
  // last view and farther than homing_stop_m.
  void home(NavigationStep& step, const cv::Mat& view) {
    const GoalCue cue = homing_(view);
    if (cue.distance_m <= params_.homing_stop_m || cue.distance_m >= homing_from_ || !cue.valid ||
        result_.homing_steps >= params_.homing_max_steps) {
      result_.steps.push_back(step);
      arrived_ = true;
      return;
    }
    step.turn_rad = cue.bearing_rad + sidestep_turn(sidestep_);
    const double distance_m = std::min(cue.distance_m, params_.homing_step_m);
    drive(step.turn_rad, distance_m);
    ++result_.homing_steps;
    result_.steps.push_back(step);
    if (driven_ >= 0.5 * distance_m) {
      homing_from_ = sidestep_ == 0 ? cue.distance_m : std::numeric_limits<double>::infinity();
      sidestep_ = 0;
    } else if (sidestep_ < kSidesteps) {
      ++sidestep_;
      ++result_.sidesteps;
    } else {
      arrived_ = true;  // blocked every way: as near as the robot gets
    }
  }

  // Turns and drives; records, for the next prediction, the direction of the motion seen from
  // every place that holds some of the belief.
  void drive(double turn_rad, double distance_m) {
    const std::vector<double>& probability = belief_.probabilities();
    const double most = *std::max_element(probability.begin(), probability.end());
    for (std::size_t p = 0; p < motion_.size(); ++p) {
      motion_[p] = probability[p] >= kNegligibleShare * most && std::isfinite(in_place_[p])
                       ? wrap_angle(in_place_[p] + turn_rad)
                       : std::numeric_limits<double>::quiet_NaN();
    }
    driven_ = world_.move(turn_rad, distance_m);
    result_.path_length_m += driven_;
  }

  bool linked(int a, int b) const {
    return std::any_of(links_.begin(), links_.end(), [&](const MeasuredLink& link) {
      return link.places == PlacePair(a, b) || link.places == PlacePair(b, a);
    });
  }

  NavigationWorld& world_;
  const GoalNavigationSetup& setup_;
  const NavigatorParams& params_;
  const GoalHoming& homing_;
  std::vector<MeasuredLink> links_;  // without the links found blocked
  RoutePlan plan_;
  PlaceBelief belief_;
  std::vector<double> motion_;    // the last motion, seen from each place (NaN: not computed)
  std::vector<double> in_place_;  // the view's heading relative to each place (NaN: not measured)
  std::vector<double> dissimilarity_;
  NavigationResult result_;
  double driven_ = 0.0;
  int sidestep_ = 0;
  int previous_place_ = -1;
  bool was_lost_ = false;
  bool homing_started_ = false;
  bool arrived_ = false;
  double homing_from_ = std::numeric_limits<double>::infinity();
  // Progress: the place nearest the goal the belief has acted on, its cost then, and the
  // distance driven since.
  int progress_place_ = -1;
  double progress_cost_ = std::numeric_limits<double>::infinity();
  double since_progress_m_ = 0.0;
};

}  // namespace

NavigationResult navigate(NavigationWorld& world, const GoalNavigationSetup& setup, int goal,
                          const GoalHoming& homing) {
  if (setup.places.empty()) throw UsageError("navigate: a map without places");
  if (goal < 0 || static_cast<std::size_t>(goal) >= setup.places.size()) {
    throw UsageError("navigate: goal " + std::to_string(goal) + " is not one of the " +
                     std::to_string(setup.places.size()) + " places");
  }
  if (setup.signatures.size() != setup.places.size()) {
    throw UsageError("navigate: " + std::to_string(setup.signatures.size()) + " signatures for " +
                     std::to_string(setup.places.size()) + " places");
  }
  return NavigationRun(world, setup, goal, homing).run();
}

}  // namespace omninav::navigation
