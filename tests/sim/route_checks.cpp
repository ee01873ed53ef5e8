#include "route_checks.hpp"

#include <gtest/gtest.h>

#include "omninav/core/errors.hpp"

namespace omninav::sim::testing {

void expect_in_free_space(const World& world, const Trajectory& route, double clearance_m,
                          const std::string& label) {
  for (std::size_t i = 0; i < route.poses.size(); ++i) {
    const CameraPose& p = route.poses[i].pose;
    ASSERT_TRUE(world.is_free(p.x_m, p.y_m, clearance_m)) << label << " pose " << i;
    if (i > 0) {
      const CameraPose& q = route.poses[i - 1].pose;
      ASSERT_TRUE(world.segment_is_free(q.x_m, q.y_m, p.x_m, p.y_m, clearance_m))
          << label << " " << i;
    }
  }
}

void expect_trajectory_error(const std::string& spec, const World& world,
                             const std::vector<std::string>& fragments) {
  try {
    make_trajectory(spec, world);
    ADD_FAILURE() << "no error for " << spec;
  } catch (const Error& error) {
    for (const std::string& fragment : fragments) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos)
          << spec << " gave: " << error.what();
    }
  }
}

}  // namespace omninav::sim::testing
