#include "driven_lattice.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include "odometry_step.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/signature/motion.hpp"
#include "omninav/signature/phase_heading.hpp"
#include "two_way_fit.hpp"

namespace omninav::lattice::detail {

bool driven_with_odometry(const memory::VisualMemory& memory) {
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    if (edge.edge->kind == memory::EdgeKind::kSequence && memory.place(edge.from).odometry &&
        memory.place(edge.to).odometry) {
      return true;
    }
  }
  return false;
}

namespace {

// How far apart a revisit's places are, from the phases. The motion fitted between two views
// measures their parallax ρ = d / r, the baseline d over the depth r of the scene (signature/
// motion.hpp); the travelled steps at either place see the same scene over a baseline the
// odometry measured, and so give its depth, r = d / ρ. A revisit's length is its parallax times
// the median depth of the steps into and out of its two places.
class RevisitLength {
 public:
  RevisitLength(const memory::VisualMemory& memory, const std::vector<double>& headings_rad,
                double spacing_m)
      : memory_(memory),
        headings_(headings_rad),
        spacing_m_(spacing_m),
        next_(memory.place_count(), -1),
        previous_(memory.place_count(), -1),
        depth_after_(memory.place_count()) {
    for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
      if (edge.edge->kind != memory::EdgeKind::kSequence) continue;
      next_[edge.from] = static_cast<int>(edge.to);
      previous_[edge.to] = static_cast<int>(edge.from);
    }
  }

  // None when no step at either place has both odometry and a fit.
  std::optional<double> length_m(std::pair<int, int> places, double parallax_rad) {
    std::vector<double> depths;
    for (const int place : {places.first, places.second}) {
      for (const int step_from : {previous_[place], next_[place] >= 0 ? place : -1}) {
        if (step_from < 0) continue;
        if (const std::optional<double> depth = depth_after(step_from)) depths.push_back(*depth);
      }
    }
    if (depths.empty()) return std::nullopt;
    return parallax_rad * median(std::move(depths));
  }

 private:
  // The depth seen by the step from `place` to the next place of its stream, fitted once and
  // one way: the depth needs only the parallax, which one fit gives at half the cost (a two-way
  // fit's agreement checks a direction; on the benchmark's tours the lattices came out the same
  // within 0.01 spacings).
  std::optional<double> depth_after(int place) {
    std::optional<std::optional<double>>& depth = depth_after_[place];
    if (depth) return *depth;
    depth.emplace();
    const int next = next_[place];
    const std::optional<OdometryStep> step = odometry_step(memory_, place, next);
    // A step on the spot has no baseline; its parallax is noise.
    if (!step || step->translation_m.norm() < 0.1 * spacing_m_) return *depth;
    const signature::MotionEstimate fit =
        signature::estimate_motion(memory_.place(place).signature, memory_.place(next).signature,
                                   -1, signed_difference(headings_[next], headings_[place]));
    if (fit.valid && fit.parallax_rad > 0.0) *depth = step->translation_m.norm() / fit.parallax_rad;
    return *depth;
  }

  const memory::VisualMemory& memory_;
  const std::vector<double>& headings_;
  double spacing_m_;
  std::vector<int> next_, previous_;
  std::vector<std::optional<std::optional<double>>> depth_after_;  // outer: fitted yet
};

// A revisit's parallax and direction (at its first place) from the motion fitted at the turn the
// images bear out. The confirmed links fit it holding the turn at the stored headings'; it is
// fitted again at the phases' turn, and the fit with the smaller residual is kept. A fit held at a
// wrong turn explains the difference by translation (signature/motion.hpp: held 5° off, the
// direction's 90th percentile error rose to 17-30°), and the stored headings between a stretch
// and its revisit are as far apart as the compass drifted in between: 14° on the README's room
// tour, where a degree more drift switched off one more revisit and moved the lattice by 0.17
// spacings; on the evaluation suite's house maps, whose compass headings miss by up to 100°,
// parallaxes of up to 3 rad between places half a spacing apart, lengths of 10-17 spacings.
std::pair<double, double> revisit_parallax(const memory::VisualMemory& memory,
                                           const MeasuredLink& revisit, double phases_turn_rad) {
  const std::pair<double, double> held{revisit.parallax_rad, revisit.direction_at_first_rad};
  const auto [a, b] = revisit.places;
  const std::optional<TwoWayFit> at_phases = fit_two_way(memory, a, b, phases_turn_rad);
  if (!at_phases || revisit.fit_residual <= at_phases->residual) return held;
  return {at_phases->parallax_rad, at_phases->direction_at_a_rad};
}

}  // namespace

