#pragma once
// Pictures of a route plan, like Fig. 18 of 001_5bb151a4e28490b4.txt: (a) the places on the
// lattice with the direction each must take towards the goal, (b) the same route over the
// places' true positions when the map has ground truth.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "omninav/navigation/route_planner.hpp"

namespace omninav::report {

// The lattice panel: every place, an arrow at each place that reaches the goal along its
// direction (lattice frame), the route from `start` drawn over them, start and goal marked.
// With `truth_m` (one true position per place) a second panel beside it draws the route over
// the true positions. BGR, CV_8UC3.
cv::Mat route_figure(const std::vector<navigation::PlaceNode>& places,
                     const navigation::RoutePlan& plan, int start,
                     const std::optional<std::vector<Eigen::Vector2d>>& truth_m);

}  // namespace omninav::report
