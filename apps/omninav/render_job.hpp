#pragma once
// Rendering a trajectory into a BoB database: the renderer (libs/sim) feeding the dataset
// writer (libs/io). Used by `omninav render` and `omninav demo`.

#include <filesystem>
#include <string>
#include <vector>

#include "omninav/eval/plot.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"

namespace omninav::cli {

// Renders every pose, frames in parallel on all cores (each frame is independent and the
// renderer is thread-safe, so the result does not depend on the number of threads), and
// writes them in order to a database in `folder`. Returns a few frames spread along the run
// for a contact sheet.
std::vector<cv::Mat> render_database(const sim::Renderer& renderer,
                                     const sim::Trajectory& trajectory,
                                     const std::filesystem::path& folder,
                                     const std::string& description, bool overwrite,
                                     std::size_t preview_frames = 12);

// Outlines of floor rectangles (obstacles, regions) as segments of grey level `grey`.
void add_floor_boxes(eval::PointsPlot& plot, const std::vector<sim::FloorBox>& boxes, double grey);

// The world seen from above: its floor, obstacles and named regions, and the trajectory's
// positions (plan.png of `omninav render`).
eval::PointsPlot floor_plan(const sim::World& world, const sim::Trajectory& trajectory);

}  // namespace omninav::cli
