#pragma once
// The visual memory as the planner and the navigator see it.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/homing.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/navigation/place_belief.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::navigation {

// Every place's lattice position and its heading in the map's frame. Throws InputError for a
// map without places, UsageError when the map has no lattice yet ("run omninav organise") or a
// place has no heading (neither stored nor measurable along the exploration).
std::vector<PlaceNode> places_from_memory(const memory::VisualMemory& memory);

// The goal image's localiser backed by the memory's hierarchical localisation: the panorama's
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

// The largest mean dissimilarity per value at which a view recognises its best place: the
// median over the map's links of their dissimilarity per value (places about one spacing apart:
// a view on the map stands nearer its best place than neighbouring places are to each other).
// Infinite for a map without links.
double recognition_limit(const memory::VisualMemory& memory);

// What homing on a goal image needs from `memory` (homing.hpp): its signature parameters and
// weights, and the map's spacing (map_spacing) over the median dissimilarity per value of its
// links, which join places about one spacing apart. Without links, metres_per_dissimilarity is
// 0 (homing never moves), with a warning in the log.
HomingScale homing_scale(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places);

// The distance between neighbouring places the map states (a grid database's grid spacing, else
// the exploration's spacing), else the lattice spacing of `places`.
double map_spacing(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places);

// The confirmed links of `memory` (lattice/confirmed_links.hpp) with `places`' headings and the
// map's spacing, and the neighbours `places`' lattice positions give a map made by driving.
std::vector<MeasuredLink> map_links(const memory::VisualMemory& memory,
                                    const std::vector<PlaceNode>& places, const LinkParams& params);

// The plan to `goal` over the confirmed links of `memory` (confirmed_links). `places` are
// places_from_memory(memory).
RoutePlan plan_route(const memory::VisualMemory& memory, const std::vector<PlaceNode>& places,
                     const LinkParams& links, int goal);

// Everything navigating to goal images on `memory` needs (goal_navigation.hpp): its places, its
// match limit and homing scale, its confirmed links, its places' signatures and thumbnails, with
// `localise` and the settings (homing's metres from map_spacing). Throws UsageError for
// parameters out of range.
GoalNavigationSetup goal_navigation_setup(const memory::VisualMemory& memory,
                                          PanoramaLocaliser localise, const RouteParams& route,
                                          const NavigatorParams& navigator, const LinkParams& links,
                                          const BeliefParams& belief,
                                          const SteeringParams& steering);

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
