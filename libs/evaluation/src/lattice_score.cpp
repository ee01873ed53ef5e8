#include "omninav/evaluation/lattice_score.hpp"

#include <fmt/format.h>

#include <map>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/memory/localisation.hpp"

namespace omninav::evaluation {
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
    points.push_back(*memory.place(i).lattice_position);
  }
  return points;
}

// Places with fewer than 8 true neighbours within 1.5 spacings.
std::vector<std::size_t> boundary_places(const std::vector<Eigen::Vector2d>& truth,
                                         double spacing_m) {
  std::vector<std::size_t> boundary;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    int neighbours = 0;
    for (std::size_t j = 0; j < truth.size(); ++j) {
      neighbours += i != j && (truth[i] - truth[j]).norm() <= 1.5 * spacing_m;
    }
    if (neighbours < 8) boundary.push_back(i);
  }
  return boundary;
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

std::optional<LatticeScore> score_lattice(const memory::VisualMemory& memory,
                                          bool allow_reflection) {
  if (!memory.all_have_truth() || !memory.all_have_lattice() || memory.place_count() < 3)
    return std::nullopt;
  std::vector<Eigen::Vector2d> truth;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const CameraPose& pose = *memory.place(i).truth;
    if (!plausible_position(pose)) {
      log_warning(fmt::format(
          "place {}'s true position ({}, {}) m is not finite or farther than {} km from the "
          "origin: the lattice is not compared with the truth",
          i, general(pose.x_m), general(pose.y_m), general(kMaxCoordinateM / 1000)));
      return std::nullopt;
    }
    truth.push_back(pose.floor_position());
  }
  LatticeScore score;
  score.spacing_m = memory::typical_spacing(truth);
  score.boundary = boundary_places(truth, score.spacing_m);
  measures::ProcrustesParams params;
  params.allow_reflection = allow_reflection;
  const measures::ProcrustesResult aligned =
      measures::align_similarity(lattice_points(memory), truth, params);
  score.aligned = aligned.aligned;
  score.rmse =
      measures::split_rmse_in_spacing(aligned.aligned, truth, score.boundary, score.spacing_m);
  const std::vector<std::array<std::size_t, 3>> triangles =
      neighbour_triangles(truth, 1.5 * score.spacing_m);
  score.neighbour_triangles = static_cast<int>(triangles.size());
  for (const std::array<std::size_t, 3>& triangle : triangles) {
    // Turned over, or flattened to a line (a lattice collapsed onto itself).
    if (signed_area(score.aligned, triangle) <= 0.0) score.folded.push_back(triangle);
  }
  return score;
}

}  // namespace omninav::evaluation
