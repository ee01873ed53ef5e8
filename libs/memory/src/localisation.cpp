#include "omninav/memory/localisation.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

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

std::optional<std::pair<PositionFrame, std::vector<cv::Point2d>>> place_positions(
    const VisualMemory& memory) {
  std::vector<cv::Point2d> points;
  if (memory.all_have_lattice()) {
    for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
      points.emplace_back(memory.place(i).lattice->x, memory.place(i).lattice->y);
    }
    return std::make_pair(PositionFrame::kLattice, points);
  }
  if (memory.all_have_truth()) {
    for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
      points.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
    }
    return std::make_pair(PositionFrame::kTruth, points);
  }
  return std::nullopt;
}

double typical_spacing(const std::vector<cv::Point2d>& points) {
  if (points.size() < 2) return 1.0;
  std::vector<double> nearest;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (i != j) best = std::min(best, cv::norm(points[i] - points[j]));
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
    const cv::Point2d& best = points[result.best.front().place];
    estimate.x = best.x;
    estimate.y = best.y;
    const double threshold = params_.hierarchy.candidate_similarity;
    double weight_sum = 0.0;
    cv::Point2d sum(0.0, 0.0);
    for (const PlaceMatch& match : result.best) {
      const double weight = std::max(0.0, match.similarity - threshold);
      sum += weight * points[match.place];
      weight_sum += weight;
    }
    if (weight_sum > 0.0) {
      estimate.interpolated_x = sum.x / weight_sum;
      estimate.interpolated_y = sum.y / weight_sum;
    } else {
      estimate.interpolated_x = best.x;
      estimate.interpolated_y = best.y;
    }
    result.position = estimate;
  }
  result.search = std::move(search);
  return result;
}

LocalisationScore::LocalisationScore(const VisualMemory& memory) {
  if (!memory.all_have_truth()) {
    throw UsageError("scoring a localisation needs ground truth for every place of the map");
  }
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
    places_.emplace_back(memory.place(i).truth->x_m, memory.place(i).truth->y_m);
  }
  spacing_m_ = typical_spacing(places_);
}

LocalisationScore::Query LocalisationScore::add(const Localisation& result,
                                                const CameraPose& truth) {
  Query q;
  const cv::Point2d at(truth.x_m, truth.y_m);
  q.nearest_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < places_.size(); ++i) {
    const double d = cv::norm(places_[i] - at);
    if (d < q.nearest_m) {
      q.nearest_m = d;
      q.nearest_place = i;
    }
  }
  if (q.nearest_m > spacing_m_ * std::sqrt(0.5) * (1.0 + 1e-6)) {
    q.outside = true;
    ++outside_;
  }
  if (contains_.size() < result.search.levels.size()) {
    contains_.resize(result.search.levels.size(), 0);
    size_sum_.resize(result.search.levels.size(), 0.0);
  }
  for (std::size_t l = 0; l < result.search.levels.size(); ++l) {
    const auto& candidates = result.search.levels[l].candidates;
    const bool contains =
        std::any_of(candidates.begin(), candidates.end(),
                    [&](const signature::Candidate& c) { return c.place == q.nearest_place; });
    q.level_contains_nearest.push_back(contains);
    if (!q.outside) {
      contains_[l] += contains;
      size_sum_[l] += static_cast<double>(candidates.size());
    }
  }
  if (!result.best.empty()) {
    // A small tolerance: a query exactly one spacing from its best place counts as within.
    q.error_m = cv::norm(places_[result.best.front().place] - at);
    q.within_spacing = q.error_m <= spacing_m_ * (1.0 + 1e-6);
    if (result.best.front().heading_rad) {
      q.heading_error_rad = signed_difference(*result.best.front().heading_rad, truth.heading_rad);
      if (!q.outside) heading_errors_.push_back(std::fabs(*q.heading_error_rad));
    }
  }
  if (!q.outside) {
    ++queries_;
    within_ += q.within_spacing;
    nearest_ += !result.best.empty() && result.best.front().place == q.nearest_place;
    error_sum_m_ += q.error_m;
  }
  return q;
}

double LocalisationScore::within_spacing_share() const {
  return queries_ == 0 ? 0.0 : static_cast<double>(within_) / static_cast<double>(queries_);
}

double LocalisationScore::nearest_share() const {
  return queries_ == 0 ? 0.0 : static_cast<double>(nearest_) / static_cast<double>(queries_);
}

double LocalisationScore::mean_error_m() const {
  return queries_ == 0 ? 0.0 : error_sum_m_ / static_cast<double>(queries_);
}

std::vector<double> LocalisationScore::level_contains_share() const {
  std::vector<double> out;
  for (std::size_t c : contains_) {
    out.push_back(queries_ == 0 ? 0.0 : static_cast<double>(c) / static_cast<double>(queries_));
  }
  return out;
}

std::vector<double> LocalisationScore::level_mean_size() const {
  std::vector<double> out;
  for (double s : size_sum_) out.push_back(queries_ == 0 ? 0.0 : s / static_cast<double>(queries_));
  return out;
}

std::optional<double> LocalisationScore::median_heading_error_rad() const {
  if (heading_errors_.empty()) return std::nullopt;
  return median(heading_errors_);
}

std::string LocalisationScore::summary(const std::vector<int>& levels) const {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(1);
  text << "localised " << queries_ << (queries_ == 1 ? " query" : " queries") << ": "
       << 100.0 * within_spacing_share() << "% within one grid spacing (" << std::setprecision(2)
       << spacing_m_ << " m) of the truth, " << std::setprecision(1) << 100.0 * nearest_share()
       << "% at the nearest place, mean error " << std::setprecision(3) << mean_error_m() << " m"
       << std::setprecision(1);
  if (const auto heading = median_heading_error_rad()) {
    text << ", median heading error " << rad_to_deg(*heading) << " deg";
  }
  if (outside_ > 0) {
    text << " (" << outside_ << " more off the grid, farther than half a cell diagonal from "
         << "every place, not scored)";
  }
  text << "\n";
  const std::vector<double> contains = level_contains_share();
  const std::vector<double> sizes = level_mean_size();
  for (std::size_t l = 0; l < contains.size(); ++l) {
    text << "  level m=" << (l < levels.size() ? levels[l] : 0) << ": candidate set holds the "
         << "nearest place in " << 100.0 * contains[l] << "% of queries, " << sizes[l]
         << " places on average (of " << places_.size() << ")\n";
  }
  return text.str();
}

}  // namespace omninav::memory
