// Links between places a driven map's organised lattice puts side by side (confirmed_links.hpp).

#include <cmath>
#include <complex>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "driven_lattice.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/lattice/confirmed_links.hpp"

namespace omninav::lattice {

namespace {

// A travelled link shorter than this share of the lattice's spacing in the lattice is a turn
// on the spot: its direction there is noise.
constexpr double kLeastStepShare = 0.1;

// Each place's turn from its stored heading into the lattice's frame: over its travelled links
// that moved, the circular mean of the link's direction in the lattice less its stored
// direction at the place. None for a place whose every step was on the spot.
std::vector<std::optional<double>> lattice_frame_turns(
    const std::vector<Eigen::Vector2d>& positions, const std::vector<MeasuredLink>& travelled,
    double least_step) {
  std::vector<std::complex<double>> sums(positions.size(), 0.0);
  for (const MeasuredLink& link : travelled) {
    const auto [a, b] = link.places;
    const Eigen::Vector2d step = positions[b] - positions[a];
    if (step.norm() < least_step) continue;
    const double along = std::atan2(step.y(), step.x());
    sums[a] += std::polar(1.0, along - link.direction_at_first_rad);
    sums[b] += std::polar(1.0, along + kPi - link.direction_at_second_rad);
  }
  std::vector<std::optional<double>> turns(positions.size());
  for (std::size_t place = 0; place < positions.size(); ++place) {
    if (std::abs(sums[place]) > 0.0) turns[place] = std::arg(sums[place]);
  }
  return turns;
}

}  // namespace

std::vector<MeasuredLink> lattice_neighbour_links(const memory::VisualMemory& memory,
                                                  const std::vector<Eigen::Vector2d>& positions,
                                                  const std::vector<MeasuredLink>& links,
                                                  const LinkParams& params) {
  params.check();
  if (positions.size() != memory.place_count()) {
    throw UsageError("lattice neighbours: " + std::to_string(positions.size()) +
                     " positions for a map of " + std::to_string(memory.place_count()) + " places");
  }
  if (!detail::driven_with_odometry(memory)) return {};
  std::vector<MeasuredLink> travelled;
  std::set<std::pair<int, int>> linked;
  for (const MeasuredLink& link : links) {
    if (link.kind == LinkKind::kTravelled) travelled.push_back(link);
    linked.insert(std::minmax(link.places.first, link.places.second));
  }
  std::vector<double> lattice_lengths, metres;
  for (const MeasuredLink& link : travelled) {
    const double length = (positions[link.places.second] - positions[link.places.first]).norm();
    if (length > 0.0) {
      lattice_lengths.push_back(length);
      metres.push_back(link.length_m);
    }
  }
  const std::optional<double> typical = median_dissimilarity_per_value(memory, travelled);
  if (lattice_lengths.empty() || !typical) return {};
  const double spacing = median(std::move(lattice_lengths));
  const double metres_per_unit = median(std::move(metres)) / spacing;
  const double radius = params.neighbour_spacings * spacing;
  const double agreement_limit = params.grid_agreement_ratio * *typical;
  const std::vector<std::optional<double>> turns =
      lattice_frame_turns(positions, travelled, kLeastStepShare * spacing);

  // Places by cells of the radius: a place's neighbours lie in its cell and the eight around
  // it, so the search grows with the places, not with their pairs.
  std::map<std::pair<long, long>, std::vector<int>> cells;
  const auto cell_of = [radius](const Eigen::Vector2d& p) {
    return std::pair<long, long>{std::lround(std::floor(p.x() / radius)),
                                 std::lround(std::floor(p.y() / radius))};
  };
  for (std::size_t place = 0; place < positions.size(); ++place) {
    if (turns[place]) cells[cell_of(positions[place])].push_back(static_cast<int>(place));
  }
  std::vector<MeasuredLink> neighbours;
  for (const auto& [cell, members] : cells) {
    for (long dx = -1; dx <= 1; ++dx) {
      for (long dy = -1; dy <= 1; ++dy) {
        const auto found = cells.find({cell.first + dx, cell.second + dy});
        if (found == cells.end()) continue;
        for (const int a : members) {
          for (const int b : found->second) {
            if (b <= a || linked.count({a, b})) continue;
            const Eigen::Vector2d step = positions[b] - positions[a];
            const double distance = step.norm();
            if (distance > radius || distance <= 0.0) continue;
            if (!(dissimilarity_per_value(memory, a, b) <= agreement_limit)) continue;
            const double along = std::atan2(step.y(), step.x());
            MeasuredLink link;
            link.places = {a, b};
            link.kind = LinkKind::kNeighbour;
            link.length_m = distance * metres_per_unit;
            link.direction_at_first_rad = wrap_angle(along - *turns[a]);
            link.direction_at_second_rad = wrap_angle(along + kPi - *turns[b]);
            neighbours.push_back(link);
          }
        }
      }
    }
  }
  log_info("and " + std::to_string(neighbours.size()) +
           " between neighbours in the organised lattice");
  return neighbours;
}

}  // namespace omninav::lattice
