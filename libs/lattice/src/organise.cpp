#include "omninav/lattice/organise.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::lattice {
namespace {

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

double quantile(std::vector<double> values, double share) {
  const std::size_t index =
      std::min(values.size() - 1, static_cast<std::size_t>(share * values.size()));
  std::nth_element(values.begin(), values.begin() + index, values.end());
  return values[index];
}

// The step between consecutive places: the user's, else the map's spacing policy.
std::pair<double, std::string> scale_of(const memory::VisualMemory& memory,
                                        const OrganiseParams& params) {
  if (params.step_m > 0.0) return {params.step_m, "user"};
  const auto note = memory.notes().find("exploration.every_m");
  if (note != memory.notes().end()) {
    const double every_m = parse_double(note->second, "map note exploration.every_m");
    if (every_m > 0.0) return {every_m, "map: exploration.every_m"};
  }
  throw UsageError(
      "organise: the map does not say how far apart consecutive places are (explore with a "
      "spacing in metres, or give the step, e.g. --step-m 0.3)");
}

}  // namespace

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

void load_organise_params(const ConfigReader& section, OrganiseParams& params) {
  section.read("step_m", params.step_m, 0.0, 100.0);
  section.read("neighbours", params.neighbours, 1, 1000);
  section.read("range_fraction", params.range_fraction, 0.1, 0.99);
  section.read("motion_constraints", params.motion_constraints);
  section.read("min_motion_confidence", params.min_motion_confidence, 0.0, 1.0);
  section.read("min_stiffness", params.lattice.min_stiffness, 1e-9, 0.5);
  section.read("loss_scale_m", params.lattice.loss_scale_m, 1e-4, 100.0);
  section.read("max_iterations", params.lattice.max_iterations, 1, 100000);
}

double DistanceCalibration::distance_m(double dissimilarity) const {
  // Clamp below the plateau: beyond it, images no longer tell distance (x → ∞).
  const double share = std::min(dissimilarity / plateau_dissimilarity, 0.99);
  return -length_scale_m * std::log1p(-share);
}

OrganiseResult organise(memory::VisualMemory& memory, const OrganiseParams& params) {
  const int count = static_cast<int>(memory.place_count());
  if (count < 2)
    throw UsageError("organise: the map has " + std::to_string(count) +
                     " place(s); a lattice needs two");
  OrganiseResult result;
  DistanceCalibration& calibration = result.calibration;
  std::tie(calibration.step_m, calibration.step_source) = scale_of(memory, params);

  // Every pair's dissimilarity (the map's own components and weights), and each place's most
  // similar others as its springs.
  const signature::ComponentWeights& weights = memory.parameters().weights;
  std::vector<double> all;
  std::vector<std::vector<std::pair<double, int>>> nearest(count);
  for (int a = 0; a < count; ++a) {
    for (int b = a + 1; b < count; ++b) {
      const double d = signature::dissimilarity(memory.place(a).signature,
                                                memory.place(b).signature, -1, weights);
      all.push_back(d);
      nearest[a].emplace_back(d, b);
      nearest[b].emplace_back(d, a);
    }
  }
  std::vector<double> consecutive;
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges())
    consecutive.push_back(edge.edge->dissimilarity);
  if (consecutive.empty())
    throw UsageError("organise: the map has no edges between consecutive places");
  calibration.step_dissimilarity = median(consecutive);
  calibration.plateau_dissimilarity = quantile(all, 0.9);
  if (!(calibration.step_dissimilarity > 0.0) ||
      calibration.plateau_dissimilarity <= calibration.step_dissimilarity) {
    throw UsageError(
        "organise: consecutive places look as different as any two places; the map cannot be "
        "calibrated");
  }
  // Slope at 0 of D(x) = D_sat(1 − e^(−x/λ)) through (step, D_step): λ from the exact inverse.
  calibration.length_scale_m = calibration.step_m / -std::log1p(-calibration.step_dissimilarity /
                                                                calibration.plateau_dissimilarity);
  calibration.correlation_range_m =
      -calibration.length_scale_m * std::log1p(-params.range_fraction);

  std::vector<SpringMeasurement>& springs = result.springs;
  for (int a = 0; a < count; ++a) {
    std::vector<std::pair<double, int>>& candidates = nearest[a];
    const std::size_t keep = std::min<std::size_t>(params.neighbours, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + keep, candidates.end());
    for (std::size_t i = 0; i < keep; ++i) {
      const int b = candidates[i].second;
      if (a < b || std::none_of(nearest[b].begin(),
                                nearest[b].begin() +
                                    std::min<std::size_t>(params.neighbours, nearest[b].size()),
                                [a](const auto& item) { return item.second == a; })) {
        springs.push_back({a, b, calibration.distance_m(candidates[i].first)});
      }
    }
  }

  std::vector<MotionMeasurement>& motions = result.motions;
  if (params.motion_constraints) {
    const std::vector<std::optional<double>> headings = lattice_headings(memory);
    for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
      const memory::Edge& e = *edge.edge;
      if (!e.motion_bearing_rad || !headings[edge.from] ||
          e.heading_confidence < params.min_motion_confidence)
        continue;
      motions.push_back({static_cast<int>(edge.from), static_cast<int>(edge.to),
                         wrap_angle(*headings[edge.from] + *e.motion_bearing_rad),
                         std::max(e.motion_bearing_stddev_rad, deg_to_rad(5.0))});
    }
  }

  LatticeParams lattice = params.lattice;
  lattice.correlation_range_m = calibration.correlation_range_m;
  result.lattice = solve_lattice(count, springs, motions, lattice);
  for (int i = 0; i < count; ++i) {
    memory.place(i).lattice =
        memory::LatticePosition{result.lattice.positions[i].x(), result.lattice.positions[i].y()};
  }
  log_info("organise: " + std::to_string(result.lattice.springs_kept) + " of " +
           std::to_string(result.lattice.springs_given) + " springs kept, " +
           std::to_string(motions.size()) + " motion constraints; " + result.lattice.summary);
  return result;
}

}  // namespace omninav::lattice
