#include "omninav/navigation/goal_drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::navigation {

namespace {

// A place whose probability is below this share of the most probable one's is not worth the
// phases' heading: its prediction keeps its (negligible) probability in place.
constexpr double kNegligibleShare = 1e-4;
// Blocked, the robot turns aside by this, then twice, ... alternately left and right, this many
// times (every direction once, the last straight back), before it drops the link it was
// following: a robot steered at a place behind a corner must be able to back out of it.
constexpr double kSidestepDeg = 45.0;
constexpr int kSidesteps = 7;
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

}  // namespace

class GoalDrive::Run {
 public:
  Run(const GoalNavigationSetup& setup, int goal, GoalHoming homing)
      : setup_(setup),
        params_(setup.navigator),
        homing_(std::move(homing)),
        steering_(setup.snapshots),
        links_(setup.links),
        plan_(plan_to_goal(setup.places, links_, goal)),
        belief_(setup.places.size(), links_, setup.belief.view_scale * setup.link_dissimilarity,
                setup.belief),
        motion_(setup.places.size(), std::numeric_limits<double>::quiet_NaN()),
        in_place_(setup.places.size(), std::numeric_limits<double>::quiet_NaN()),
        dissimilarity_(setup.places.size(), 0.0) {}

  bool finished() const { return arrived_ || views_ >= params_.max_steps; }
  const NavigationResult& result() const { return result_; }

  DriveCommand step(const cv::Mat& view) {
    if (finished()) throw UsageError("GoalDrive::step: the navigation has finished");
    if (waiting_) throw UsageError("GoalDrive::step: the last command's motion is not reported");
    DriveCommand command;
    look(view, command.step);
    const int place = static_cast<int>(command.step.match->place);
    const double in_place = command.step.match->relative_heading_rad;

    // Arrived at the goal's place: the belief is on it (the most probable place, holding at
    // least the confident share of the belief with its linked places, and at least
    // kArrivalShare itself: on a small map a place's linked places are much of the map).
    const bool at_goal = belief_.most_likely() == plan_.goal && !command.step.lost &&
                         belief_.probability(plan_.goal) >= kArrivalShare;
    if (!homing_started_ && at_goal) {
      if (!homing_ || !params_.home_on_goal_image || params_.homing_max_steps == 0) {
        arrive(command);
        return command;
      }
      homing_started_ = true;
      result_.reached = true;  // at the goal's place: homing only brings the robot nearer
      homing_from_ = std::numeric_limits<double>::infinity();
      sidestep_ = 0;
    }
    if (homing_started_) {
      command.step.phase = NavigationPhase::kHoming;
      home(command, view);
    } else {
      follow_route(command, place, in_place, view);
    }
    return command;
  }

  // What the last command's motion tells: how far the robot got decides the sidesteps and the
  // links dropped; the distance carries the belief at the next view.
  void moved(double driven_m) {
    if (!waiting_) throw UsageError("GoalDrive::moved: no command is waiting for its motion");
    if (!std::isfinite(driven_m)) {
      throw InputError("GoalDrive::moved: " + std::to_string(driven_m) +
                       " is not the metres driven (a finite distance)");
    }
    const Waiting waiting = *waiting_;
    waiting_.reset();
    driven_ = driven_m;
    stepped_towards_goal_ = waiting.towards_goal && driven_ >= 0.5 * waiting.distance_m;
    result_.path_length_m += driven_;
    if (waiting.phase == NavigationPhase::kHoming) {
      homed(waiting);
    } else {
      followed(waiting);
    }
  }

 private:
  // A command given, its motion not yet reported.
  struct Waiting {
    NavigationPhase phase = NavigationPhase::kFollowingRoute;
    int place = -1;                // the place acted on (following the route)
    double distance_m = 0.0;       // commanded
    double goal_distance_m = 0.0;  // how far the goal seemed (homing)
    bool towards_goal = false;     // a step towards the goal image's bearing (following the route)
  };

  // The view's evidence: the belief carried by the last motion and updated by the view, the
  // place acted on and the view's heading relative to it.
  void look(const cv::Mat& view, NavigationStep& step) {
    step.index = views_++;
    const signature::Signature signature = setup_.signature_of(view);
    place_dissimilarities(setup_, signature, dissimilarity_);
    if (step.index > 0) belief_.predict(motion_, driven_);
    // A robot that did not move sees what it saw: the same evidence again, not new evidence
    // (counted twice, a view's look-alike would win by repetition).
    if (step.index == 0 || driven_ > 0.0) belief_.update(dissimilarity_);
    if (!plan_.reaches_goal(belief_.most_likely())) restore_links();
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
  }

