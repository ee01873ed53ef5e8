#pragma once
// `omninav evaluate`: for each world of a suite, render the trajectories and run on them what
// the commands run (render, compass, explore, organise, localise, navigate --trials: the same
// library calls), collect the measures into a table (table.hpp) and the command lines that
// remake every figure. docs/evaluation.md defines every measure.
//
// Per world (lengths scale with the world's spacing_m / 0.3 m where it has its own):
//   compass: `rotate` on the spot at the free centre, a `circle` round it (the largest free
//     radius up to circle_radius_m), a `wander` from it, the same wander with pitch and roll
//     noise ("bumpy"), and a `saccade` route from it (straight stretches, saccades, stops and
//     turns on the spot), each through `omninav compass --truth`: max |e|, mean e, end e
//     (degrees);
//   memory: a grid_nx x grid_ny grid at spacing_m centred on the floor (shrunk to fit; points in
//     obstacles left out), explored (every image a place), organised (--step-m spacing); queries
//     at seeded random free poses and headings inside the grid's rectangle, localised: share
//     within one spacing, share at the nearest place, median heading error (degrees) and, in
//     worlds with regions, the share whose best place lies in the query's region;
//   lattice: that grid, and two zig-zag streams over the grid's rectangle, rows as far apart as
//     their places, explored with a place every 1 and every 2 spacings (--every-m,
//     --dissimilarity 0), organised with the map's spacing: RMSE after Procrustes (all places,
//     interior, boundary) in spacings (interior not applicable when no place is), and folds;
//   navigation: `navigate --trials` on the organised grid map: share reached (stopped within
//     goal_radius_m of the goal's position), mean path over straight line (reached trials), and
//     how far the robot went outside the mapped area: the largest distance from a true position
//     of the robot (at any step of any trial) to the convex hull of the places' true positions,
//     in metres and in the world's spacings;
//   driven: a `tour` of the grid's rectangle (sim/tour.hpp) rendered with odometry, explored
//     with a place every spacing by that odometry, organised and navigated as the grid map:
//     the share of the free floor within one lane of the tour, the lattice and the navigation
//     measures of that map.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/evaluation/configuration.hpp"
#include "omninav/evaluation/suite.hpp"
#include "omninav/evaluation/table.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::evaluation {

// Where a world's trajectories go.
struct WorldLayout {
  Eigen::Vector2d centre;  // a free point near the floor's centre: rotation, circle, wanders
  double circle_radius_m;  // the largest free circle round `centre` up to the suite's radius
  // The grid: nx x ny points `spacing_m` apart from `first_point` (its least x and y).
  Eigen::Vector2d first_point = Eigen::Vector2d::Zero();
  int nx = 0, ny = 0;
  double spacing_m = 0.3;
};

// Chooses the layout in `world` (deterministic). The clearance kept from obstacles is the
// grid's 5 cm for grid points and `clearance_m` for the centre and the circle. Throws
// InputError when the floor holds no free point or is smaller than 2 x 2 spacings.
WorldLayout plan_layout(const sim::World& world, int nx, int ny, double spacing_m,
                        double circle_radius_m, double clearance_m);

// `count` seeded poses uniform over the rectangle from `min` to `max` (its corners of least and
// greatest x and y) where `world` is free (5 cm clearance, as grid points), headings uniform, at
// height z_m.
std::vector<CameraPose> random_free_poses(const sim::World& world, const Eigen::Vector2d& min,
                                          const Eigen::Vector2d& max, int count, std::uint32_t seed,
                                          double z_m);

// The convex hull of `points` (counter-clockwise).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points);
// How far `p` lies outside the convex polygon `hull` (0 inside or on it); a hull of one or two
// points is a point or a segment.
double distance_outside(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p);

// "Localised in the right room": of the queries standing in a region of `world` (a house's
// room or corridor; those in a doorway or wall are left out), the share whose best place
// stands in the same region. Each pair is (query's true position, best place's true position).
// Nothing when no query stands in a region (a world without regions).
std::optional<double> right_region_share(
    const sim::World& world,
    const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& localised);

struct WorldEvaluation {
  Row row;
  std::vector<std::string> commands;  // the command lines that remake its figures, in order
};

// Measures one world of the suite, writing its databases, maps and pictures under `dir`.
// A stage that throws marks its cells failed (the reason in row.notes) and the others go on.
WorldEvaluation evaluate_world(const SuiteWorld& world, const SuiteParams& params,
                               const ConfigFolder& config, const std::filesystem::path& dir);

struct SuiteEvaluation {
  std::vector<Row> rows;
  std::vector<std::string> commands;  // every world's, each block headed by a comment line
  // "<label>: <reason>" of each world that could not be evaluated at all (its world file
  // missing, not an OBJ, damaged): its row is all failed, and `evaluate` exits non-zero.
  std::vector<std::string> failed_worlds;
};

// Every world of the suite in order, each in <out>/<label>/; `on_row` (may be empty) is called
// after each world, e.g. to print progress.
SuiteEvaluation evaluate_suite(const Suite& suite, const ConfigFolder& config,
                               const std::filesystem::path& out,
                               const std::function<void(const Row&, std::size_t)>& on_row = {});

}  // namespace omninav::evaluation
