#include "odometry_step.hpp"

#include <cmath>

#include "omninav/core/angles.hpp"

namespace omninav::lattice {

std::optional<OdometryStep> odometry_step(const memory::VisualMemory& memory, int a, int b) {
  const std::optional<CameraPose>& from = memory.place(a).odometry;
  const std::optional<CameraPose>& to = memory.place(b).odometry;
  if (!from || !to) return std::nullopt;
  const double c = std::cos(from->heading_rad), s = std::sin(from->heading_rad);
  const double dx = to->x_m - from->x_m, dy = to->y_m - from->y_m;
  return OdometryStep{{c * dx + s * dy, -s * dx + c * dy},
                      signed_difference(to->heading_rad, from->heading_rad)};
}

OdometryStepStddev odometry_step_stddev(const OdometryStep& step, double noise, double spacing_m) {
  return {noise * (step.translation_m.norm() + 0.1 * spacing_m),
          noise * (std::abs(step.turn_rad) + 0.1)};
}

}  // namespace omninav::lattice
