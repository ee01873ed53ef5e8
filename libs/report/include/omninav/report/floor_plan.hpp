#pragma once
// Floor plans: the world seen from above, under render's plan.png and navigate's path.png.

#include <string>
#include <vector>

#include "omninav/measures/plot.hpp"
#include "omninav/sim/trajectory.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::report {

// Outlines of floor rectangles (obstacles, regions) as segments of grey level `grey`.
void add_floor_boxes(measures::PointsPlot& plot, const std::vector<sim::FloorBox>& boxes,
                     double grey);

// The boxes that reach into `frame` grown on every side by a quarter of its larger side (at
// least 0.5 m): the surroundings of what a figure shows, without the rest of a large world
// (a field's tussocks 20 m away would shrink a 2 m map to a dot).
std::vector<sim::FloorBox> boxes_around(const std::vector<sim::FloorBox>& boxes,
                                        const sim::FloorBox& frame);

// The world seen from above: its floor, obstacles and named regions, and the trajectory's
// positions (plan.png of `omninav render`).
measures::PointsPlot floor_plan(const sim::World& world, const sim::Trajectory& trajectory);

}  // namespace omninav::report
