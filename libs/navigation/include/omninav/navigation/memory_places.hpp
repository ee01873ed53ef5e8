#pragma once
// The organised visual memory as the planner and the navigator see it.

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/homing.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::navigation {

// Every place's lattice position and its heading in the lattice frame. Throws InputError for a
// map without places, UsageError when the map has no lattice yet ("run omninav organise") or a
// place has no heading (neither stored nor measurable along the exploration).
std::vector<PlaceNode> places_from_memory(const memory::VisualMemory& memory);

// The navigator's localiser backed by the memory's hierarchical localisation: the panorama's
// signature (made by `extractor`) localised by `localiser`. Throws InputError for a panorama
// of another height than the map's. The localiser and the extractor must outlive the returned
// function.
PanoramaLocaliser memory_localiser(const memory::Localiser& localiser,
                                   signature::SignatureExtractor& extractor);

// The largest mean dissimilarity per value at which an image still matches a place of
// `memory`: params.match_dissimilarity_ratio × the median over the map's links of their
// dissimilarity per value. Infinite for a map without links (then only an empty candidate set
// fails to match), with a warning in the log.
double match_limit(const memory::VisualMemory& memory, const RouteParams& params);

// The largest mean dissimilarity per value at which the navigator recognises a view's best
// place: params.recognition_link_ratio × the median over the map's links of their
// dissimilarity per value. Infinite for a map without links (then the navigator never finds
// itself lost by recognition).
double recognition_limit(const memory::VisualMemory& memory, const NavigatorParams& params);

// Whether the navigator recognises `match` as the view's place: its dissimilarity per value is
// at most the place's own limit when `place_limits` has them (place_recognition_limits), else
// `limit` (recognition_limit).
bool is_recognised(const memory::PlaceMatch& match, double limit,
                   const std::vector<double>& place_limits);

// Each place's median over its links (the exploration's: consecutive places of a stream or a
// grid, truly about a spacing apart whatever look-alikes the map holds) of their mean
// dissimilarity per value, leaving out links more than twice the map's median (a grid's jump
// from the end of one row to the start of the next); the map's median link for a place without
// links (infinite without any).
std::vector<double> link_dissimilarities(const memory::VisualMemory& memory);

// Each place's own recognition limit, params.recognition_place_link_ratio × link_dissimilarities
// (which replaces recognition_limit for views whose best place it is); empty when the ratio is 0.
std::vector<double> place_recognition_limits(const memory::VisualMemory& memory,
                                             const NavigatorParams& params);

// What homing on a goal image needs from `memory` (homing.hpp): its signature parameters and
// weights, and the lattice spacing of `places` over the median dissimilarity per value of the
// map's links, which join places about one spacing apart. Without links, metres_per_dissimilarity
// is 0 (homing never moves), with a warning in the log.
HomingScale homing_scale(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places);

// The memory graph of motions measured from the phases (§3.4), which rests on no lattice
// position: each place linked to its params.motion_neighbours most similar places and, along a
// stream, to the places before and after it. Each link's direction is fitted both ways
// (signature::estimate_motion with the turn held at the difference of the places' headings, as
// the lattice's motions are) and the two averaged. A link is a look-alike's, and dropped, when
// either fit fails, or its fit leaves more than params.motion_residual_ratio times the median
// residual of the candidates, or its parallax (distance over depth) is more than
// params.motion_parallax_ratio times their median (when that is > 0), or the two fits disagree by
// more than
// params.motion_disagreement_deg (docs/navigation.md has the measurements); steps along a
// stream are kept, and dropped links join, most similar first, places the others leave apart.
// A link's length is map_spacing times the pair's dissimilarity over the geometric mean of the
// two places' dissimilarity to their most similar place (the organiser's calibration,
// lattice/organise.hpp, without its saturation: links are short). Homing's scale then comes
// from map_spacing too (goal_navigation_setup).
std::vector<MeasuredLink> motion_links(const memory::VisualMemory& memory,
                                       const std::vector<PlaceNode>& places,
                                       const RouteParams& params);

// The distance between neighbouring places the map states (a grid database's grid spacing, else
// the exploration's spacing), else the lattice spacing of `places`.
double map_spacing(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places);

// Whether plans on `memory` run over motion_links: params.links says so, or is auto and the
// map's stored lattice quality says its lattice is not trustworthy.
bool plans_over_motions(const memory::VisualMemory& memory, const RouteParams& params);

// The plan to `goal` over setup.links when it has them, else over the lattice.
RoutePlan plan_route(const GoalNavigationSetup& setup, int goal);

// The plan to `goal` over the other link set, which a stalled robot switches to
// (NavigatorParams::stall_spacings, stall_other_links): over the lattice when setup.links has
// the motions, over setup.other_links when it has them; none (goal -1) otherwise or when the
// navigator's stalls or their switch are off.
RoutePlan plan_over_other_links(const GoalNavigationSetup& setup, int goal);

// The plan to `goal` over the links plans_over_motions chooses for `memory`: motion_links or the
// lattice neighbours. `places` are places_from_memory(memory).
RoutePlan plan_route(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places,
                     const RouteParams& params, int goal);

// What navigating to goal images on `memory` needs: its places (places_from_memory), its match
// and recognition limits and homing scale, its motion_links when plans_over_motions (else, with
// stalls switching link sets, as other_links), with `localise` and the settings (homing's and
// the stall's metres from map_spacing).
GoalNavigationSetup goal_navigation_setup(const memory::VisualMemory& memory,
                                          PanoramaLocaliser localise, const RouteParams& route,
                                          const NavigatorParams& navigator);

// Why `localisation` matches no place of the map, none when it does: no candidate, or a best
// place whose mean dissimilarity per value is above `limit` (see match_limit). The one
// criterion of route, navigate and localise.
std::optional<std::string> no_match_reason(const memory::Localisation& localisation, double limit);

// Localises `image` (named `what` in messages, e.g. "goal.png") and checks that it matches a
// place: InputError when it matches none (no candidate, or a mean dissimilarity per value above
// `limit`, see match_limit), when it is not a panorama or has another height than the map's.
// Returns the best place.
memory::PlaceMatch match_image(const PanoramaLocaliser& localise, const cv::Mat& image,
                               double limit, const std::string& what);

}  // namespace omninav::navigation
