#include "motions.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "headings.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/statistics.hpp"
#include "place_sets.hpp"
#include "two_way_fit.hpp"

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
  const std::optional<TwoWayFit> fit =
      fit_two_way(memory, a, b, signed_difference(*headings[b], *headings[a]));
  if (!fit) return std::nullopt;
  return DirectionFit{wrap_angle(*headings[a] + fit->direction_at_a_rad), fit->residual};
}

// A step between places whose headings differ by more than this went round a bend.
constexpr double kStraightTurnRad = 0.35;  // 20°

// From the motion's first place to its second, metres in the lattice frame.
Eigen::Vector2d displacement(const MotionMeasurement& motion) {
  return motion.length_m *
         Eigen::Vector2d(std::cos(motion.direction_rad), std::sin(motion.direction_rad));
}

// Along a stream, the steps between two places that are few steps apart tell where one lies
// from the other (dead reckoning, errors growing with the square root of the steps); a
// neighbour motion between such places that disagrees with them by more than step_check_sigmas
// standard deviations is a look-alike's. Places not joined by unbroken steps, or too many steps
// apart, are not judged.
class StepCheck {
 public:
  // step_limit_m: how far a motion may be from the steps' dead reckoning over one step (so many
  // standard deviations of one step's displacement); over n steps, sqrt(n) times that.
  StepCheck(const std::vector<Candidate>& candidates, int place_count, int max_steps,
            double step_limit_m)
      : step_after_(place_count), max_steps_(max_steps), step_limit_m_(step_limit_m) {
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
           step_limit_m_ * std::sqrt(static_cast<double>(last - first));
  }

 private:
  std::vector<std::optional<Eigen::Vector2d>> step_after_;  // from place i to place i + 1
  int max_steps_;
  double step_limit_m_;  // over one step
};

// The headings the motions are measured with: the map's (lattice_headings), those of the visual
// compass made consistent across the map (headings.hpp) when asked.
std::vector<std::optional<double>> motion_headings(
    const memory::VisualMemory& memory, const std::vector<std::vector<SimilarPlace>>& ranking,
    const OrganiseParams& params) {
  std::vector<std::optional<double>> headings = lattice_headings(memory);
  bool compass = params.synchronise_compass_headings;
  for (std::size_t i = 0; i < memory.place_count() && compass; ++i) {
    compass = memory.place(i).heading_source == memory::HeadingSource::kCompass;
  }
  if (!compass) return headings;
  return synchronise_headings(memory, std::move(headings), ranking, params.motion_neighbours,
                              kStraightTurnRad);
}

// measure_motions, as its steps: the candidates (steps, listed pairs, neighbours), the
// screening of look-alikes, and the joins of what is left apart. Each pair is fitted once.
class MotionMeasurer {
 public:
  MotionMeasurer(const memory::VisualMemory& memory, const PlaceDissimilarities& dissimilarity,
                 const std::vector<std::vector<SimilarPlace>>& ranking,
                 const DistanceCalibration& calibration, const OrganiseParams& params)
      : memory_(memory),
        dissimilarity_(dissimilarity),
        ranking_(ranking),
        calibration_(calibration),
        params_(params),
        headings_(motion_headings(memory, ranking, params)),
        direction_stddev_(deg_to_rad(params.motion_direction_stddev_deg)),
        joined_(static_cast<int>(ranking.size())) {}

  MeasuredMotions measure() {
    std::vector<Candidate> candidates = candidate_motions();
    if (candidates.empty()) return result_;
    if (params_.steps_along_heading) steer_steps_by_headings(candidates);
    const std::vector<Candidate> dropped = keep_all_but_look_alikes(candidates);
    result_.look_alikes_dropped = static_cast<int>(dropped.size());
    result_.pieces = joined_.count();
    if (joined_.count() > 1) join_what_is_apart(dropped);
    return result_;
  }

 private:
  // Fits the motion from a to b unless the pair was tried before.
  std::optional<Candidate> fit(int a, int b, double length_m, double length_stddev, bool step) {
    if (!tried_.insert({std::min(a, b), std::max(a, b)}).second) return std::nullopt;
    const auto direction = fit_direction(memory_, headings_, a, b);
    if (!direction) return std::nullopt;
    return Candidate{{a, b, direction->direction_rad, length_m, direction_stddev_,
                      length_stddev * length_m, step},
                     direction->residual};
  }

  // A motion to a most similar place: its length the calibrated distance, held loosely.
  std::optional<Candidate> neighbour(int a, int b, double pair_dissimilarity) {
    return fit(a, b, calibration_.distance_m(a, b, pair_dissimilarity),
               params_.neighbour_motion_length_stddev, false);
  }

  // A stream's steps, an unordered input's listed pairs that look one step apart, and each
  // place's most similar places, in that order.
  std::vector<Candidate> candidate_motions() {
    std::vector<Candidate> candidates;
    for (const memory::VisualMemory::EdgeRef& edge : memory_.edges()) {
      const int a = static_cast<int>(edge.from), b = static_cast<int>(edge.to);
      const bool step = edge.edge->kind == memory::EdgeKind::kSequence;
      if (!step && calibration_.distance_m(a, b, dissimilarity_(a, b)) >
                       params_.step_likeness * calibration_.step_m) {
        continue;
      }
      if (auto candidate = fit(a, b, calibration_.step_m, params_.motion_length_stddev, step)) {
        candidates.push_back(*candidate);
      }
    }
    for (int a = 0; a < static_cast<int>(ranking_.size()); ++a) {
      for (const SimilarPlace& similar :
           most_similar_first(ranking_[a], params_.motion_neighbours)) {
        if (auto candidate = neighbour(a, similar.place, similar.dissimilarity)) {
          candidates.push_back(*candidate);
        }
      }
    }
    return candidates;
  }

