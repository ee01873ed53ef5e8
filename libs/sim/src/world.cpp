#include "omninav/sim/world.hpp"

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

const Region* World::region_at(double x_m, double y_m) const {
  for (const Region& region : regions) {
    if (region.area.contains(x_m, y_m)) return &region;
  }
  return nullptr;
}

}  // namespace omninav::sim
