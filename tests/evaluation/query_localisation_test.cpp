// localise's pipeline (query_localisation.hpp) against the rendered room's grid map: a stored
// view finds its own place, scored against the truth; a map without places is refused.
#include "omninav/evaluation/query_localisation.hpp"

#include <gtest/gtest.h>

#include <string>

#include "omninav/core/errors.hpp"
#include "support/room_navigation_map.hpp"

namespace omninav::evaluation {
namespace {

using testing::RoomNavigation;

TEST_F(RoomNavigation, AQueryAtAPlaceFindsItAndIsScored) {
  QueryLocaliser localiser(map().memory, "room.vmem", memory::LocalisationParams{},
                           navigation::RouteParams{}, QueryLocalisationOptions{});
  ASSERT_TRUE(localiser.score().has_value());  // the rendered map's places have truth
  const testing::StoredView& view = map().grid.front();
  io::Frame frame;
  frame.image = view.panorama;
  frame.source = "view 0";
  frame.truth = view.pose;
  const QueryLocalisation q = localiser.localise(frame, localiser.signature_of(frame));
  EXPECT_EQ(q.source, "view 0");
  EXPECT_FALSE(q.no_match.has_value());
  ASSERT_FALSE(q.result.best.empty());
  ASSERT_TRUE(q.score.has_value());
  EXPECT_LT(q.score->error_m, 0.01);
  EXPECT_EQ(localiser.score()->queries(), 1u);
  EXPECT_FALSE(q.home.has_value());  // not asked for
}

TEST(QueryLocaliser, AMapWithoutPlacesIsRefusedNamingIt) {
  const memory::VisualMemory empty{memory::MapParameters{}};
  try {
    QueryLocaliser localiser(empty, "empty.vmem", memory::LocalisationParams{},
                             navigation::RouteParams{}, QueryLocalisationOptions{});
    FAIL() << "a map without places was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("empty.vmem"), std::string::npos);
  }
}

}  // namespace
}  // namespace omninav::evaluation
