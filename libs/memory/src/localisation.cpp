#include "omninav/memory/localisation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::memory {

void load_localisation_params(const ConfigReader& section, LocalisationParams& params) {
  signature::load_hierarchy_params(section, params.hierarchy);
  section.read("top_k", params.top_k);
  section.read("fine_candidates", params.fine_candidates);
  section.read("fine_rotational_weight", params.fine_rotational_weight);
  check_loaded(section.source_name(), [&] { params.check(); });
}

void LocalisationParams::check() const {
  hierarchy.check();
  check_range("localisation.top_k", top_k, 1, 100000);
  check_range("localisation.fine_candidates", fine_candidates, 0, 100000);
  check_range("localisation.fine_rotational_weight", fine_rotational_weight, 0.0, 1000.0);
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

namespace {

// The median distance from every `stride`-th point to its nearest other point (each against
// every point); 1 for fewer than two points or a median of 0.
double nearest_distance_median(const std::vector<Eigen::Vector2d>& points, std::size_t stride) {
  if (points.size() < 2) return 1.0;
  std::vector<double> nearest;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (i != j) best = std::min(best, (points[i] - points[j]).norm());
    }
    nearest.push_back(best);
  }
  const double spacing = median(std::move(nearest));
  return spacing > 0.0 ? spacing : 1.0;
}

// typical_spacing over at most 200 points spread over the listing, so that a map of 100,000
// places costs milliseconds, not minutes.
double sampled_spacing(const std::vector<Eigen::Vector2d>& points) {
  constexpr std::size_t kSampled = 200;
  return nearest_distance_median(points, std::max<std::size_t>(1, points.size() / kSampled));
}

}  // namespace

double typical_spacing(const std::vector<Eigen::Vector2d>& points) {
  return nearest_distance_median(points, 1);
}

namespace {

// The exponent of the weights between places, (least Dis / Dis)^p. Chosen across the zoo leaving
// one family out (docs/memory.md): over p = 1, 2, 3, 4, 6, 8, 12, every fold (field, house,
// office, room, Ofstad left out) picks 3 by the mean over the other rows of the median position
// error relative to the best place's.
constexpr double kBetweenPlacesPower = 3.0;

// The position between places: the mean of the positions of the best place and those of the
// matches within 1.5 spacings of it (its neighbours, diagonals included), weighted by
// (least Dis / Dis)^kBetweenPlacesPower over Eq. 6's dissimilarities. Places farther away are
// other candidates, not neighbours: averaging across a look-alike would put the estimate
// between the two, where neither is.
Eigen::Vector2d between_places(const std::vector<PlaceMatch>& best,
                               const std::vector<Eigen::Vector2d>& points, double spacing_m) {
  const Eigen::Vector2d at = points[best.front().place];
  const auto neighbour = [&](const PlaceMatch& match) {
    return (points[match.place] - at).norm() <= 1.5 * spacing_m;
  };
  double least = std::numeric_limits<double>::infinity();
  for (const PlaceMatch& match : best) {
    if (neighbour(match)) least = std::min(least, match.dissimilarity);
  }
  if (!(least > 0.0)) return at;  // an exact match
  Eigen::Vector2d sum(0.0, 0.0);
  double weight_sum = 0.0;
  for (const PlaceMatch& match : best) {
    if (!neighbour(match)) continue;
    const double weight = std::pow(least / match.dissimilarity, kBetweenPlacesPower);
    sum += weight * points[match.place];
    weight_sum += weight;
  }
  return sum / weight_sum;
}

// The fine level's order: each of the first fine_magnitude.size() matches scores
// `rotational_weight` times its rotational dissimilarity over the least among them plus its
// magnitude dissimilarity over the least among them, lowest first; the rest keep
// their order behind.
void rerank_fine(std::vector<PlaceMatch>& best, const std::vector<double>& fine_magnitude,
                 double rotational_weight) {
  const std::size_t fine = fine_magnitude.size();
  if (fine < 2) return;
  double least_rotational = std::numeric_limits<double>::infinity();
  double least_magnitude = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fine; ++i) {
    least_rotational = std::min(least_rotational, *best[i].rotational_dissimilarity);
    least_magnitude = std::min(least_magnitude, fine_magnitude[i]);
  }
  // An exact match (0) ranks first by either term; the floor only avoids dividing by 0.
  least_rotational = std::max(least_rotational, 1e-12);
  least_magnitude = std::max(least_magnitude, 1e-12);
  std::vector<std::size_t> order(fine);
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> score(fine);
  for (std::size_t i = 0; i < fine; ++i) {
    score[i] = rotational_weight * *best[i].rotational_dissimilarity / least_rotational +
               fine_magnitude[i] / least_magnitude;
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
  std::vector<PlaceMatch> sorted;
  sorted.reserve(best.size());
  for (std::size_t i : order) sorted.push_back(best[i]);
  for (std::size_t i = fine; i < best.size(); ++i) sorted.push_back(best[i]);
  best = std::move(sorted);
}

}  // namespace

