#include "omninav/lattice/organise.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "driven_lattice.hpp"
#include "motions.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/lattice/similar_places.hpp"
#include "omninav/signature/plateau.hpp"

namespace omninav::lattice {
namespace {

// The step between consecutive places: the user's, else the map's spacing policy.
std::pair<double, ScaleSource> scale_of(const memory::VisualMemory& memory,
                                        const OrganiseParams& params) {
  if (params.step_m > 0.0) return {params.step_m, ScaleSource::kUser};
  if (memory.exploration_spacing_m()) return {*memory.exploration_spacing_m(), ScaleSource::kMap};
  if (memory.grid_spacing_m()) return {*memory.grid_spacing_m(), ScaleSource::kGrid};
  throw UsageError(
      "organise: the map does not say how far apart consecutive places are (explore with a "
      "spacing in metres or a grid database whose metadata states grid.separationMM, or give "
      "the step, e.g. --step-m 0.3)");
}

}  // namespace

std::string to_string(ScaleSource source) {
  switch (source) {
    case ScaleSource::kMap:
      return "map: exploration.every_m";
    case ScaleSource::kGrid:
      return "map: the grid database's grid.separationMM";
    case ScaleSource::kUser:
      break;
  }
  return "user";
}

std::vector<std::optional<double>> lattice_headings(const memory::VisualMemory& memory) {
  std::vector<std::optional<double>> headings(memory.place_count());
  const std::optional<double> first = memory.place(0).heading_rad;
  bool all = first.has_value();
  for (std::size_t i = 0; i < memory.place_count(); ++i)
    all = all && memory.place(i).heading_rad.has_value();
  if (all) {
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      headings[i] = signed_difference(*memory.place(i).heading_rad, *first);
    }
    return headings;
  }
  headings[0] = 0.0;
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    if (headings[edge.from] && !headings[edge.to]) {
      headings[edge.to] = wrap_angle(*headings[edge.from] + edge.edge->relative_heading_rad);
    }
  }
  return headings;
}

void OrganiseParams::check() const {
  check_range("organise.step_m", step_m, 0.0, 100.0);
  check_range("organise.neighbours", neighbours, 1, 1000);
  check_range("organise.range_fraction", range_fraction, 0.1, 0.99);
  check_range("organise.at_least_beyond_steps", at_least_beyond_steps, 1.0, 1000.0);
  check_range("organise.motion_neighbours", motion_neighbours, 0, 100);
  check_range("organise.step_likeness", step_likeness, 1.0, 10.0);
  check_range("organise.look_alike_residual", look_alike_residual, 1.0, 100.0);
  check_range("organise.step_check_steps", step_check_steps, 0, 1000);
  check_range("organise.step_check_sigmas", step_check_sigmas, 0.1, 100.0);
  check_range("organise.motion_direction_stddev_deg", motion_direction_stddev_deg, 0.1, 90.0);
  check_range("organise.motion_length_stddev", motion_length_stddev, 0.01, 10.0);
  check_range("organise.neighbour_motion_length_stddev", neighbour_motion_length_stddev, 0.01,
              10.0);
  check_range("organise.spring_weight", lattice.spring_weight, 0.0, 1.0);
  check_range("organise.min_stiffness", lattice.min_stiffness, 1e-9, 0.5);
  check_range("organise.loss_scale_m", lattice.loss_scale_m, 1e-4, 100.0);
  check_range("organise.motion_loss_scale", lattice.motion_loss_scale, 0.01, 100.0);
  check_range("organise.max_iterations", lattice.max_iterations, 1, 100000);
  check_range("organise.max_motions_off", max_motions_off, 0.0, 1.0);
  check_range("driven.odometry_noise", driven.odometry_noise, 1e-4, 1.0);
  check_range("driven.visual_turn_stddev_deg", driven.visual_turn_stddev_deg, 0.01, 180.0);
  driven.solver.check();
}

void load_driven_params(const ConfigReader& section, DrivenLatticeParams& params) {
  section.read("odometry_noise", params.odometry_noise);
  section.read("visual_turn_stddev_deg", params.visual_turn_stddev_deg);
  section.read("switch_prior_stddev", params.solver.switch_prior_stddev);
  section.read("max_iterations", params.solver.max_iterations);
}

