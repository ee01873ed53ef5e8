#include "driven_lattice.hpp"

#include <cmath>
#include <optional>

#include "odometry_step.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/signature/phase_heading.hpp"

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

std::vector<RelativePoseMeasurement> link_measurements(const memory::VisualMemory& memory,
                                                       const std::vector<MeasuredLink>& links,
                                                       const std::vector<double>& headings_rad,
                                                       double spacing_m,
                                                       const OrganiseParams& params) {
  const double visual_turn = deg_to_rad(params.driven.visual_turn_stddev_deg);
  const double noise = params.driven.odometry_noise;
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
      // baseline too short for the phases' direction to say much; their turn from the phases.
      m.along_stddev_m = m.across_stddev_m = spacing_m;
      m.turn_rad = signature::relative_heading(memory.place(a).signature, memory.place(b).signature)
                       .turn_rad;
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