Localiser::Localiser(const VisualMemory& memory, LocalisationParams params)
    : memory_(memory),
      params_(std::move(params)),
      index_(memory.parameters().panorama_rows > 0 ? memory.parameters().panorama_rows : 1,
             memory.parameters().signature.colour == signature::ColourMode::kLuminance ? 1 : 3,
             params_.hierarchy.levels, memory.parameters().weights),
      extractor_(memory.parameters().signature) {
  params_.check();
  if (params_.hierarchy.levels.back() > memory.parameters().signature.components) {
    throw UsageError("the finest level compares " +
                     std::to_string(params_.hierarchy.levels.back()) +
                     " components but the map's signatures hold " +
                     std::to_string(memory.parameters().signature.components));
  }
  index_.reserve(memory.place_count());
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) index_.add(memory.place(i).signature);
  positions_ = place_positions(memory);
  if (positions_) spacing_m_ = sampled_spacing(positions_->second);
}

std::size_t Localiser::searched_top() const {
  return static_cast<std::size_t>(std::max(params_.top_k, params_.fine_candidates));
}

Localisation Localiser::localise(const signature::Signature& query) const {
  return finish(query, index_.search(query, params_.hierarchy.candidate_similarity, searched_top(),
                                     params_.hierarchy.max_probes));
}

signature::Signature Localiser::signature_of(const cv::Mat& panorama, const std::string& what) {
  signature::Signature query = extractor_.compute(panorama, what);
  const int rows = memory_.parameters().panorama_rows;
  if (query.rows != rows) {
    throw InputError(what + ": a panorama of " + std::to_string(query.rows) +
                     " rows; the map's have " + std::to_string(rows));
  }
  return query;
}

Localisation Localiser::localise(const cv::Mat& panorama, const std::string& what) {
  return localise(signature_of(panorama, what));
}

Localisation Localiser::localise_exhaustive(const signature::Signature& query) const {
  return finish(query, index_.search_exhaustive(query, params_.hierarchy.candidate_similarity,
                                                searched_top()));
}

Localisation Localiser::finish(const signature::Signature& query,
                               signature::SearchResult search) const {
  Localisation result;
  const int m = params_.hierarchy.levels.back();
  const std::size_t fine =
      std::min(search.best.size(), static_cast<std::size_t>(params_.fine_candidates));
  std::vector<double> fine_magnitude;  // the finest level's Dis of the first `fine` places
  for (const signature::Candidate& c : search.best) {
    PlaceMatch match;
    match.place = c.place;
    match.similarity = c.similarity;
    const Place& place = memory_.place(c.place);
    match.dissimilarity = c.dissimilarity;  // Eq. 6 with the map's weights
    match.dissimilarity_per_value =
        c.dissimilarity / (static_cast<double>(place.signature.lines()) * m);
    // The place's signature is `from`, the query `to`: turn = heading(query) − heading(place).
    const signature::PhaseHeading heading = signature::relative_heading(
        place.signature, query, std::min(place.signature.components, query.components));
    match.relative_heading_rad = heading.turn_rad;
    match.heading_confidence = heading.confidence;
    if (place.heading_rad) match.heading_rad = wrap_angle(*place.heading_rad + heading.turn_rad);
    if (result.best.size() < fine) {
      match.rotational_dissimilarity = signature::rotational_dissimilarity(
          place.signature, query, heading.turn_rad, m, memory_.parameters().weights);
      fine_magnitude.push_back(c.dissimilarity);
    }
    result.best.push_back(match);
  }
  rerank_fine(result.best, fine_magnitude, params_.fine_rotational_weight);
  std::optional<Eigen::Vector2d> between;  // over every searched match, before the cut to top_k
  if (positions_ && !result.best.empty()) {
    between = between_places(result.best, positions_->second, spacing_m_);
  }
  if (result.best.size() > static_cast<std::size_t>(params_.top_k)) {
    result.best.resize(static_cast<std::size_t>(params_.top_k));
  }
  if (between) {
    const auto& [frame, points] = *positions_;
    PositionEstimate estimate;
    estimate.frame = frame;
    estimate.position = points[result.best.front().place];
    estimate.between_places = *between;
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