  // A stream's steps along the robot's headings: the direction from one place to the next is
  // the mean of the two places' headings plus the offset between the camera's front and the
  // way the robot drives (the median over the steps of the phases' direction against the
  // headings'; 0 for a robot that drives forward with its camera's front ahead).
  void steer_steps_by_headings(std::vector<Candidate>& candidates) const {
    std::vector<double> offsets;
    for (const Candidate& candidate : candidates) {
      if (candidate.motion.step && !turned(candidate.motion)) {
        offsets.push_back(
            signed_difference(candidate.motion.direction_rad, heading_between(candidate.motion)));
      }
    }
    if (offsets.empty()) return;
    const double offset = circular_median(offsets);
    for (Candidate& candidate : candidates) {
      if (candidate.motion.step && !turned(candidate.motion)) {
        candidate.motion.direction_rad = wrap_angle(heading_between(candidate.motion) + offset);
      }
    }
  }

  // Whether the robot turned between the motion's places by more than kStraightTurnRad: then
  // the path between them bends and the mean heading is no better than the phases' fit.
  bool turned(const MotionMeasurement& motion) const {
    return std::abs(signed_difference(*headings_[motion.to], *headings_[motion.from])) >
           kStraightTurnRad;
  }

  double heading_between(const MotionMeasurement& motion) const {
    const double from = *headings_[motion.from], to = *headings_[motion.to];
    return wrap_angle(from + 0.5 * signed_difference(to, from));
  }

  // Keeps the steps and the neighbour motions that are no look-alike's (by their residual, or
  // against the steps); returns those dropped.
  std::vector<Candidate> keep_all_but_look_alikes(const std::vector<Candidate>& candidates) {
    std::vector<double> residuals;
    for (const Candidate& candidate : candidates) residuals.push_back(candidate.residual);
    const double limit = params_.look_alike_residual * median(std::move(residuals));
    const StepCheck steps(candidates, static_cast<int>(ranking_.size()), params_.step_check_steps,
                          params_.step_check_sigmas * calibration_.step_m *
                              std::hypot(direction_stddev_, params_.motion_length_stddev));
    std::vector<Candidate> dropped;
    for (const Candidate& candidate : candidates) {
      if (!candidate.motion.step &&
          (candidate.residual > limit || steps.contradicts(candidate.motion))) {
        dropped.push_back(candidate);
      } else {
        result_.motions.push_back(candidate.motion);
        joined_.join(candidate.motion.from, candidate.motion.to);
      }
    }
    return dropped;
  }

  // Joining: the best-fitting pairs first (the smallest fit residual), among the dropped motions
  // and each place's ranked places not yet joined, each fitted. Not the most similar pairs,
  // which are often look-alikes metres away (docs/evaluation.md, "Joins").
  void join_what_is_apart(const std::vector<Candidate>& dropped) {
    std::vector<std::tuple<double, int, int, Candidate>> joins;
    for (const Candidate& candidate : dropped) {
      joins.emplace_back(candidate.residual, candidate.motion.from, candidate.motion.to, candidate);
    }
    for (int a = 0; a < static_cast<int>(ranking_.size()); ++a) {
      for (const SimilarPlace& similar : ranking_[a]) {
        if (joined_.joined(a, similar.place)) continue;
        if (auto candidate = neighbour(a, similar.place, similar.dissimilarity)) {
          joins.emplace_back(candidate->residual, a, similar.place, *candidate);
        }
      }
    }
    std::sort(joins.begin(), joins.end(), [](const auto& x, const auto& y) {
      return std::tie(std::get<0>(x), std::get<1>(x), std::get<2>(x)) <
             std::tie(std::get<0>(y), std::get<1>(y), std::get<2>(y));
    });
    std::set<std::pair<int, int>> dropped_pairs;
    for (const Candidate& candidate : dropped) {
      dropped_pairs.insert({candidate.motion.from, candidate.motion.to});
    }
    for (const auto& [residual, a, b, candidate] : joins) {
      if (joined_.joined(a, b)) continue;
      const bool was_dropped = dropped_pairs.count({a, b}) > 0;
      result_.motions.push_back(candidate.motion);
      joined_.join(a, b);
      ++result_.joins;
      result_.look_alikes_dropped -= was_dropped;
      if (joined_.count() == 1) break;
    }
  }

  const memory::VisualMemory& memory_;
  const PlaceDissimilarities& dissimilarity_;
  const std::vector<std::vector<SimilarPlace>>& ranking_;
  const DistanceCalibration& calibration_;
  const OrganiseParams& params_;
  const std::vector<std::optional<double>> headings_;
  const double direction_stddev_;
  std::set<std::pair<int, int>> tried_;
  PlaceSets joined_;
  MeasuredMotions result_;
};

}  // namespace

MeasuredMotions measure_motions(const memory::VisualMemory& memory,
                                const PlaceDissimilarities& dissimilarity,
                                const std::vector<std::vector<SimilarPlace>>& ranking,
                                const DistanceCalibration& calibration,
                                const OrganiseParams& params) {
  return MotionMeasurer(memory, dissimilarity, ranking, calibration, params).measure();
}

}  // namespace omninav::lattice::detail
