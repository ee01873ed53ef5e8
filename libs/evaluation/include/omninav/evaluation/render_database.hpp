#pragma once
// Rendering a trajectory into a BoB database: the renderer (libs/sim) feeding the dataset
// writer (libs/io). Used by `omninav render` and `omninav evaluate`.

#include <filesystem>
#include <string>
#include <vector>

#include "omninav/sim/renderer.hpp"
#include "omninav/sim/trajectory.hpp"

namespace omninav::evaluation {

// Renders every pose, frames in parallel on all cores (each frame is independent and the
// renderer is thread-safe, so the result does not depend on the number of threads), and
// writes them in order to a database in `folder`. Returns a few frames spread along the run
// for a contact sheet.
std::vector<cv::Mat> render_database(const sim::Renderer& renderer,
                                     const sim::Trajectory& trajectory,
                                     const std::filesystem::path& folder,
                                     const std::string& description, bool overwrite,
                                     std::size_t preview_frames = 12);

}  // namespace omninav::evaluation
