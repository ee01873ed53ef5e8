#include "motions.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "omninav/core/angles.hpp"
#include "omninav/core/statistics.hpp"
#include "omninav/signature/motion.hpp"
#include "place_sets.hpp"

namespace omninav::lattice::detail {
namespace {

// A motion with how well its fit explained the two views.
struct Candidate {
  MotionMeasurement motion;
  double residual = 0.0;  // the worse of the two ways, MotionEstimate::residual
};

struct DirectionFit {
  double direction_rad = 0.0;  // in the lattice frame
  double residual = 0.0;       // the worse of the two ways, MotionEstimate::residual
};

// The direction from a to b in the lattice frame, fitted both ways (from a's view, and from
// b's view reversed) with the turn held at the headings' difference; nothing when either fit
// fails or a place has no heading.
std::optional<DirectionFit> fit_direction(const memory::VisualMemory& memory,
                                          const std::vector<std::optional<double>>& headings, int a,
                                          int b) {
  if (!headings[a] || !headings[b]) return std::nullopt;
  const double turn = signed_difference(*headings[b], *headings[a]);
  const signature::MotionEstimate forward =
      signature::estimate_motion(memory.place(a).signature, memory.place(b).signature, -1, turn);
  const signature::MotionEstimate backward =
      signature::estimate_motion(memory.place(b).signature, memory.place(a).signature, -1, -turn);
  if (!forward.valid || !backward.valid) return std::nullopt;
  const double there = wrap_angle(*headings[a] + forward.bearing_rad);
  const double back = wrap_angle(*headings[b] + backward.bearing_rad + kPi);
  return DirectionFit{wrap_angle(there + 0.5 * signed_difference(back, there)),
                      std::max(forward.residual, backward.residual)};
}

// From the motion's first place to its second, metres in the lattice frame.
Eigen::Vector2d displacement(const MotionMeasurement& motion) {
  return motion.length_m *
         Eigen::Vector2d(std::cos(motion.direction_rad), std::sin(motion.direction_rad));
}

// Along a stream, the steps between two places that are few steps apart tell where one lies
// from the other (dead reckoning, errors growing with the square root of the steps); a
// neighbour motion between such places that disagrees with them by more than 3 standard
// deviations is a look-alike's. Places not joined by unbroken steps, or too many steps apart,
// are not judged.
class StepCheck {
 public:
  StepCheck(const std::vector<Candidate>& candidates, int place_count, int max_steps,
            double step_stddev_m)
      : step_after_(place_count), max_steps_(max_steps), step_stddev_m_(step_stddev_m) {
    for (const Candidate& candidate : candidates) {
      const MotionMeasurement& motion = candidate.motion;
      if (!motion.step) continue;
      if (motion.to == motion.from + 1) step_after_[motion.from] = displacement(motion);
      if (motion.from == motion.to + 1) step_after_[motion.to] = -displacement(motion);
    }
  }

  bool contradicts(const MotionMeasurement& motion) const {
    const int first = std::min(motion.from, motion.to), last = std::max(motion.from, motion.to);
    if (motion.step || last - first > max_steps_) return false;
    Eigen::Vector2d along_steps = Eigen::Vector2d::Zero();
    for (int place = first; place < last; ++place) {
      if (!step_after_[place]) return false;
      along_steps += *step_after_[place];
    }
    const Eigen::Vector2d measured =
        motion.from == first ? displacement(motion) : Eigen::Vector2d(-displacement(motion));
    return (measured - along_steps).norm() >
           3.0 * step_stddev_m_ * std::sqrt(static_cast<double>(last - first));
  }

