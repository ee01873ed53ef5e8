#include "omninav/lattice/confirmed_links.hpp"

#include <algorithm>
#include <boost/pending/disjoint_sets.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "image_agreement.hpp"
#include "odometry_spread.hpp"
#include "odometry_step.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "two_way_fit.hpp"

namespace omninav::lattice {

void LinkParams::check() const {
  check_range("links.grid_agreement_ratio", grid_agreement_ratio, 1.0, 100.0);
  check_range("links.grid_direction_deg", grid_direction_deg, 0.0, 180.0);
  check_range("links.revisit_run", revisit_run, 3, 101);
  check_range("links.revisit_ratio", revisit_ratio, 0.1, 100.0);
  check_range("links.revisit_image_ratio", revisit_image_ratio, 0.1, 100.0);
  check_range("links.revisit_disagreement_deg", revisit_disagreement_deg, 0.0, 180.0);
  check_range("links.revisits_per_place", revisits_per_place, 0, 100);
  check_range("links.revisit_candidates", revisit_candidates, 1, 1000);
  check_range("links.odometry_noise", odometry_noise, 0.0, 10.0);
  check_range("links.neighbour_spacings", neighbour_spacings, 0.5, 3.0);
}

void load_link_params(const ConfigReader& section, LinkParams& params) {
  section.read("grid_agreement_ratio", params.grid_agreement_ratio);
  section.read("grid_direction_deg", params.grid_direction_deg);
  section.read("revisit_run", params.revisit_run);
  section.read("revisit_ratio", params.revisit_ratio);
  section.read("revisit_image_ratio", params.revisit_image_ratio);
  section.read("revisit_disagreement_deg", params.revisit_disagreement_deg);
  section.read("revisits_per_place", params.revisits_per_place);
  section.read("revisit_candidates", params.revisit_candidates);
  section.read("odometry_noise", params.odometry_noise);
  section.read("neighbour_spacings", params.neighbour_spacings);
  check_loaded(section.source_name(), [&] { params.check(); });
  if (params.revisit_run % 2 == 0) ++params.revisit_run;
}

std::string to_string(LinkKind kind) {
  switch (kind) {
    case LinkKind::kTravelled:
      return "travelled";
    case LinkKind::kGrid:
      return "grid";
    case LinkKind::kNeighbour:
      return "neighbour";
    case LinkKind::kRevisit:
      return "revisit";
  }
  return "?";
}

namespace {

using Pair = std::pair<int, int>;

// A step the odometry measures shorter than this is a turn on the spot: its direction is noise.
constexpr double kLeastOdometryStepM = 0.01;

Pair ordered(int a, int b) {
  return {std::min(a, b), std::max(a, b)};
}

// The link from a to b as the two places' odometry measures it (length, and the direction seen
// from each end's front: the place's heading is the robot's); false when either place has no
// odometry or the step is too short to have a direction.
bool measure_by_odometry(const memory::VisualMemory& memory, MeasuredLink& link) {
  const std::optional<OdometryStep> step =
      odometry_step(memory, link.places.first, link.places.second);
  if (!step || step->translation_m.norm() < kLeastOdometryStepM) return false;
  link.length_m = step->translation_m.norm();
  link.direction_at_first_rad = std::atan2(step->translation_m.y(), step->translation_m.x());
  // Seen from b: back along the step, in b's frame, which is turned by the step's turn.
  link.direction_at_second_rad = wrap_angle(link.direction_at_first_rad + kPi - step->turn_rad);
  return true;
}

// Consecutive places of a stream, the robot's own path: always links.
std::vector<MeasuredLink> travelled_links(const memory::VisualMemory& memory,
                                          const std::vector<double>& headings, double spacing_m) {
  std::vector<MeasuredLink> links;
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    if (edge.edge->kind != memory::EdgeKind::kSequence) continue;
    const int a = static_cast<int>(edge.from), b = static_cast<int>(edge.to);
    MeasuredLink link;
    link.places = {a, b};
    link.kind = LinkKind::kTravelled;
    link.length_m = spacing_m;
    if (measure_by_odometry(memory, link)) {
      // The odometry's step.
    } else if (const std::optional<TwoWayFit> fit =
                   fit_two_way(memory, a, b, signed_difference(headings[b], headings[a]))) {
      link.direction_at_first_rad = fit->direction_at_a_rad;
      link.direction_at_second_rad = fit->direction_at_b_rad;
    } else {
      // No displacement the phases can see: the robot drove forwards, as streams mostly do.
      const double turn = signed_difference(headings[b], headings[a]);
      link.direction_at_first_rad = 0.0;
      link.direction_at_second_rad = wrap_angle(kPi - turn);
    }
    links.push_back(link);
  }
  return links;
}

// Places of a grid database: the database's positions say which are neighbours.
std::vector<MeasuredLink> grid_links(const memory::VisualMemory& memory,
                                     const std::vector<double>& headings,
                                     const LinkParams& params) {
  const std::optional<double> spacing = memory.grid_spacing_m();
  if (!spacing) return {};
  std::map<Pair, std::vector<int>> cells;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    const memory::Place& place = memory.place(i);
    if (place.heading_source != memory::HeadingSource::kTruth || !place.truth) continue;
    // Rounded: a grid's points lie on whole multiples of its spacing, give or take a float.
    cells[{static_cast<int>(std::lround(place.truth->x_m / *spacing)),
           static_cast<int>(std::lround(place.truth->y_m / *spacing))}]
        .push_back(static_cast<int>(i));
  }
  const auto position = [&](int i) {
    const CameraPose& pose = *memory.place(i).truth;
    return Eigen::Vector2d(pose.x_m, pose.y_m);
  };
  struct Candidate {
    MeasuredLink link;
    double dissimilarity;
    bool agrees;  // the phases' fit agrees with the database's direction
  };
  const double direction_limit = deg_to_rad(params.grid_direction_deg);
  std::vector<Candidate> candidates;
  for (const auto& [cell, members] : cells) {
    for (int a : members) {
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const auto found = cells.find({cell.first + dx, cell.second + dy});
          if (found == cells.end()) continue;
          for (int b : found->second) {
            if (b <= a) continue;
            const Eigen::Vector2d step = position(b) - position(a);
            // The 8-neighbourhood of a square grid: up to a diagonal step.
            if (step.norm() > 1.5 * *spacing || step.norm() <= 0.0) continue;
            const double direction = std::atan2(step.y(), step.x());
            MeasuredLink link;
            link.places = {a, b};
            link.kind = LinkKind::kGrid;
            link.length_m = step.norm();
            link.direction_at_first_rad = signed_difference(direction, headings[a]);
            link.direction_at_second_rad =
                signed_difference(wrap_angle(direction + kPi), headings[b]);
            // The phases must see the step the database states: across a wall or round
            // furniture the two views are not one scene moved, and the fit points elsewhere.
            const std::optional<TwoWayFit> fit =
                fit_two_way(memory, a, b, signed_difference(headings[b], headings[a]));
            const bool agrees =
                fit &&
                std::abs(signed_difference(fit->direction_at_a_rad, link.direction_at_first_rad)) <=
                    direction_limit &&
                std::abs(signed_difference(fit->direction_at_b_rad,
                                           link.direction_at_second_rad)) <= direction_limit;
            candidates.push_back({link, dissimilarity_per_value(memory, a, b), agrees});
          }
        }
      }
    }
  }
  if (candidates.empty()) return {};
  std::vector<double> dissimilarities;
  for (const Candidate& candidate : candidates) dissimilarities.push_back(candidate.dissimilarity);
  const double limit = params.grid_agreement_ratio * median(dissimilarities);
  // The grid's pieces: a neighbour pair that fails the checks still joins, most alike first,
  // places the others leave apart (a grid round furniture hangs together by a few pairs).
  const std::size_t count = memory.place_count();
  std::vector<std::size_t> rank(count, 0), parent(count, 0);
  boost::disjoint_sets<std::size_t*, std::size_t*> pieces(rank.data(), parent.data());
  for (std::size_t place = 0; place < count; ++place) pieces.make_set(place);
  std::vector<MeasuredLink> links;
  std::vector<const Candidate*> failed;
  for (const Candidate& candidate : candidates) {
    if (candidate.agrees && candidate.dissimilarity <= limit) {
      links.push_back(candidate.link);
      pieces.union_set(candidate.link.places.first, candidate.link.places.second);
    } else {
      failed.push_back(&candidate);
    }
  }
  std::sort(failed.begin(), failed.end(), [](const Candidate* x, const Candidate* y) {
    return std::tie(x->dissimilarity, x->link.places) < std::tie(y->dissimilarity, y->link.places);
  });
  for (const Candidate* candidate : failed) {
    const auto [a, b] = candidate->link.places;
    if (pieces.find_set(a) == pieces.find_set(b)) continue;
    links.push_back(candidate->link);
    pieces.union_set(a, b);
  }
  // Pieces no neighbours join (a gap of grid points left out in furniture): the nearest pair
  // of places between them, by the database's positions, joins them; the robot finds its way
  // round what lies between (navigator.hpp, recovery).
  std::vector<int> gridded;
  for (const auto& [cell, members] : cells)
    gridded.insert(gridded.end(), members.begin(), members.end());
  std::vector<std::tuple<double, int, int>> gaps;
  for (std::size_t i = 0; i < gridded.size(); ++i) {
    for (std::size_t j = i + 1; j < gridded.size(); ++j) {
      if (pieces.find_set(gridded[i]) == pieces.find_set(gridded[j])) continue;
      gaps.emplace_back((position(gridded[j]) - position(gridded[i])).norm(), gridded[i],
                        gridded[j]);
    }
  }
  std::sort(gaps.begin(), gaps.end());
  for (const auto& [distance, a, b] : gaps) {
    if (pieces.find_set(a) == pieces.find_set(b)) continue;
    const Eigen::Vector2d step = position(b) - position(a);
    const double direction = std::atan2(step.y(), step.x());
    links.push_back({{a, b},
                     distance,
                     signed_difference(direction, headings[a]),
                     signed_difference(wrap_angle(direction + kPi), headings[b]),
                     LinkKind::kGrid});
    pieces.union_set(a, b);
  }
  return links;
}

