#include "omninav/compass/heading_window.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/turn_residual.hpp"

namespace omninav::compass {
namespace {

// The Cauchy loss of a residual r in standard deviations: a² log(1 + (r/a)²), as ceres::CauchyLoss.
double cauchy(double residual, double scale) {
  const double ratio = residual / scale;
  return scale * scale * std::log1p(ratio * ratio);
}

// The sub-pixel fit's own variance under the uncertainty model's: one column, uniform.
double sigma_rad(double match_variance_rad2, int width_px) {
  const double column_rad = kTwoPi / width_px;
  return std::sqrt(match_variance_rad2 + column_rad * column_rad / 12.0);
}

// A match counts while the amplitude allows it (𝒜_n >= t, Algorithm 1's line 10) and it has one
// reading.
bool usable(const PairMatch& match, const SamplingParams& sampling) {
  return match.amplitude_norm >= sampling.threshold_norm_amp && !match.flags.featureless &&
         !match.flags.competing_minima;
}

}  // namespace

HeadingWindow::HeadingWindow(const CompassParams& params)
    : params_(params), local_(std::make_unique<PairMatcher>(params.matcher)) {
  const WindowParams& window = params.window;
  if (window.keyframes < 0 || window.length_frames < 2 || !(window.loss_scale > 0.0)) {
    throw UsageError(
        "the heading window needs keyframes >= 0, length_frames >= 2 and loss_scale > 0");
  }
  PairMatcherParams global = params.matcher;
  global.minimiser.kind = params.matcher.distance.metric == Metric::kL2
                              ? MinimiserKind::kFft
                              : MinimiserKind::kExhaustive;
  global_ = std::make_unique<PairMatcher>(global);
}

HeadingWindow::~HeadingWindow() = default;

std::optional<HeadingWindow::Measurement> HeadingWindow::measure(
    const Keyframe& keyframe, const CompassFrame& frame, int position,
    double predicted_heading_rad) const {
  const double predicted_rad = predicted_heading_rad - headings_rad_[keyframe.position];
  const int start_shift =
      static_cast<int>(std::lround(-shift_px_of_rotation(predicted_rad, frame.width())));
  PairMatch match = local_->match(keyframe.frame, frame, start_shift);
  if (!usable(match, params_.sampling) && params_.matcher.minimiser.kind != MinimiserKind::kFft &&
      params_.matcher.minimiser.kind != MinimiserKind::kExhaustive) {
    match = global_->match(keyframe.frame, frame, start_shift);
  }
  if (!usable(match, params_.sampling)) return std::nullopt;
  // Beyond the rotation cap with parallax (visual_compass.hpp): a baseline Algorithm 1 would
  // have cut, biased by the parallax of the turn.
  const SamplingParams& sampling = params_.sampling;
  const bool long_baseline = sampling.max_reference_rotation_rad > 0.0 &&
                             std::abs(match.rotation_rad) > sampling.max_reference_rotation_rad &&
                             match.distance_min > sampling.parallax_step_ratio * match.self_step;
  return Measurement{keyframe.position, position, match.rotation_rad,
                     sigma_rad(match_variance_rad2(match, frame.width()), frame.width()),
                     long_baseline};
}

double HeadingWindow::starting_heading(const std::vector<Measurement>& incoming) const {
  double best_heading = 0.0;
  double best_loss = std::numeric_limits<double>::infinity();
  for (const Measurement& candidate : incoming) {
    const double heading = headings_rad_[candidate.from] + candidate.rotation_rad;
    double loss = 0.0;
    for (const Measurement& m : incoming) {
      const double residual =
          signed_difference(heading - headings_rad_[m.from], m.rotation_rad) / m.sigma_rad;
      loss += cauchy(residual, params_.window.loss_scale);
    }
    if (loss < best_loss) {
      best_loss = loss;
      best_heading = heading;
    }
  }
  return best_heading;
}

void HeadingWindow::solve() {
  const int newest = static_cast<int>(headings_rad_.size()) - 1;
  // Frame 0 is the start (the initial heading): never solved.
  const int first = std::max(1, newest - params_.window.length_frames + 1);
  while (!measurements_.empty() && measurements_.front().to < first) measurements_.pop_front();
  ceres::CauchyLoss loss(params_.window.loss_scale);
  ceres::Problem::Options options;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  for (const Measurement& m : measurements_) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<TurnResidual, 1, 1, 1>(
                                 new TurnResidual(m.rotation_rad, m.sigma_rad)),
                             &loss, &headings_rad_[m.from], &headings_rad_[m.to]);
    if (m.from < first) problem.SetParameterBlockConstant(&headings_rad_[m.from]);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 20;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
}

CompassEstimate HeadingWindow::push(const CompassFrame& frame, const CompassEstimate& chain) {
  const int position = static_cast<int>(headings_rad_.size());
  CompassEstimate estimate = chain;
  if (position == 0) {
    headings_rad_.push_back(chain.heading_rad);
    keyframes_.push_back({frame, 0});
    previous_ = frame;
    return estimate;
  }
  if (chain.new_reference) {
    // Lines 11-13: the previous frame is the new reference, and a keyframe.
    keyframes_.push_back({*previous_, position - 1});
    while (static_cast<int>(keyframes_.size()) > params_.window.keyframes + 1) {
      keyframes_.pop_front();
    }
  }
  previous_ = frame;
  const Keyframe& reference = keyframes_.back();
  if (reference.frame.index() != chain.reference_index) {
    throw UsageError("the heading window was given the frames out of Algorithm 1's order");
  }
  std::vector<Measurement> incoming = {{reference.position, position, chain.reference_rotation_rad,
                                        sigma_rad(chain.match_variance_rad2, frame.width())}};
  const double predicted_rad = headings_rad_[reference.position] + chain.reference_rotation_rad;
  // The earlier keyframes, newest first, while the amplitude allows.
  for (int k = static_cast<int>(keyframes_.size()) - 2; k >= 0; --k) {
    if (std::optional<Measurement> m = measure(keyframes_[k], frame, position, predicted_rad)) {
      incoming.push_back(*m);
      ++keyframe_matches_;
    } else {
      keyframes_.erase(keyframes_.begin() + k);
    }
  }
  double start_rad = incoming.size() == 1 ? predicted_rad : starting_heading(incoming);
  if (params_.window.gate_long_baselines &&
      std::abs(signed_difference(start_rad, predicted_rad)) <
          params_.matcher.confidence.competing_separation_rad) {
    // The baselines agree with the chain's reading: the long ones, biased by parallax, stay out.
    std::erase_if(incoming, [](const Measurement& m) { return m.long_baseline; });
    start_rad = incoming.size() == 1 ? predicted_rad : starting_heading(incoming);
  }
  headings_rad_.push_back(start_rad);
  measurements_.insert(measurements_.end(), incoming.begin(), incoming.end());
  if (incoming.size() > 1) solve();
  estimate.heading_rad = headings_rad_[position];
  estimate.rotation_rad = headings_rad_[position] - headings_rad_[position - 1];
  return estimate;
}

}  // namespace omninav::compass
