#include "omninav/report/lattice_figures.hpp"

#include <algorithm>
#include <set>

#include "omninav/lattice/stiffness.hpp"
#include "omninav/measures/plot.hpp"

namespace omninav::report {
namespace {

// The lattice, its springs shaded by stiffness.
cv::Mat springs_panel(const memory::VisualMemory& memory,
                      const lattice::OrganiseResult& organised) {
  std::vector<cv::Point2d> places;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    places.push_back(measures::plot_point(*memory.place(i).lattice_position));
  }
  measures::PointsPlot plot("Lattice: springs shaded by stiffness (dark = stiff)", "x (m)",
                            "y (m)");
  // Weak springs first, so that the stiff ones are drawn on top.
  std::vector<lattice::SpringMeasurement> springs = organised.springs;
  std::sort(springs.begin(), springs.end(),
            [](const lattice::SpringMeasurement& a, const lattice::SpringMeasurement& b) {
              return a.length_m > b.length_m;
            });
  for (const lattice::SpringMeasurement& spring : springs) {
    const double stiffness =
        lattice::spring_stiffness(spring.length_m, organised.calibration.correlation_range_m);
    if (stiffness < 1e-3) continue;  // too weak to see, and to matter
    plot.add_segment({places[spring.a], places[spring.b], 0.85 - 0.75 * stiffness, 0.6});
  }
  plot.add_points("places", places);
  return plot.render();
}

// The truth, the aligned lattice over it, and the places in a fold.
cv::Mat truth_panel(const memory::VisualMemory& memory, const LatticeOverTruth& truth) {
  measures::PointsPlot plot("Truth and the aligned lattice", "x (m)", "y (m)");
  std::vector<cv::Point2d> true_points, aligned_points;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    true_points.push_back(measures::plot_point(memory.place(i).truth->floor_position()));
    aligned_points.push_back(measures::plot_point(truth.aligned[i]));
    plot.add_segment({true_points.back(), aligned_points.back(), 0.5, 0.8});
  }
  plot.add_points("truth", true_points);
  plot.add_points("lattice, aligned", aligned_points);
  std::set<std::size_t> folded;
  for (const std::array<std::size_t, 3>& triangle : truth.folded) {
    folded.insert(triangle.begin(), triangle.end());
  }
  std::vector<cv::Point2d> folded_points;
  for (std::size_t place : folded) folded_points.push_back(aligned_points[place]);
  if (!folded_points.empty()) plot.add_points("in a fold (lattice)", folded_points);
  return plot.render();
}

}  // namespace

cv::Mat lattice_picture(const memory::VisualMemory& memory,
                        const lattice::OrganiseResult& organised, const LatticeOverTruth* truth) {
  cv::Mat picture = springs_panel(memory, organised);
  if (truth) cv::hconcat(picture, truth_panel(memory, *truth), picture);
  return picture;
}

}  // namespace omninav::report
