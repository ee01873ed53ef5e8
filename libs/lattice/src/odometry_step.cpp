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

}  // namespace omninav::lattice
