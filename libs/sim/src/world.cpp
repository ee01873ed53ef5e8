#include "omninav/sim/world.hpp"

#include <algorithm>

namespace omninav::sim {

bool World::is_free(double x_m, double y_m, double clearance_m) const {
  const FloorBox inner{floor.min_x_m + clearance_m, floor.min_y_m + clearance_m,
                       floor.max_x_m - clearance_m, floor.max_y_m - clearance_m};
  if (!inner.contains(x_m, y_m)) return false;
  for (const FloorBox& box : obstacles) {
    const FloorBox grown{box.min_x_m - clearance_m, box.min_y_m - clearance_m,
                         box.max_x_m + clearance_m, box.max_y_m + clearance_m};
    if (grown.contains(x_m, y_m)) return false;
  }
  return true;
}

namespace {

// Whether the segment from a to a + d meets the closed box (Liang-Barsky clipping).
bool segment_meets(const FloorBox& box, double ax, double ay, double dx, double dy) {
  double enter = 0.0, leave = 1.0;
  const auto clip = [&](double delta, double low, double high, double start) {
    if (delta == 0.0) return start >= low && start <= high;
    double t0 = (low - start) / delta, t1 = (high - start) / delta;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    return enter <= leave;
  };
  return clip(dx, box.min_x_m, box.max_x_m, ax) && clip(dy, box.min_y_m, box.max_y_m, ay);
}

}  // namespace

bool World::segment_is_free(double x0_m, double y0_m, double x1_m, double y1_m,
                            double clearance_m) const {
  // The floor is convex: both ends inside means the whole segment is.
  if (!is_free(x0_m, y0_m, clearance_m) || !is_free(x1_m, y1_m, clearance_m)) return false;
  for (const FloorBox& box : obstacles) {
    const FloorBox grown{box.min_x_m - clearance_m, box.min_y_m - clearance_m,
                         box.max_x_m + clearance_m, box.max_y_m + clearance_m};
    if (segment_meets(grown, x0_m, y0_m, x1_m - x0_m, y1_m - y0_m)) return false;
  }
  return true;
}

const Region* World::region_at(double x_m, double y_m) const {
  for (const Region& region : regions) {
    if (region.area.contains(x_m, y_m)) return &region;
  }
  return nullptr;
}

}  // namespace omninav::sim