std::vector<RelativePoseMeasurement> link_measurements(const memory::VisualMemory& memory,
                                                       const std::vector<MeasuredLink>& links,
                                                       const std::vector<double>& headings_rad,
                                                       double spacing_m,
                                                       const OrganiseParams& params) {
  const double visual_turn = deg_to_rad(params.driven.visual_turn_stddev_deg);
  const double noise = params.driven.odometry_noise;
  RevisitLength revisit_length(memory, headings_rad, spacing_m);
  std::vector<RelativePoseMeasurement> measurements;
  for (const MeasuredLink& link : links) {
    const auto [a, b] = link.places;
    RelativePoseMeasurement m;
    m.from = a;
    m.to = b;
    const double direction = link.direction_at_first_rad;
    m.translation_m = link.length_m * Eigen::Vector2d(std::cos(direction), std::sin(direction));
    m.turn_rad = signed_difference(headings_rad[b], headings_rad[a]);
    const std::optional<OdometryStep> step =
        link.kind == LinkKind::kTravelled ? odometry_step(memory, a, b) : std::nullopt;
    if (step) {
      m.translation_m = step->translation_m;
      m.turn_rad = step->turn_rad;
      const OdometryStepStddev stddev = odometry_step_stddev(*step, noise, spacing_m);
      m.along_stddev_m = m.across_stddev_m = stddev.translation_m;
      m.turn_stddev_rad = stddev.turn_rad;
    } else if (link.kind == LinkKind::kRevisit) {
      // Two stretches seen again: the places lie within about a spacing of each other, a
      // baseline too short for the phases' direction to say much; their length from the
      // parallax, their turn from the phases (its direction and parallax from the motion fitted
      // at the turn the images bear out, revisit_parallax).
      m.turn_rad = signature::relative_heading(memory.place(a).signature, memory.place(b).signature)
                       .turn_rad;
      const auto [parallax, fitted_direction] = revisit_parallax(memory, link, m.turn_rad);
      if (const std::optional<double> length = revisit_length.length_m(link.places, parallax)) {
        m.translation_m =
            *length * Eigen::Vector2d(std::cos(fitted_direction), std::sin(fitted_direction));
      }
      m.along_stddev_m = m.across_stddev_m = spacing_m;
      m.turn_stddev_rad = visual_turn;
      m.switchable = true;
    } else {
      // A step of the spacing in the phases' direction (§3.4), the turn the compass's.
      m.along_stddev_m = params.motion_length_stddev * link.length_m;
      m.across_stddev_m = link.length_m * deg_to_rad(params.motion_direction_stddev_deg);
      m.turn_stddev_rad = visual_turn;
    }
    measurements.push_back(m);
  }
  return measurements;
}

void organise_driven(memory::VisualMemory& memory, const OrganiseParams& params,
                     const PlaceDissimilarities& dissimilarity,
                     const std::vector<std::vector<SimilarPlace>>& most_similar,
                     OrganiseResult& result) {
  const int count = static_cast<int>(memory.place_count());
  const double spacing_m = result.calibration.step_m;
  std::vector<double> headings;
  for (const std::optional<double>& heading : lattice_headings(memory)) {
    headings.push_back(heading.value_or(0.0));
  }
  const std::vector<MeasuredLink> links =
      confirmed_links(memory, headings, spacing_m, params.links, dissimilarity, most_similar);
  const std::vector<RelativePoseMeasurement> measurements =
      link_measurements(memory, links, headings, spacing_m, params);
  LatticeParams springs = params.lattice;
  springs.correlation_range_m = result.calibration.correlation_range_m;
  const PoseGraphResult solved =
      solve_pose_graph(count, measurements, result.springs, springs, params.driven.solver);

  LatticeResult& lattice_result = result.lattice;
  for (const Eigen::Vector3d& pose : solved.poses)
    lattice_result.positions.push_back(pose.head<2>());
  lattice_result.motion_constraints = measurements.size();
  lattice_result.converged = solved.converged;
  lattice_result.summary = solved.summary;
  std::size_t next_switch = 0;
  for (const RelativePoseMeasurement& m : measurements) {
    const bool kept = !m.switchable || solved.switches[next_switch++] >= 0.5;
    result.travelled_links += m.switchable ? 0 : 1;
    result.revisits += m.switchable ? 1 : 0;
    result.revisits_switched_off += kept ? 0 : 1;
    // The quality compares displacements; a turn on the spot has none.
    if (!kept || m.translation_m.norm() < 0.01 * spacing_m) continue;
    MotionMeasurement motion;
    motion.from = m.from;
    motion.to = m.to;
    motion.direction_rad =
        wrap_angle(solved.poses[m.from].z() + std::atan2(m.translation_m.y(), m.translation_m.x()));
    motion.length_m = m.translation_m.norm();
    motion.step = !m.switchable;
    result.motions.push_back(motion);
  }
  memory.set_lattice_positions(lattice_result.positions);
  result.quality = measure_quality(lattice_result.positions, result.motions, 0, spacing_m,
                                   params.max_motions_off);
  result.quality.pieces = solved.pieces;
  result.quality.trustworthy =
      solved.pieces == 1 && result.quality.motions_off <= params.max_motions_off;
}

}  // namespace omninav::lattice::detail