// The streams of the map: each a chain of places joined by travelled links, in order.
std::vector<std::vector<int>> streams(const memory::VisualMemory& memory) {
  const std::size_t count = memory.place_count();
  std::vector<int> next(count, -1), previous(count, -1);
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    if (edge.edge->kind != memory::EdgeKind::kSequence) continue;
    next[edge.from] = static_cast<int>(edge.to);
    previous[edge.to] = static_cast<int>(edge.from);
  }
  std::vector<std::vector<int>> chains;
  for (std::size_t i = 0; i < count; ++i) {
    if (previous[i] >= 0 || next[i] < 0) continue;
    std::vector<int> chain;
    for (int place = static_cast<int>(i); place >= 0; place = next[place]) chain.push_back(place);
    chains.push_back(std::move(chain));
  }
  return chains;
}

// Sequence matching over the streams: for each place with a full run of views round it, the
// places whose runs (forwards or backwards) match it best, among the runs at its most similar
// places and downhill from them along their streams.
std::vector<MeasuredLink> revisit_links(
    const memory::VisualMemory& memory, const std::vector<double>& headings,
    const std::vector<MeasuredLink>& travelled, double spacing_m, const LinkParams& params,
    const PlaceDissimilarities& dissimilarity,
    const std::vector<std::vector<SimilarPlace>>& most_similar) {
  if (params.revisits_per_place <= 0 || travelled.empty()) return {};
  const std::vector<std::vector<int>> chains = streams(memory);
  // Every place of a stream with its stream and position there.
  struct At {
    int chain;
    int position;
  };
  std::vector<int> members;
  std::vector<At> at;
  std::vector<int> member_of(memory.place_count(), -1);
  for (std::size_t c = 0; c < chains.size(); ++c) {
    for (std::size_t k = 0; k < chains[c].size(); ++k) {
      member_of[chains[c][k]] = static_cast<int>(members.size());
      members.push_back(chains[c][k]);
      at.push_back({static_cast<int>(c), static_cast<int>(k)});
    }
  }
  const std::size_t n = members.size();
  // Eq. 6 per value between the places at two indices of `members`, from one source for the
  // runs and for the travelled links they are measured against.
  const double values = static_cast<double>(memory.place(0).signature.size());
  const auto d = [&](std::size_t i, std::size_t j) {
    return dissimilarity(members[i], members[j]) / values;
  };
  std::vector<double> travelled_values;
  for (const MeasuredLink& link : travelled) {
    travelled_values.push_back(dissimilarity(link.places.first, link.places.second) / values);
  }
  const double limit = params.revisit_ratio * median(std::move(travelled_values));
  const int half = params.revisit_run / 2;
  const auto full_run = [&](const At& where) {
    return where.position - half >= 0 &&
           where.position + half < static_cast<int>(chains[where.chain].size());
  };
  // The mean over the run of d between i's views and j's, j's stretch forwards (+1) or back (−1).
  const auto run_score = [&](std::size_t i, std::size_t j, int direction) {
    double sum = 0.0;
    for (int t = -half; t <= half; ++t) sum += d(i + t, j + direction * t);
    return sum / static_cast<double>(params.revisit_run);
  };
  // With odometry, two places of one stream can only be neighbours when the odometry puts them
  // within a spacing and a half, give or take three standard deviations of its drift over the
  // way between them (a Gaussian's 99.7 %).
  const OdometrySpread spread(memory, chains, params.odometry_noise, spacing_m);
  const auto odometry_allows = [&](std::size_t i, std::size_t j) {
    const std::optional<CameraPose>& a = memory.place(members[i]).odometry;
    const std::optional<CameraPose>& b = memory.place(members[j]).odometry;
    if (!a || !b || at[i].chain != at[j].chain) return true;
    return std::hypot(a->x_m - b->x_m, a->y_m - b->y_m) <=
           1.5 * spacing_m + 3.0 * spread.stddev_m(at[i].chain, at[i].position, at[j].position);
  };
  std::set<Pair> seen;
  for (const MeasuredLink& link : travelled)
    seen.insert(ordered(link.places.first, link.places.second));
  const double disagreement_limit = deg_to_rad(params.revisit_disagreement_deg);
  ImageAgreement images(memory, travelled);
  std::vector<MeasuredLink> links;
  for (std::size_t i = 0; i < n; ++i) {
    if (!full_run(at[i])) continue;
    // The run's score against another place with a full run, not within the same stretch
    // (infinite where there is none), computed once per place compared.
    std::map<std::size_t, double> scores;
    const auto score = [&](std::size_t j) {
      const auto [known, added] = scores.try_emplace(j, std::numeric_limits<double>::infinity());
      if (!added) return known->second;
      const bool compared =
          full_run(at[j]) &&
          !(at[j].chain == at[i].chain && std::abs(at[j].position - at[i].position) <= 2 * half) &&
          odometry_allows(i, j);
      if (compared) known->second = std::min(run_score(i, j, 1), run_score(i, j, -1));
      return known->second;
    };
    const auto same_stream = [&](std::size_t j, std::size_t k) {
      return k < n && at[k].chain == at[j].chain;
    };
    // From each of the place's most similar places, downhill along that stream to a local
    // minimum of the runs' scores; those within the limit, best first.
    std::set<std::pair<double, std::size_t>> found;
    for (const SimilarPlace& similar :
         most_similar_first(most_similar[members[i]], params.revisit_candidates)) {
      if (member_of[similar.place] < 0) continue;
      std::size_t j = static_cast<std::size_t>(member_of[similar.place]);
      for (double here = score(j); std::isfinite(here);) {
        const double before = same_stream(j, j - 1) ? score(j - 1) : here;
        const double after = same_stream(j, j + 1) ? score(j + 1) : here;
        if (before >= here && after >= here) break;
        j = before < after ? j - 1 : j + 1;
        here = std::min(before, after);
      }
      if (score(j) <= limit) found.insert({score(j), j});
    }
    int kept = 0;
    for (const auto& [run, j] : found) {
      if (kept >= params.revisits_per_place) break;
      const int a = members[i], b = members[j];
      if (!seen.insert(ordered(a, b)).second) continue;
      // The images confirm a revisit where the map keeps them (checked first: a look-alike
      // costs no motion fit); the two fits' agreement only where it does not: places a few
      // centimetres apart have no direction between them to agree on, and look-alikes' fits can
      // agree (docs/evaluation.md).
      const std::optional<double> image = images.ratio(a, b);
      if (image && *image > params.revisit_image_ratio) continue;
      const std::optional<TwoWayFit> fit =
          fit_two_way(memory, a, b, signed_difference(headings[b], headings[a]));
      if (!fit || (!image && fit->disagreement_rad > disagreement_limit)) continue;
      MeasuredLink link;
      link.places = {a, b};
      link.kind = LinkKind::kRevisit;
      link.length_m = spacing_m;
      link.direction_at_first_rad = fit->direction_at_a_rad;
      link.direction_at_second_rad = fit->direction_at_b_rad;
      link.parallax_rad = fit->parallax_rad;
      link.fit_residual = fit->residual;
      links.push_back(link);
      ++kept;
    }
  }
  return links;
}

}  // namespace

