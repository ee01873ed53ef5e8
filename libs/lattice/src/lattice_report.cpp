#include "omninav/lattice/lattice_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>
#include <utility>

#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/eval/plot.hpp"
#include "omninav/lattice/stiffness.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_file.hpp"

namespace omninav::lattice {
namespace {

// Twice the signed area of a triangle: positive when its corners go counter-clockwise.
double signed_area(const std::vector<Eigen::Vector2d>& points,
                   const std::array<std::size_t, 3>& triangle) {
  const Eigen::Vector2d u = points[triangle[1]] - points[triangle[0]];
  const Eigen::Vector2d v = points[triangle[2]] - points[triangle[0]];
  return u.x() * v.y() - u.y() * v.x();
}

std::vector<Eigen::Vector2d> lattice_points(const memory::VisualMemory& memory) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const memory::LatticePosition& p = *memory.place(i).lattice;
    points.emplace_back(p.x, p.y);
  }
  return points;
}

// The triangles of the truth's Delaunay triangulation (OpenCV's Subdiv2D) whose sides are all
// at most `longest_side` long, as place indices in counter-clockwise order.
std::vector<std::array<std::size_t, 3>> neighbour_triangles(
    const std::vector<Eigen::Vector2d>& truth, double longest_side) {
  std::map<std::pair<float, float>, std::size_t> index_of;
  std::vector<cv::Point2f> points;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    points.emplace_back(static_cast<float>(truth[i].x()), static_cast<float>(truth[i].y()));
    index_of.emplace(std::pair{points.back().x, points.back().y}, i);
  }
  // Subdiv2D wants every point strictly inside its (integer) rectangle.
  const cv::Rect bounds = cv::boundingRect(points);
  cv::Subdiv2D subdivision(
      cv::Rect(bounds.x - 1, bounds.y - 1, bounds.width + 3, bounds.height + 3));
  subdivision.insert(points);
  std::vector<cv::Vec6f> corners;
  subdivision.getTriangleList(corners);
  std::vector<std::array<std::size_t, 3>> triangles;
  for (const cv::Vec6f& c : corners) {
    std::array<std::size_t, 3> triangle{};
    bool known = true;
    for (int k = 0; k < 3; ++k) {
      const auto found = index_of.find({c[2 * k], c[2 * k + 1]});
      known = known && found != index_of.end();
      if (known) triangle[k] = found->second;
    }
    if (!known) continue;  // a corner of Subdiv2D's outer triangle
    bool short_sides = true;
    for (int k = 0; k < 3; ++k) {
      short_sides =
          short_sides && (truth[triangle[k]] - truth[triangle[(k + 1) % 3]]).norm() <= longest_side;
    }
    if (!short_sides) continue;
    if (signed_area(truth, triangle) < 0.0) std::swap(triangle[1], triangle[2]);
    triangles.push_back(triangle);
  }
  return triangles;
}

}  // namespace

std::optional<LatticeEvaluation> evaluate_against_truth(const memory::VisualMemory& memory,
                                                        bool allow_reflection) {
  if (!memory.all_have_truth() || !memory.all_have_lattice() || memory.place_count() < 3)
    return std::nullopt;
  std::vector<Eigen::Vector2d> truth;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const CameraPose& pose = *memory.place(i).truth;
    if (!plausible_position(pose)) {
      std::ostringstream message;
      message << "place " << i << "'s true position (" << pose.x_m << ", " << pose.y_m
              << ") m is not finite or farther than " << kMaxCoordinateM / 1000
              << " km from the origin: the lattice is not compared with the truth";
      log_warning(message.str());
      return std::nullopt;
    }
    truth.emplace_back(pose.x_m, pose.y_m);
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
  const std::vector<std::array<std::size_t, 3>> triangles =
      neighbour_triangles(truth, 1.5 * evaluation.spacing_m);
  evaluation.neighbour_triangles = static_cast<int>(triangles.size());
  for (const std::array<std::size_t, 3>& triangle : triangles) {
    // Turned over, or flattened to a line (a lattice collapsed onto itself).
    if (signed_area(evaluation.aligned, triangle) <= 0.0) evaluation.folded.push_back(triangle);
  }
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
    eval::PointsPlot truth("Truth and the aligned lattice", "x (m)", "y (m)");
    std::vector<cv::Point2d> true_points, aligned_points;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      true_points.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
      aligned_points.emplace_back(evaluation->aligned[i].x(), evaluation->aligned[i].y());
      truth.add_segment({true_points.back(), aligned_points.back(), 0.5, 0.8});
    }
    truth.add_points("truth", true_points);
    truth.add_points("lattice, aligned", aligned_points);
    std::set<std::size_t> folded;
    for (const std::array<std::size_t, 3>& triangle : evaluation->folded)
      folded.insert(triangle.begin(), triangle.end());
    std::vector<cv::Point2d> folded_points;
    for (std::size_t place : folded) folded_points.push_back(aligned_points[place]);
    if (!folded_points.empty()) truth.add_points("in a fold (lattice)", folded_points);
    cv::hconcat(picture, truth.render(), picture);
  }
  return picture;
}

OrganisedMap organise_map_file(const std::filesystem::path& map_file,
                               const OrganiseParams& params) {
  OrganisedMap result{memory::load_map(map_file), {}, std::nullopt, {}};
  result.organised = organise(result.memory, params);
  for (std::size_t i = 0; i < result.memory.place_count(); ++i) {
    const memory::LatticePosition& position = *result.memory.place(i).lattice;
    if (!std::isfinite(position.x) || !std::isfinite(position.y)) {
      throw InputError(map_file.string() + ": the lattice has no finite position for place " +
                       std::to_string(i) + "; the map is left unchanged");
    }
    result.positions.push_back(position);
  }
  result.evaluation = evaluate_against_truth(result.memory, result.organised.motions.empty());
  return result;
}

}  // namespace omninav::lattice
