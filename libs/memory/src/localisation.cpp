#include "omninav/memory/localisation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::memory {

void load_localisation_params(const ConfigReader& section, LocalisationParams& params) {
  signature::load_hierarchy_params(section, params.hierarchy);
  section.read("top_k", params.top_k, 1, 100000);
}

std::string to_string(PositionFrame frame) {
  return frame == PositionFrame::kLattice ? "lattice" : "truth";
}

std::optional<std::pair<PositionFrame, std::vector<Eigen::Vector2d>>> place_positions(
    const VisualMemory& memory) {
  std::vector<Eigen::Vector2d> points;
  if (memory.all_have_lattice()) {
    for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
      points.push_back(*memory.place(i).lattice_position);
    }
    return std::make_pair(PositionFrame::kLattice, points);
  }
  if (memory.all_have_truth()) {
    for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
      points.push_back(memory.place(i).truth->floor_position());
    }
    return std::make_pair(PositionFrame::kTruth, points);
  }
  return std::nullopt;
}

double typical_spacing(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) return 1.0;
  std::vector<double> nearest;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (i != j) best = std::min(best, (points[i] - points[j]).norm());
    }
    nearest.push_back(best);
  }
  const double spacing = median(std::move(nearest));
  return spacing > 0.0 ? spacing : 1.0;
}

Localiser::Localiser(const VisualMemory& memory, LocalisationParams params)
    : memory_(memory),
      params_(std::move(params)),
      index_(memory.parameters().panorama_rows > 0 ? memory.parameters().panorama_rows : 1,
             memory.parameters().signature.colour == signature::ColourMode::kLuminance ? 1 : 3,
             params_.hierarchy.levels, memory.parameters().weights) {
  if (params_.hierarchy.levels.back() > memory.parameters().signature.components) {
    throw UsageError("the finest level compares " +
                     std::to_string(params_.hierarchy.levels.back()) +
                     " components but the map's signatures hold " +
                     std::to_string(memory.parameters().signature.components));
  }
  index_.reserve(memory.place_count());
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) index_.add(memory.place(i).signature);
  positions_ = place_positions(memory);
}

Localisation Localiser::localise(const signature::Signature& query) const {
  return finish(
      query, index_.search(query, params_.hierarchy.candidate_similarity,
                           static_cast<std::size_t>(params_.top_k), params_.hierarchy.max_probes));
}

Localisation Localiser::localise_exhaustive(const signature::Signature& query) const {
  return finish(query, index_.search_exhaustive(query, params_.hierarchy.candidate_similarity,
                                                static_cast<std::size_t>(params_.top_k)));
}

Localisation Localiser::finish(const signature::Signature& query,
                               signature::SearchResult search) const {
  Localisation result;
  for (const signature::Candidate& c : search.best) {
    PlaceMatch match;
    match.place = c.place;
    match.dissimilarity = c.dissimilarity;
    match.similarity = c.similarity;
    const Place& place = memory_.place(c.place);
    match.dissimilarity_per_value =
        c.dissimilarity /
        (static_cast<double>(place.signature.lines()) * params_.hierarchy.levels.back());
    // The place's signature is `from`, the query `to`: turn = heading(query) − heading(place).
    const signature::PhaseHeading heading = signature::relative_heading(
        place.signature, query, std::min(place.signature.components, query.components));
    match.relative_heading_rad = heading.turn_rad;
    match.heading_confidence = heading.confidence;
    if (place.heading_rad) match.heading_rad = wrap_angle(*place.heading_rad + heading.turn_rad);
    result.best.push_back(match);
  }
  if (positions_ && !result.best.empty()) {
    const auto& [frame, points] = *positions_;
    PositionEstimate estimate;
    estimate.frame = frame;
    estimate.position = points[result.best.front().place];
    const double threshold = params_.hierarchy.candidate_similarity;
    double weight_sum = 0.0;
    Eigen::Vector2d sum(0.0, 0.0);
    for (const PlaceMatch& match : result.best) {
      const double weight = std::max(0.0, match.similarity - threshold);
      sum += weight * points[match.place];
      weight_sum += weight;
    }
    estimate.interpolated_position = estimate.position;
    if (weight_sum > 0.0) estimate.interpolated_position = sum / weight_sum;
    result.position = estimate;
  }
  result.search = std::move(search);
  return result;
}

}  // namespace omninav::memory