double dissimilarity_per_value(const memory::VisualMemory& memory, int a, int b) {
  const signature::Signature& first = memory.place(a).signature;
  return signature::dissimilarity(first, memory.place(b).signature, -1,
                                  memory.parameters().weights) /
         static_cast<double>(first.size());
}

std::optional<double> median_dissimilarity_per_value(const memory::VisualMemory& memory,
                                                     const std::vector<MeasuredLink>& links) {
  if (links.empty()) return std::nullopt;
  std::vector<double> values;
  for (const MeasuredLink& link : links) {
    values.push_back(dissimilarity_per_value(memory, link.places.first, link.places.second));
  }
  return median(std::move(values));
}

std::vector<MeasuredLink> confirmed_links(
    const memory::VisualMemory& memory, const std::vector<double>& headings, double spacing_m,
    const LinkParams& params, const PlaceDissimilarities& dissimilarity,
    const std::vector<std::vector<SimilarPlace>>& most_similar) {
  params.check();
  std::vector<MeasuredLink> links = travelled_links(memory, headings, spacing_m);
  const std::size_t travelled = links.size();
  std::vector<MeasuredLink> revisits =
      revisit_links(memory, headings, links, spacing_m, params, dissimilarity, most_similar);
  std::vector<MeasuredLink> grid = grid_links(memory, headings, params);
  log_info("the plan runs over " + std::to_string(travelled + revisits.size() + grid.size()) +
           " confirmed links: " + std::to_string(travelled) + " travelled, " +
           std::to_string(revisits.size()) + " revisits, " + std::to_string(grid.size()) +
           " between grid neighbours");
  links.insert(links.end(), revisits.begin(), revisits.end());
  links.insert(links.end(), grid.begin(), grid.end());
  return links;
}

std::vector<MeasuredLink> confirmed_links(const memory::VisualMemory& memory,
                                          const std::vector<double>& headings, double spacing_m,
                                          const LinkParams& params) {
  params.check();
  const PlaceDissimilarities dissimilarity(memory);
  return confirmed_links(memory, headings, spacing_m, params, dissimilarity,
                         dissimilarity.most_similar_indexed(params.revisit_candidates));
}

}  // namespace omninav::lattice