 private:
  std::vector<std::optional<Eigen::Vector2d>> step_after_;  // from place i to place i + 1
  int max_steps_;
  double step_stddev_m_;  // of one step's displacement
};

}  // namespace

MeasuredMotions measure_motions(const memory::VisualMemory& memory,
                                const PlaceDissimilarities& dissimilarity,
                                const std::vector<std::vector<SimilarPlace>>& ranking,
                                const DistanceCalibration& calibration,
                                const OrganiseParams& params) {
  const std::vector<std::optional<double>> headings = lattice_headings(memory);
  const double direction_stddev = deg_to_rad(params.motion_direction_stddev_deg);
  std::set<std::pair<int, int>> tried;
  // Fits the motion from a to b unless the pair was tried before.
  const auto measure = [&](int a, int b, double length_m, double length_stddev,
                           bool step) -> std::optional<Candidate> {
    if (!tried.insert({std::min(a, b), std::max(a, b)}).second) return std::nullopt;
    const auto fit = fit_direction(memory, headings, a, b);
    if (!fit) return std::nullopt;
    return Candidate{
        {a, b, fit->direction_rad, length_m, direction_stddev, length_stddev * length_m, step},
        fit->residual};
  };
  const auto neighbour = [&](int a, int b, double pair_dissimilarity) {
    return measure(a, b, calibration.distance_m(a, b, pair_dissimilarity),
                   params.neighbour_motion_length_stddev, false);
  };

  std::vector<Candidate> candidates;
  for (const memory::VisualMemory::EdgeRef& edge : memory.edges()) {
    const int a = static_cast<int>(edge.from), b = static_cast<int>(edge.to);
    const bool step = edge.edge->kind == memory::EdgeKind::kSequence;
    if (!step && calibration.distance_m(a, b, dissimilarity(a, b)) >
                     params.step_likeness * calibration.step_m) {
      continue;
    }
    if (auto candidate = measure(a, b, calibration.step_m, params.motion_length_stddev, step)) {
      candidates.push_back(*candidate);
    }
  }
  for (int a = 0; a < static_cast<int>(ranking.size()); ++a) {
    for (const SimilarPlace& similar : most_similar_first(ranking[a], params.motion_neighbours)) {
      if (auto candidate = neighbour(a, similar.place, similar.dissimilarity)) {
        candidates.push_back(*candidate);
      }
    }
  }

  MeasuredMotions result;
  if (candidates.empty()) return result;
  std::vector<double> residuals;
  for (const Candidate& candidate : candidates) residuals.push_back(candidate.residual);
  const double limit = params.look_alike_residual * median(std::move(residuals));
  const StepCheck steps(
      candidates, static_cast<int>(ranking.size()), params.step_check_steps,
      calibration.step_m * std::hypot(direction_stddev, params.motion_length_stddev));
  std::vector<Candidate> dropped;
  PlaceSets joined(static_cast<int>(ranking.size()));
  for (const Candidate& candidate : candidates) {
    if (!candidate.motion.step &&
        (candidate.residual > limit || steps.contradicts(candidate.motion))) {
      dropped.push_back(candidate);
    } else {
      result.motions.push_back(candidate.motion);
      joined.join(candidate.motion.from, candidate.motion.to);
    }
  }
  result.look_alikes_dropped = static_cast<int>(dropped.size());
  if (joined.count() == 1) return result;

  // Joining: the most similar pairs first, among the dropped motions and each place's ranked
  // places (those not tried yet are fitted now).
  std::vector<std::tuple<double, int, int, std::optional<Candidate>>> joins;
  for (const Candidate& candidate : dropped) {
    joins.emplace_back(dissimilarity(candidate.motion.from, candidate.motion.to),
                       candidate.motion.from, candidate.motion.to, candidate);
  }
  for (int a = 0; a < static_cast<int>(ranking.size()); ++a) {
    for (const SimilarPlace& similar : ranking[a]) {
      joins.emplace_back(similar.dissimilarity, a, similar.place, std::nullopt);
    }
  }
  std::sort(joins.begin(), joins.end(), [](const auto& x, const auto& y) {
    return std::tie(std::get<0>(x), std::get<1>(x), std::get<2>(x)) <
           std::tie(std::get<0>(y), std::get<1>(y), std::get<2>(y));
  });
  for (auto& [pair_dissimilarity, a, b, candidate] : joins) {
    if (joined.joined(a, b)) continue;
    const bool was_dropped = candidate.has_value();
    if (!candidate) candidate = neighbour(a, b, pair_dissimilarity);
    if (!candidate) continue;
    result.motions.push_back(candidate->motion);
    joined.join(a, b);
    ++result.joins;
    result.look_alikes_dropped -= was_dropped;
    if (joined.count() == 1) break;
  }
  return result;
}

}  // namespace omninav::lattice::detail
