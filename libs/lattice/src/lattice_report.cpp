#include "omninav/lattice/lattice_report.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "omninav/eval/plot.hpp"
#include "omninav/lattice/stiffness.hpp"
#include "omninav/memory/localisation.hpp"

namespace omninav::lattice {
namespace {

std::vector<Eigen::Vector2d> lattice_points(const memory::VisualMemory& memory) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const memory::LatticePosition& p = *memory.place(i).lattice;
    points.emplace_back(p.x, p.y);
  }
  return points;
}

}  // namespace

std::optional<LatticeEvaluation> evaluate_against_truth(const memory::VisualMemory& memory,
                                                        bool allow_reflection) {
  if (!memory.all_have_truth() || !memory.all_have_lattice() || memory.place_count() < 3)
    return std::nullopt;
  std::vector<Eigen::Vector2d> truth;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    truth.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
  }
  LatticeEvaluation evaluation;
  std::vector<cv::Point2d> truth_points;
  for (const Eigen::Vector2d& t : truth) truth_points.emplace_back(t.x(), t.y());
  evaluation.spacing_m = memory::typical_spacing(truth_points);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    int neighbours = 0;
    for (std::size_t j = 0; j < truth.size(); ++j) {
      neighbours += i != j && (truth[i] - truth[j]).norm() <= 1.5 * evaluation.spacing_m;
    }
    if (neighbours < 8) evaluation.boundary.push_back(i);
  }
  eval::ProcrustesParams params;
  params.allow_reflection = allow_reflection;
  const eval::ProcrustesResult aligned =
      eval::align_similarity(lattice_points(memory), truth, params);
  evaluation.aligned = aligned.aligned;
  evaluation.rmse = eval::split_rmse_in_spacing(aligned.aligned, truth, evaluation.boundary,
                                                evaluation.spacing_m);
  return evaluation;
}

cv::Mat lattice_picture(const memory::VisualMemory& memory, const OrganiseResult& organised,
                        const std::optional<LatticeEvaluation>& evaluation) {
  const std::vector<Eigen::Vector2d> points = lattice_points(memory);
  eval::PointsPlot lattice("Lattice: springs shaded by stiffness (dark = stiff)", "x (m)", "y (m)");
  // Weak springs first, so that the stiff ones are drawn on top.
  std::vector<SpringMeasurement> springs = organised.springs;
  std::sort(springs.begin(), springs.end(),
            [](const SpringMeasurement& a, const SpringMeasurement& b) {
              return a.length_m > b.length_m;
            });
  for (const SpringMeasurement& spring : springs) {
    const double stiffness =
        spring_stiffness(spring.length_m, organised.calibration.correlation_range_m);
    if (stiffness < 1e-3) continue;  // too weak to see, and to matter
    lattice.add_segment({cv::Point2d(points[spring.a].x(), points[spring.a].y()),
                         cv::Point2d(points[spring.b].x(), points[spring.b].y()),
                         0.85 - 0.75 * stiffness, 0.6});
  }
  std::vector<cv::Point2d> places;
  for (const Eigen::Vector2d& p : points) places.emplace_back(p.x(), p.y());
  lattice.add_points("places", places);
  cv::Mat picture = lattice.render();
  if (evaluation) {
    eval::PointsPlot truth("Truth (blue) and the aligned lattice (orange)", "x (m)", "y (m)");
    std::vector<cv::Point2d> true_points, aligned_points;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      true_points.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
      aligned_points.emplace_back(evaluation->aligned[i].x(), evaluation->aligned[i].y());
      truth.add_segment({true_points.back(), aligned_points.back(), 0.5, 0.8});
    }
    truth.add_points("truth", true_points);
    truth.add_points("lattice, aligned", aligned_points);
    cv::hconcat(picture, truth.render(), picture);
  }
  return picture;
}

}  // namespace omninav::lattice
