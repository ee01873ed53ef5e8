#pragma once
// The reactive navigator of 001_5bb151a4e28490b4.txt §3.5: grab a panorama, recognise the
// place, measure the robot's heading against the place's image, turn to the direction the
// route plan assigned to that place, step, repeat. It never uses the robot's true pose: the
// plan, the memory and the images are all it knows. When localisation jumps to a place other
// than the one expected (the paper's O4/O5 case: the lattice is distorted), it simply follows
// the new place's direction; the jump is recorded. When the robot cannot drive along a place's
// direction (furniture the lattice knows nothing of, met because the robot stands beside the
// place rather than on it), it first turns a little aside (sidesteps), and when that fails too
// that link of the memory graph is dropped and the plan is made again from the goal without
// it; only when no route is left does the robot try escape turns.
// More goes beyond the paper (docs/navigation.md says what and why): the robot aims from
// its position estimate at a place several links ahead where the lattice says the straight
// line follows the route (look_ahead_place, route_planner.hpp), a place the robot keeps coming
// back to gets the same treatment as a blocked link, and once the goal's place is recognised
// the robot homes on the goal image itself (homing.hpp).

#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/navigation/homing.hpp"
#include "omninav/navigation/route_planner.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::navigation {

// How the navigator localises what the robot sees: the memory's hierarchical localisation of
// the panorama (memory_localiser, memory_places.hpp) or a stand-in. Of the localisation it reads
// the best place (its similarity, the robot's heading relative to the place's stored heading)
// and, when the position estimate is on the lattice, where the robot is between places.
using PanoramaLocaliser = std::function<memory::Localisation(const cv::Mat& panorama)>;

