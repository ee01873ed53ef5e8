#include "odometry_spread.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "odometry_step.hpp"

namespace omninav::lattice {

OdometrySpread::OdometrySpread(const memory::VisualMemory& memory,
                               const std::vector<std::vector<int>>& streams, double noise,
                               double spacing_m) {
  for (const std::vector<int>& stream : streams) {
    std::vector<Sums>& sums = sums_.emplace_back(stream.size());
    std::vector<Eigen::Vector2d>& positions = positions_.emplace_back(stream.size());
    for (std::size_t k = 0; k < stream.size(); ++k) {
      const std::optional<CameraPose>& odometry = memory.place(stream[k]).odometry;
      positions[k] =
          odometry ? Eigen::Vector2d(odometry->x_m, odometry->y_m) : Eigen::Vector2d::Zero();
      if (k == 0) continue;
      Sums& sum = sums[k];
      sum = sums[k - 1];
      const std::optional<OdometryStep> step = odometry_step(memory, stream[k - 1], stream[k]);
      if (!step) {
        ++sum.unmeasured;
        continue;
      }
      const OdometryStepStddev stddev = odometry_step_stddev(*step, noise, spacing_m);
      // The turn's error swings what follows round the step's end, place k.
      const double turn_variance = stddev.turn_rad * stddev.turn_rad;
      sum.length_variance += stddev.translation_m * stddev.translation_m;
      sum.turn_variance += turn_variance;
      sum.turn_moment += turn_variance * positions[k];
      sum.turn_second_moment += turn_variance * positions[k].squaredNorm();
    }
  }
}

double OdometrySpread::stddev_m(int stream, int from, int to) const {
  if (from > to) std::swap(from, to);
  const std::vector<Sums>& sums = sums_[stream];
  const Sums& first = sums[from];
  const Sums& last = sums[to];
  if (last.unmeasured > first.unmeasured) return std::numeric_limits<double>::infinity();
  // Σ over the steps after `from` up to `to` of σ_turn² |p_to − p_k|², expanded into the sums.
  const Eigen::Vector2d& p = positions_[stream][to];
  const double swing = p.squaredNorm() * (last.turn_variance - first.turn_variance) -
                       2.0 * p.dot(last.turn_moment - first.turn_moment) +
                       (last.turn_second_moment - first.turn_second_moment);
  return std::sqrt(std::max(0.0, last.length_variance - first.length_variance + swing));
}

}  // namespace omninav::lattice