void load_organise_params(const ConfigReader& section, OrganiseParams& params) {
  section.read("step_m", params.step_m);
  section.read("neighbours", params.neighbours);
  section.read("range_fraction", params.range_fraction);
  section.read("at_least_beyond_steps", params.at_least_beyond_steps);
  section.read("motion_constraints", params.motion_constraints);
  section.read("motion_neighbours", params.motion_neighbours);
  section.read("steps_along_heading", params.steps_along_heading);
  section.read("synchronise_compass_headings", params.synchronise_compass_headings);
  section.read("step_likeness", params.step_likeness);
  section.read("look_alike_residual", params.look_alike_residual);
  section.read("step_check_steps", params.step_check_steps);
  section.read("step_check_sigmas", params.step_check_sigmas);
  section.read("motion_direction_stddev_deg", params.motion_direction_stddev_deg);
  section.read("motion_length_stddev", params.motion_length_stddev);
  section.read("neighbour_motion_length_stddev", params.neighbour_motion_length_stddev);
  section.read("spring_weight", params.lattice.spring_weight);
  section.read("min_stiffness", params.lattice.min_stiffness);
  section.read("loss_scale_m", params.lattice.loss_scale_m);
  section.read("motion_loss_scale", params.lattice.motion_loss_scale);
  section.read("max_iterations", params.lattice.max_iterations);
  section.read("max_motions_off", params.max_motions_off);
  check_loaded(section.source_name(), [&] { params.check(); });
}

memory::LatticeQuality measure_quality(const std::vector<Eigen::Vector2d>& positions,
                                       const std::vector<MotionMeasurement>& motions, int joins,
                                       double step_m, double max_motions_off) {
  memory::LatticeQuality quality;
  quality.pieces = 1 + joins;
  // The joins are the last motions (motions.hpp): they rest on look-alikes, not checked ones.
  const std::size_t checked = motions.size() - std::min<std::size_t>(motions.size(), joins);
  std::vector<double> residuals;
  int off = 0;
  for (std::size_t i = 0; i < checked; ++i) {
    const MotionMeasurement& motion = motions[i];
    const Eigen::Vector2d measured =
        motion.length_m *
        Eigen::Vector2d(std::cos(motion.direction_rad), std::sin(motion.direction_rad));
    const Eigen::Vector2d on_lattice = positions[motion.to] - positions[motion.from];
    residuals.push_back((on_lattice - measured).norm() / step_m);
    const double cosine = on_lattice.dot(measured) / (on_lattice.norm() * measured.norm() + 1e-300);
    off += cosine < std::cos(M_PI / 4.0);
  }
  quality.motions = static_cast<int>(checked);
  if (checked > 0) {
    quality.motion_residual_steps = median(std::move(residuals));
    quality.motions_off = static_cast<double>(off) / static_cast<double>(checked);
  }
  quality.trustworthy = quality.pieces == 1 && quality.motions_off <= max_motions_off;
  return quality;
}

double DistanceCalibration::distance_m(int a, int b, double dissimilarity) const {
  return step_m * dissimilarity /
         std::sqrt(local_step_dissimilarity[a] * local_step_dissimilarity[b]);
}

namespace {

// Pairs whose dissimilarities give the plateau (Fig. 7): all pairs of maps up to ~1,400 places,
// an even sample of this many beyond (its 90th percentile is then within ~0.1 % of rank).
constexpr std::size_t kPlateauPairs = std::size_t{1} << 20;

// Each place's most similar other places, most similar first: searched once, for the local step
// (the first), the motions and the springs (the first few of each list).
using Ranking = std::vector<std::vector<SimilarPlace>>;

// Calibrates distance against dissimilarity at the scale already in `calibration`.
void calibrate(const PlaceDissimilarities& dissimilarity, const Ranking& ranking,
               const OrganiseParams& params, DistanceCalibration& calibration) {
  for (const std::vector<SimilarPlace>& similar : ranking) {
    calibration.local_step_dissimilarity.push_back(similar.front().dissimilarity);
  }
  calibration.step_dissimilarity = median(calibration.local_step_dissimilarity);
  calibration.plateau_dissimilarity =
      dissimilarity.pair_quantile(signature::kPlateauQuantile, kPlateauPairs);
  const double smallest = *std::min_element(calibration.local_step_dissimilarity.begin(),
                                            calibration.local_step_dissimilarity.end());
  if (!(smallest > 0.0) || calibration.plateau_dissimilarity <= calibration.step_dissimilarity) {
    throw UsageError("organise: " +
                     std::string(!(smallest > 0.0)
                                     ? "two places have identical signatures"
                                     : "neighbouring places look as different as any two") +
                     "; the map cannot be calibrated");
  }
  calibration.correlation_range_m = params.range_fraction * calibration.step_m *
                                    calibration.plateau_dissimilarity /
                                    calibration.step_dissimilarity;
}

}  // namespace