  void arrive(DriveCommand& command) {
    result_.steps.push_back(command.step);
    arrived_ = true;
    result_.reached = true;
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

  // Turns towards the plan's next place (aside when blocked) and steps. At the goal's place,
  // where the goal image says the goal lies (the goal's place has no direction of its own); and
  // there the robot stops where homing stops, once the goal seems within homing_stop_m, or once
  // it passed over the goal (passed_over_goal). Where views change within centimetres (grass
  // seen from 10 cm) the belief may never settle on the goal's place, whose image was taken up
  // to half a cell's diagonal from the goal, while the goal image itself says the robot stands
  // at the goal.
  void follow_route(DriveCommand& command, int place, double in_place, const cv::Mat& view) {
    double direction_rad = 0.0;
    bool towards_goal = false;
    if (place == plan_.goal && homing_) {
      const GoalCue cue = homing_(view);
      if (goal_seems_near(cue) || passed_over_goal(cue)) {
        arrive(command);
        return;
      }
      direction_rad = cue.valid ? cue.bearing_rad : 0.0;
      towards_goal = cue.valid && sidestep_ == 0;
      turned_about_ = towards_goal && std::abs(cue.bearing_rad) > 0.5 * kPi;
    } else {
      direction_rad = route_direction(place, in_place, view);
    }
    const double turn_rad = wrap_angle(direction_rad + sidestep_turn(sidestep_));
    check_progress(place);
    command_motion(command, turn_rad, params_.step_m);
    waiting_ = Waiting{NavigationPhase::kFollowingRoute, place, params_.step_m, 0.0, towards_goal};
  }

  // The goal image's bearing was behind the robot, it turned about and drove a step towards it,
  // and the bearing is behind it again: it crossed the goal twice, and the goal lies within that
  // step. Where views change within centimetres (grass seen from 10 cm) the goal image's
  // dissimilarity says "far" a few centimetres from it, and a robot at the goal turned about and
  // stepped to and fro. Once is not enough: a bearing that noisy is now and then behind the
  // robot half a metre from the goal.
  bool passed_over_goal(const GoalCue& cue) const {
    return stepped_towards_goal_ && turned_about_ && cue.valid &&
           std::abs(cue.bearing_rad) > 0.5 * kPi;
  }

  // Where the route leads from `place`, counter-clockwise from the robot's front: towards the
  // plan's next place by that place's image (place_steering.hpp), else to the plan's direction
  // at `place` (its heading relative to the view: `in_place`); straight on from a place without
  // a route.
  double route_direction(int place, double in_place, const cv::Mat& view) {
    if (!plan_.reaches_goal(place)) return 0.0;
    if (place != plan_.goal) {
      if (const std::optional<double> next = steering_.direction_to(plan_.next[place], view)) {
        return *next;
      }
    }
    return signed_difference(plan_.direction_in_place_rad[place], in_place);
  }

  // Blocked, the robot has met what the map's links do not show (furniture, a wall between
  // grid neighbours): after turning aside kSidesteps times, the link it was following is
  // dropped and the plan made again without it (not while lost: which link it followed is not
  // known).
  void followed(const Waiting& waiting) {
    since_progress_m_ += driven_;
    if (driven_ >= 0.5 * waiting.distance_m) {
      sidestep_ = 0;
    } else if (sidestep_ < kSidesteps) {
      // Most blocks graze furniture beside the link: turning a little aside slides past it. A
      // robot steered at a place behind a corner turns further, to straight back.
      ++sidestep_;
      ++result_.sidesteps;
    } else {
      sidestep_ = 0;
      if (!belief_.lost()) drop_link(waiting.place, plan_.next[waiting.place]);
    }
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

  // The belief's most probable place has no route to the goal: links dropped earlier, judged
  // from a belief that has moved since, cut it off. They are restored and the plan made again:
  // the robot acts on a place the belief holds, never on one it gives next to nothing because
  // that one still has a route.
  void restore_links() {
    if (links_.size() == setup_.links.size()) return;
    links_ = setup_.links;
    belief_.restore_links();
    plan_ = plan_to_goal(setup_.places, links_, plan_.goal);
    ++result_.replans;
    restart_progress(-1);
  }

  // Progress is counted afresh from `place` (-1: from no place, the next one acted on).
  void restart_progress(int place) {
    progress_place_ = place;
    progress_cost_ = place >= 0 ? plan_.cost_m[place] : std::numeric_limits<double>::infinity();
    since_progress_m_ = 0.0;
  }

  // A link the robot cannot follow: it drove kUnfollowedLinks times the link's length (and a
  // step) since the belief last came to a place nearer the goal, and is not there yet. The
  // link from that place is dropped (a revisit whose direction misleads, a passage too narrow)
  // and the plan made again without it.
  void check_progress(int place) {
    const double cost = plan_.cost_m[place];
    if (cost < progress_cost_ - 1e-9) {
      restart_progress(place);
      return;
    }
    if (progress_place_ < 0 || plan_.next[progress_place_] < 0) return;
    const int next = plan_.next[progress_place_];
    const double length = plan_.cost_m[progress_place_] - plan_.cost_m[next];
    if (since_progress_m_ <= kUnfollowedLinks * length + params_.step_m) return;
    drop_link(progress_place_, next);
    restart_progress(place);
  }

  // Where homing stops, and following the route at the goal's place too.
  bool goal_seems_near(const GoalCue& cue) const {
    return cue.valid && cue.distance_m <= params_.homing_stop_m;
  }

  // Homing on the goal image (homing.hpp): step towards it while it seems nearer than at the
  // last view and farther than homing_stop_m.
  void home(DriveCommand& command, const cv::Mat& view) {
    const GoalCue cue = homing_(view);
    if (goal_seems_near(cue) || !cue.valid || cue.distance_m >= homing_from_ ||
        result_.homing_steps >= params_.homing_max_steps) {
      arrive(command);
      return;
    }
    const double distance_m = std::min(cue.distance_m, params_.homing_step_m);
    command_motion(command, cue.bearing_rad + sidestep_turn(sidestep_), distance_m);
    ++result_.homing_steps;
    waiting_ = Waiting{NavigationPhase::kHoming, -1, distance_m, cue.distance_m};
  }

  void homed(const Waiting& waiting) {
    if (driven_ >= 0.5 * waiting.distance_m) {
      homing_from_ =
          sidestep_ == 0 ? waiting.goal_distance_m : std::numeric_limits<double>::infinity();
      sidestep_ = 0;
    } else if (sidestep_ < kSidesteps) {
      ++sidestep_;
      ++result_.sidesteps;
    } else {
      arrived_ = true;  // blocked every way: as near as the robot gets
    }
  }

  // The command; records, for the next prediction, the direction of the motion seen from
  // every place that holds some of the belief.
  void command_motion(DriveCommand& command, double turn_rad, double distance_m) {
    const std::vector<double>& probability = belief_.probabilities();
    const double most = *std::max_element(probability.begin(), probability.end());
    for (std::size_t p = 0; p < motion_.size(); ++p) {
      motion_[p] = probability[p] >= kNegligibleShare * most && std::isfinite(in_place_[p])
                       ? wrap_angle(in_place_[p] + turn_rad)
                       : std::numeric_limits<double>::quiet_NaN();
    }
    command.turn_rad = turn_rad;
    command.distance_m = distance_m;
    command.moves = true;
    command.step.turn_rad = turn_rad;
    result_.steps.push_back(command.step);
  }

  bool linked(int a, int b) const {
    return std::any_of(links_.begin(), links_.end(), [&](const MeasuredLink& link) {
      return link.places == PlacePair(a, b) || link.places == PlacePair(b, a);
    });
  }

  const GoalNavigationSetup& setup_;
  const NavigatorParams& params_;
  const GoalHoming homing_;
  PlaceSteering steering_;
  std::vector<MeasuredLink> links_;  // without the links found blocked
  RoutePlan plan_;
  PlaceBelief belief_;
  std::vector<double> motion_;    // the last motion, seen from each place (NaN: not computed)
  std::vector<double> in_place_;  // the view's heading relative to each place (NaN: not measured)
  std::vector<double> dissimilarity_;
  NavigationResult result_;
  std::optional<Waiting> waiting_;
  int views_ = 0;
  double driven_ = 0.0;
  int sidestep_ = 0;
  int previous_place_ = -1;
  bool was_lost_ = false;
  bool homing_started_ = false;
  bool stepped_towards_goal_ = false;  // the last motion: a whole step towards the goal image
  bool turned_about_ = false;          // ... after turning about to the goal image's bearing
  bool arrived_ = false;
  double homing_from_ = std::numeric_limits<double>::infinity();
  // Progress: the place nearest the goal the belief has acted on, its cost then, and the
  // distance driven since.
  int progress_place_ = -1;
  double progress_cost_ = std::numeric_limits<double>::infinity();
  double since_progress_m_ = 0.0;
};

GoalDrive::GoalDrive(const GoalNavigationSetup& setup, int goal, GoalHoming homing) {
  if (setup.places.empty()) throw UsageError("navigate: a map without places");
  if (goal < 0 || static_cast<std::size_t>(goal) >= setup.places.size()) {
    throw UsageError("navigate: goal " + std::to_string(goal) + " is not one of the " +
                     std::to_string(setup.places.size()) + " places");
  }
  if (setup.signatures.size() != setup.places.size()) {
    throw UsageError("navigate: " + std::to_string(setup.signatures.size()) + " signatures for " +
                     std::to_string(setup.places.size()) + " places");
  }
  run_ = std::make_unique<Run>(setup, goal, std::move(homing));
}

GoalDrive::~GoalDrive() = default;

DriveCommand GoalDrive::step(const cv::Mat& view) {
  return run_->step(view);
}

void GoalDrive::moved(double driven_m) {
  run_->moved(driven_m);
}

bool GoalDrive::finished() const {
  return run_->finished();
}

const NavigationResult& GoalDrive::result() const {
  return run_->result();
}

}  // namespace omninav::navigation
