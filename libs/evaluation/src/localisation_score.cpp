#include "omninav/evaluation/localisation_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/statistics.hpp"

namespace omninav::evaluation {

LocalisationScore::LocalisationScore(const memory::VisualMemory& memory) {
  if (!memory.all_have_truth()) {
    throw UsageError("scoring a localisation needs ground truth for every place of the map");
  }
  for (memory::PlaceIndex i = 0; i < memory.place_count(); ++i) {
    places_.push_back(memory.place(i).truth->floor_position());
  }
  spacing_m_ = memory::typical_spacing(places_);
}

LocalisationScore::Query LocalisationScore::add(const memory::Localisation& result,
                                                const CameraPose& truth) {
  Query q;
  const Eigen::Vector2d at = truth.floor_position();
  q.nearest_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < places_.size(); ++i) {
    const double d = (places_[i] - at).norm();
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
    q.error_m = (places_[result.best.front().place] - at).norm();
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
  text << "localised " << queries_ << (queries_ == 1 ? " query" : " queries") << ": "
       << fixed(100.0 * within_spacing_share(), 1) << "% within one grid spacing ("
       << fixed(spacing_m_, 2) << " m) of the truth, " << fixed(100.0 * nearest_share(), 1)
       << "% at the nearest place, mean error " << fixed(mean_error_m(), 3) << " m";
  if (const auto heading = median_heading_error_rad()) {
    text << ", median heading error " << fixed(rad_to_deg(*heading), 1) << " deg";
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
         << "nearest place in " << fixed(100.0 * contains[l], 1) << "% of queries, "
         << fixed(sizes[l], 1) << " places on average (of " << places_.size() << ")\n";
  }
  return text.str();
}

}  // namespace omninav::evaluation