OrganiseResult organise(memory::VisualMemory& memory, const OrganiseParams& params) {
  params.check();
  const int count = static_cast<int>(memory.place_count());
  if (count < 2)
    throw UsageError("organise: the map has " + std::to_string(count) +
                     " place(s); a lattice needs two");
  OrganiseResult result;
  DistanceCalibration& calibration = result.calibration;
  std::tie(calibration.step_m, calibration.step_source) = scale_of(memory, params);
  const bool driven = detail::driven_with_odometry(memory);
  const PlaceDissimilarities dissimilarity(memory);
  // One search of each place's most similar places for the calibration, the springs and the
  // motions (and a driven map's revisits): exact for the spring model, whose lattice rests on
  // them; from an index for a driven map, whose pose graph may reject what they propose.
  const int ranked = std::max({1, params.neighbours, params.motion_neighbours,
                               driven ? params.links.revisit_candidates : 0});
  const Ranking ranking =
      driven ? dissimilarity.most_similar_indexed(ranked) : dissimilarity.most_similar(ranked);
  try {
    calibrate(dissimilarity, ranking, params, calibration);
  } catch (const UsageError& error) {
    if (!driven) throw;
    // A map made by driving needs the calibration only for its springs, weak constraints.
    log_warning(std::string(error.what()) + "; the pose graph goes without springs");
  }

  // Springs (Eq. 4): each place to its most similar places, once per pair; those beyond the
  // range where the calibrated distance follows the truth only push.
  std::set<std::pair<int, int>> sprung;
  for (int a = 0; calibration.correlation_range_m > 0.0 && a < count; ++a) {
    for (const SimilarPlace& similar : most_similar_first(ranking[a], params.neighbours)) {
      const int b = similar.place;
      if (sprung.insert({std::min(a, b), std::max(a, b)}).second) {
        const double length_m = calibration.distance_m(a, b, similar.dissimilarity);
        result.springs.push_back(
            {a, b, length_m, length_m > params.at_least_beyond_steps * calibration.step_m});
      }
    }
  }
  if (driven) {
    detail::organise_driven(memory, params, dissimilarity, ranking, result);
    memory.set_lattice_quality(result.quality);
    log_info("organise: a pose graph of " + std::to_string(result.travelled_links) +
             " travelled links and " + std::to_string(result.revisits) + " revisits (" +
             std::to_string(result.revisits_switched_off) + " switched off); quality: " +
             std::to_string(result.quality.motions_off) + " of motions off, residual " +
             std::to_string(result.quality.motion_residual_steps) + " steps, " +
             std::to_string(result.quality.pieces) + " piece(s); " + result.lattice.summary);
    return result;
  }
  int pieces = 1;
  if (params.motion_constraints) {
    detail::MeasuredMotions measured =
        detail::measure_motions(memory, dissimilarity, ranking, calibration, params);
    result.motions = std::move(measured.motions);
    result.look_alikes_dropped = measured.look_alikes_dropped;
    result.motion_joins = measured.joins;
    pieces = measured.pieces;
  }

  LatticeParams lattice = params.lattice;
  lattice.correlation_range_m = calibration.correlation_range_m;
  result.lattice = solve_lattice(count, result.springs, result.motions, lattice);
  memory.set_lattice_positions(result.lattice.positions);
  result.quality = measure_quality(result.lattice.positions, result.motions, result.motion_joins,
                                   calibration.step_m, params.max_motions_off);
  // The pieces the checked motions left, not the joins added (the verdict is about the former).
  result.quality.pieces = pieces;
  result.quality.trustworthy = pieces == 1 && result.quality.motions_off <= params.max_motions_off;
  memory.set_lattice_quality(result.quality);
  log_info("organise: " + std::to_string(result.lattice.springs_kept) + " of " +
           std::to_string(result.lattice.springs_given) + " springs kept (of " +
           std::to_string(result.lattice.place_pairs) + " pairs of places), " +
           std::to_string(result.motions.size()) + " motions (" +
           std::to_string(result.look_alikes_dropped) + " look-alikes dropped, " +
           std::to_string(result.motion_joins) + " added to join the lattice); quality: " +
           std::to_string(result.quality.motions_off) + " of motions off, residual " +
           std::to_string(result.quality.motion_residual_steps) + " steps, " +
           std::to_string(result.quality.pieces) + " piece(s); " + result.lattice.summary);
  return result;
}

}  // namespace omninav::lattice
