#pragma once
// A coverage tour (trajectory kind `tour`): the route a robot with a coverage planner drives to
// explore a world's free space, as Menegatti et al. 2004 (§3.4) explore
// by driving a zig-zag. The free space of a rectangle of the floor (the whole floor by default)
// is rasterised at cell_m: a cell is free when World::is_free holds at its centre with
// clearance_m. The free cells joined by 4-neighbour steps are the parts of the free space; every
// part larger than a lane's square must be reachable from the start, else the tour is refused
// with the parts named (a closed room). Each area (a house's room or corridor as
// World::regions names it, or the whole part in worlds without regions) is covered by
// boustrophedon lanes lane_m apart along its longer side (Choset 2000, "Coverage of known
// spaces: the boustrophedon cellular decomposition"): every run of free cells along a lane is
// driven, the nearest (by path) next, and the robot goes from one run to the next, and from one
// area to the nearest uncovered one, along the shortest free path on the raster (breadth-first
// search), shortened by keeping only the corners a straight free segment cannot skip.
//
// The result is a polyline of waypoints; trajectory.cpp drives it at speed_m_s and fps, turning
// on the spot at corners at turn_rate_deg_s.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "omninav/sim/world.hpp"

namespace omninav::sim {

struct TourParams {
  FloorBox area;                    // the rectangle toured (clipped to the floor)
  double lane_m = 0.3;              // distance between neighbouring lanes
  double clearance_m = 0.25;        // kept from obstacles and the floor's edge at every point
  double cell_m = 0.05;             // raster resolution (at most lane_m / 3)
  Eigen::Vector2d start{0.0, 0.0};  // the robot's start: the free cell nearest it
  std::string spec;                 // for messages
};

// The waypoints of the tour, from the start. Throws UsageError naming the key and the reason when
// lane_m, clearance_m or cell_m leave no free cell or are out of range, and naming the parts
// (by their regions, or their extent) when the free space falls into parts that no free path
// joins.
std::vector<Eigen::Vector2d> plan_tour(const World& world, const TourParams& params);

// How much of the free floor a route covers: of the floor's cells (cell_m) inside `area` where
// the world is free (no clearance), the share within `reach_m` of a point of the route (its
// poses, densely sampled); per region too (a house's rooms and corridor).
struct Coverage {
  double share = 0.0;
  double free_m2 = 0.0;  // the free floor measured
  struct RegionShare {
    std::string name;
    double share = 0.0;
    double free_m2 = 0.0;
  };
  std::vector<RegionShare> regions;
};
Coverage route_coverage(const World& world, const std::vector<Eigen::Vector2d>& route,
                        const FloorBox& area, double reach_m, double cell_m = 0.05);

}  // namespace omninav::sim