struct NavigatorParams {
  double step_m = 0.15;            // distance driven between two images
  int max_steps = 300;             // budget; the run fails when it is spent
  double goal_similarity = 0.0;    // the goal place must match with at least this similarity
  int goal_confirmations = 1;      // consecutive goal matches needed to stop
  double unstick_turn_deg = 60.0;  // turn tried when no route is left round a blocked link
  // Beyond §3.5, which follows the matched place's direction (from the place to its next
  // place): aim from the localiser's position estimate at look_ahead_place(...,
  // look_ahead_links, look_ahead_tolerance_spacings × the lattice spacing, the links found
  // blocked), a place up to that many links along the route that a straight line reaches
  // (route_planner.hpp). The robot then drives the straight line instead of zig-zagging from
  // place to place, and a robot beside a place does not run parallel to the route. 0, or
  // without a position estimate: the place's direction; 1: the next place, from the estimate.
  int look_ahead_links = 6;
  double look_ahead_tolerance_spacings = 0.5;
  // Beyond §3.5: blocked, the robot tries directions turned alternately left and right of the
  // place's direction (not the look-ahead's, which led into the obstacle), by sidestep_deg,
  // then 2 × sidestep_deg, ..., sidesteps of them, before the link is dropped from the plan. Most
  // blocks are grazing contacts: the robot stands beside its place, not on it, and runs along
  // furniture; turning a little away slides it past, where dropping the link sent it round the
  // furniture (docs/navigation.md).
  int sidesteps = 4;
  double sidestep_deg = 25.0;
  // Beyond §3.5: a place entered this many times in one run means the robot goes round in
  // circles (the directions of neighbouring places lead into each other where the lattice is
  // distorted): its link to its next place is dropped and the plan made again, as for a blocked
  // link. 0: never.
  int loop_entries = 3;
  // Beyond §3.5 (homing.hpp): with a GoalHoming, once the goal place is recognised the robot
  // steps towards the goal image while the goal seems nearer than at the last view and farther
  // than homing_stop_m, instead of stopping at once.
  bool home_on_goal_image = true;
  double homing_step_m = 0.1;   // longest homing step (a step goes as far as the goal seems)
  double homing_stop_m = 0.15;  // the goal seeming this near ends homing
  // The same two in spacings of the map (> 0: goal_navigation_setup sets the metres above from
  // the map's own spacing, memory_places.hpp map_spacing, when navigation starts; 0: the metres
  // as given). A distance in metres is a claim about one world's scale; the zoo's grids are
  // 0.3 m apart, where these are the metres above.
  double homing_step_spacings = 0.333;
  double homing_stop_spacings = 0.5;
  int homing_max_steps = 8;  // homing steps at most (they count against max_steps too)
  // Beyond §3.5: knowing when it is lost (docs/navigation.md). A view is recognised when its
  // best place differs from it by at most recognition_link_ratio × the median dissimilarity
  // per value of the map's links (places about one spacing apart; memory_places.hpp,
  // recognition_limit, measured from the map when the run starts): a robot on the map stands
  // within half a cell's diagonal of a place, nearer than neighbouring places are to each
  // other. In a row of views not recognised, lost_views
  // that look no more like the map than an earlier one of the row (a robot coming onto the map
  // sees its best place nearer with every view), or 2 × lost_views of them anyway, or
  // lost_jumps jumps within lost_jump_window views, mean the robot is lost (0: never by that
  // cue). Lost, it goes back by dead reckoning (the turns it commanded and the distances it
  // drove) to where it last recognised a place without a jump (its start when it never did),
  // at most return_max_steps steps, drops the link it followed from that place and plans again
  // (from its start: it tries a direction turned 90°, then -90°, 180°, ... from the plan's), and
  // goes on. Lost more than `recoveries` times, it goes back there and stops: the run fails
  // where the map is known instead of driving away.
  double recognition_link_ratio = 1.0;
  // With recognition_place_link_ratio > 0, each place has its own limit instead: that many
  // times the median dissimilarity of the place's own links (memory_places.hpp,
  // place_recognition_limits), to places about a spacing away. Off (0): on the plain room, the
  // house and the office no ratio both recognises the views on the map and not those off it
  // (docs/navigation.md, "Recognised where the place is").
  double recognition_place_link_ratio = 0.0;
  int lost_views = 3;
  int lost_jumps = 0;
  int lost_jump_window = 8;
  int recoveries = 2;
  int return_max_steps = 20;
  // Beyond §3.5: a robot farther from its start, by its dead reckoning, than the lattice is
  // across (the diagonal of its bounding box, measured from the map when the run starts)
  // cannot be on the map: lost, whatever it recognises, it goes back as above (to its start,
  // or an anchor within that reach). Where off-map views match as well as the map's own (a field
  // seen from 10 cm), this bounds how far it strays. With it, too, a robot whose steps left only
  // just take it back to its start gives up and goes back, rather than end where the budget
  // runs out.
  bool stay_within_map_extent = true;
  // Beyond §3.5, with stay_within_map_extent: the dead reckoning carried onto the lattice from
  // the first place recognised (its position, and the heading measured there) must stay within
  // the lattice's bounding box grown by this many lattice spacings, or the robot is lost.
  bool stay_within_lattice_box = false;
  double lattice_box_margin_spacings = 1.0;
  // Beyond §3.5: not getting nearer the goal. Following the route, a robot that drives
  // stall_spacings spacings of the map (steps × step_m, blocked ones included) without
  // recognising a place nearer the goal by the plan than every place it recognised before
  // (a place with a lower cost_m than the lowest when it was reached) is stalled: it goes back
  // and forth over a link whose direction leads it astray (a motion measured between
  // look-alikes, a folded lattice's neighbours), or round in circles wider than loop_entries
  // sees. The link from the nearest place it reached to that place's next is dropped and the
  // plan made again without it. With stall_other_links, and navigate's `fallback` plan over the
  // other link set, the robot also switches plans when its own motion says the other set is the
  // better here: to the lattice when the lattice explains the distances it drove between its
  // recent recognised views (the median difference at most one spacing, over pairs at least two
  // spacings apart), to the motions when it does not. 0: off; chosen across the zoo
  // (navigation.yaml). stall_m is the distance in metres (goal_navigation_setup sets it from
  // the map's own spacing, memory_places.hpp map_spacing; 0: stall_spacings × the lattice
  // spacing of the places).
  double stall_spacings = 8.0;
  bool stall_other_links = true;
  double stall_m = 0.0;
};

// Reads the `navigator:` section of navigation.yaml.
void load_navigator_params(const ConfigReader& section, NavigatorParams& params);

