#include "omninav/navigation/place_belief.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"

namespace omninav::navigation {

void BeliefParams::check() const {
  check_range("belief.view_scale", view_scale, 0.01, 100.0);
  check_range("belief.direction_sigma_deg", direction_sigma_deg, 1.0, 180.0);
  check_range("belief.uniform_share", uniform_share, 0.0, 0.5);
  check_range("belief.confident_share", confident_share, 0.0, 1.0);
}

void load_belief_params(const ConfigReader& section, BeliefParams& params) {
  section.read("view_scale", params.view_scale);
  section.read("direction_sigma_deg", params.direction_sigma_deg);
  section.read("uniform_share", params.uniform_share);
  section.read("confident_share", params.confident_share);
  check_loaded(section.source_name(), [&] { params.check(); });
}

PlaceBelief::PlaceBelief(std::size_t place_count, std::vector<MeasuredLink> links,
                         double view_scale_per_value, const BeliefParams& params)
    : links_(std::move(links)),
      links_of_(place_count),
      view_scale_(view_scale_per_value),
      params_(params),
      probability_(place_count, place_count > 0 ? 1.0 / static_cast<double>(place_count) : 0.0) {
  params_.check();
  if (place_count == 0) throw UsageError("a belief over no places");
  if (!(view_scale_ > 0.0) || !std::isfinite(view_scale_)) {
    throw UsageError("a belief's view scale must be finite and positive");
  }
  for (const MeasuredLink& link : links_) {
    const auto [a, b] = link.places;
    if (a < 0 || b < 0 || static_cast<std::size_t>(std::max(a, b)) >= place_count) {
      throw UsageError("a link names a place beyond the map's " + std::to_string(place_count));
    }
  }
  index_links();
}

void PlaceBelief::index_links() {
  for (std::vector<std::size_t>& own : links_of_) own.clear();
  for (std::size_t l = 0; l < links_.size(); ++l) {
    links_of_[links_[l].places.first].push_back(l);
    links_of_[links_[l].places.second].push_back(l);
  }
}

void PlaceBelief::predict(std::span<const double> motion_in_place_rad, double distance_m) {
  const std::size_t count = probability_.size();
  if (motion_in_place_rad.size() != count) {
    throw UsageError("predict: a motion for " + std::to_string(motion_in_place_rad.size()) +
                     " places, the belief has " + std::to_string(count));
  }
  const double sigma = deg_to_rad(params_.direction_sigma_deg);
  std::vector<double> next(count, 0.0);
  for (std::size_t p = 0; p < count; ++p) {
    const double mass = probability_[p];
    if (mass <= 0.0) continue;
    const double motion = motion_in_place_rad[p];
    if (!std::isfinite(motion) || distance_m <= 0.0) {
      next[p] += mass;
      continue;
    }
    // Each link's share: how well its direction agrees with the motion, times how much of it
    // the distance driven covers.
    double moved = 0.0;
    std::vector<std::pair<int, double>> shares;
    for (const std::size_t l : links_of_[p]) {
      const MeasuredLink& link = links_[l];
      const bool first = link.places.first == static_cast<int>(p);
      const double direction = first ? link.direction_at_first_rad : link.direction_at_second_rad;
      const double off = signed_difference(motion, direction);
      const double share = std::min(1.0, distance_m / std::max(link.length_m, 1e-9)) *
                           std::exp(-0.5 * off * off / (sigma * sigma));
      shares.emplace_back(first ? link.places.second : link.places.first, share);
      moved += share;
    }
    const double scale = moved > 1.0 ? 1.0 / moved : 1.0;
    for (const auto& [to, share] : shares) next[to] += mass * share * scale;
    next[p] += mass * (1.0 - moved * scale);
  }
  const double uniform = params_.uniform_share / static_cast<double>(count);
  for (double& p : next) p = (1.0 - params_.uniform_share) * p + uniform;
  probability_ = std::move(next);
}

void PlaceBelief::update(std::span<const double> dissimilarity_per_value) {
  const std::size_t count = probability_.size();
  if (dissimilarity_per_value.size() != count) {
    throw UsageError("update: dissimilarities to " +
                     std::to_string(dissimilarity_per_value.size()) + " places, the belief has " +
                     std::to_string(count));
  }
  const double least =
      *std::min_element(dissimilarity_per_value.begin(), dissimilarity_per_value.end());
  double total = 0.0;
  for (std::size_t p = 0; p < count; ++p) {
    probability_[p] *= std::exp(-(dissimilarity_per_value[p] - least) / view_scale_);
    total += probability_[p];
  }
  // A view unlike every place the belief holds (total underflows): start again from the view.
  if (!(total > 1e-300)) {
    total = 0.0;
    for (std::size_t p = 0; p < count; ++p) {
      probability_[p] = std::exp(-(dissimilarity_per_value[p] - least) / view_scale_);
      total += probability_[p];
    }
  }
  for (double& p : probability_) p /= total;
}

int PlaceBelief::most_likely() const {
  return static_cast<int>(std::max_element(probability_.begin(), probability_.end()) -
                          probability_.begin());
}

double PlaceBelief::neighbourhood_probability(int place) const {
  double total = probability_[place];
  for (const std::size_t l : links_of_[place]) {
    const auto [a, b] = links_[l].places;
    total += probability_[a == place ? b : a];
  }
  return total;
}

void PlaceBelief::remove_link(int a, int b) {
  for (std::vector<std::size_t>& own : links_of_) {
    std::erase_if(own, [&](std::size_t l) {
      const auto [x, y] = links_[l].places;
      return (x == a && y == b) || (x == b && y == a);
    });
  }
}

void PlaceBelief::restore_links() {
  index_links();
}

}  // namespace omninav::navigation