// What the navigator acts on: a robot somewhere that shows what it sees and moves when told.
// The loop is the same whether the world is rendered or a grid of stored images (the
// evaluation layer's robot worlds) or a stand-in.
class NavigationWorld {
 public:
  virtual ~NavigationWorld() = default;
  // The panorama the robot sees now; `step` numbers the views (it seeds sensor noise).
  virtual cv::Mat view(int step) = 0;
  // Turns by `turn_rad` (counter-clockwise positive), then drives up to `distance_m` forward.
  // Returns the distance actually driven (0 when blocked).
  virtual double move(double turn_rad, double distance_m) = 0;
  // Where the robot really is: for evaluation and the step log only, the loop never reads it.
  virtual CameraPose truth() const = 0;
};

// What the navigator was doing at a step.
enum class NavigationPhase {
  kFollowingRoute,  // §3.5's loop (with the additions above)
  kHoming,          // homing on the goal image
  kReturning,       // lost: going back to where it last recognised a place
};

// "route", "homing", "returning" (steps.csv).
const char* phase_name(NavigationPhase phase);

struct NavigationStep {
  int index = 0;
  CameraPose truth;                         // where the robot really was (evaluation only)
  std::optional<memory::PlaceMatch> match;  // the best place; none when nothing was recognised
  double heading_estimate_rad = 0.0;  // in the lattice frame: place heading + heading in place
  double turn_rad = 0.0;              // the turn commanded
  bool jump = false;                  // matched neither the expected place nor its neighbours
  // The best place lies within the map's recognition limit (NavigatorParams, lost_views).
  bool recognised = false;
  NavigationPhase phase = NavigationPhase::kFollowingRoute;
  bool lost = false;  // the robot found itself lost at this step and turned back
  // Stalled (NavigatorParams::stall_spacings) at this step: a link dropped, the plan switched.
  bool stalled = false;
};

struct NavigationResult {
  bool reached = false;
  std::vector<NavigationStep> steps;
  double path_length_m = 0.0;  // distance the robot drove
  int jumps = 0;
  int sidesteps = 0;      // moves turned aside after a block
  int replans = 0;        // links of the memory graph found blocked, and the plan made without them
  int loops = 0;          // places entered loop_entries times, and the plan made without their link
  int homing_steps = 0;   // steps taken towards the goal image after recognising its place
  int lost_events = 0;    // times the robot found itself lost (NavigatorParams, lost_views)
  int recoveries = 0;     // times it recognised a place again after being lost
  bool gave_up = false;   // lost more than `recoveries` times: it went back and stopped
  int stalls = 0;         // times it got no nearer the goal over stall_spacings (NavigatorParams)
  int link_switches = 0;  // ... of them that switched to the plan over the other link set
};

// Drives `world`'s robot along `plan` until it recognises the goal place, then, when `homing`
// is given and params.home_on_goal_image, homes on the goal image. A view whose best place
// differs by more than `recognition_limit` per value (memory_places.hpp, recognition_limit) is
// not recognised: the robot's cue that it is lost (infinite: every view with a candidate is
// recognised).
NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const PanoramaLocaliser& localise,
                          const NavigatorParams& params, const GoalHoming& homing = {},
                          double recognition_limit = std::numeric_limits<double>::infinity());

// The same, each view judged against the limit of its best place, place_recognition_limits[place]
// (memory_places.hpp; empty: recognition_limit for every place).
NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const PanoramaLocaliser& localise,
                          const NavigatorParams& params, const GoalHoming& homing,
                          double recognition_limit,
                          const std::vector<double>& place_recognition_limits);

// The same with a second plan to the same goal over the other link set (the lattice's
// neighbours for a plan over measured motions, or the reverse; memory_places.hpp
// plan_over_other_links), which a stalled robot switches to (NavigatorParams::stall_spacings,
// stall_other_links). A fallback whose goal is -1 is none. Throws UsageError for a fallback to
// another goal.
NavigationResult navigate(NavigationWorld& world, const std::vector<PlaceNode>& places,
                          const RoutePlan& plan, const RoutePlan& fallback,
                          const PanoramaLocaliser& localise, const NavigatorParams& params,
                          const GoalHoming& homing, double recognition_limit,
                          const std::vector<double>& place_recognition_limits);

}  // namespace omninav::navigation
