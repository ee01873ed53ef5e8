// Suites: the YAML of config/suites/ read strictly and expanded into rows.
#include "omninav/evaluation/suite.hpp"

#include <gtest/gtest.h>

#include "omninav/core/errors.hpp"
#include "support/shared_data.hpp"

namespace omninav::evaluation {
namespace {

TEST(Suite, ExpandsSeedsAndCameraHeightsIntoRows) {
  const Suite suite = parse_suite(R"(
name: test
panorama: {width_px: 120, height_px: 16}
memory: {queries: 30, spacing_m: 0.25}
navigation: {trials: 7, goal_radius_m: 0.2}
tour: {fps: 4, turn_rate_deg_s: 60, odometry_noise: 0.1}
worlds:
  - {name: room, world: "room:boxes=3", seeds: [1, 2]}
  - {world: field, camera_heights_m: [0.1, 1.0], spacing_m: 0.5}
  - {name: arena, world: arena.obj, obj_scale_to_m: 20}
)",
                                  "test.yaml");
  EXPECT_EQ(suite.name, "test");
  EXPECT_EQ(suite.params.width_px, 120);
  EXPECT_EQ(suite.params.queries, 30);
  EXPECT_EQ(suite.params.trials, 7);
  EXPECT_EQ(suite.params.goal_radius_m, 0.2);
  EXPECT_EQ(suite.params.tour_fps, 4.0);
  EXPECT_EQ(suite.params.tour_turn_rate_deg_s, 60.0);
  EXPECT_EQ(suite.params.odometry_noise, 0.1);
  EXPECT_EQ(SuiteParams{}.goal_radius_m, 0.3);  // the default of every suite
  ASSERT_EQ(suite.worlds.size(), 5u);
  EXPECT_EQ(suite.worlds[0].label, "room-s1");
  EXPECT_EQ(suite.worlds[0].spec, "room:boxes=3,seed=1");
  EXPECT_EQ(suite.worlds[1].spec, "room:boxes=3,seed=2");
  EXPECT_EQ(suite.worlds[1].seed, 2u);
  EXPECT_EQ(suite.worlds[0].spacing_m, 0.25);  // the suite's
  EXPECT_EQ(suite.worlds[2].label, "field-h10cm");
  EXPECT_EQ(suite.worlds[2].spec, "field");  // no seeds: the spec as given
  EXPECT_EQ(suite.worlds[2].camera_height_m, 0.1);
  EXPECT_EQ(suite.worlds[3].label, "field-h100cm");
  EXPECT_EQ(suite.worlds[3].spacing_m, 0.5);
  EXPECT_EQ(suite.worlds[4].family, "obj");
  EXPECT_EQ(suite.worlds[4].obj_scale_to_m, 20.0);
}

TEST(Suite, UnknownKeysAndBadValuesAreConfigErrorsNamingTheKey) {
  const auto error_of = [](const std::string& yaml) {
    try {
      parse_suite(yaml, "bad.yaml");
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("worlds: [{world: room}]\nmemroy: {queries: 3}").find("memroy"),
            std::string::npos);
  EXPECT_NE(error_of("worlds: [{world: room, sedes: [1]}]").find("worlds[0].sedes"),
            std::string::npos);
  EXPECT_NE(error_of("worlds: [{world: room}]\nmemory: {queries: -3}").find("memory.queries"),
            std::string::npos);
  EXPECT_NE(error_of("worlds: []").find("worlds"), std::string::npos);
  EXPECT_NE(
      error_of("worlds: [{world: room}]\ntour: {odometry_noise: 2}").find("tour.odometry_noise"),
      std::string::npos);
  EXPECT_NE(error_of("worlds: [{world: room}]\nnavigation: {goal_radius_m: 0}")
                .find("navigation.goal_radius_m"),
            std::string::npos);
  EXPECT_NE(error_of("worlds: [{name: a}]").find("world"), std::string::npos);
  EXPECT_NE(error_of("worlds: [{world: room}, {world: room}]").find("two rows"), std::string::npos);
}

TEST(Suite, NamesAreNamesNotPaths) {
  // A suite's name and a world's become folders under evaluation/: none may lead out of it.
  for (const std::string name : {"../x", "/tmp/x", "a/b", "..", ".hidden", "x\\y", "a b"}) {
    SCOPED_TRACE(name);
    EXPECT_THROW(parse_suite("name: '" + name + "'\nworlds: [{world: room}]", "s.yaml"),
                 ConfigError);
    EXPECT_THROW(parse_suite("worlds: [{name: '" + name + "', world: room}]", "s.yaml"),
                 ConfigError);
  }
  EXPECT_EQ(parse_suite("name: quick-2.1_b\nworlds: [{name: room_1, world: room}]", "s.yaml").name,
            "quick-2.1_b");
}

TEST(Suite, FamiliesAreTheSpecsHeadsAndPathsAreObj) {
  EXPECT_EQ(family_of("room"), "room");
  EXPECT_EQ(family_of("house:seed=2,rooms=4"), "house");
  EXPECT_EQ(family_of("../shared/data/worlds/ofstad/ofstad.obj"), "obj");
  EXPECT_EQ(family_of("arena.obj"), "obj");
}

TEST(Suite, TheShippedSuitesLoad) {
  for (const std::string name : {"quick", "full"}) {
    const Suite suite = load_suite(name, omninav::testing::config_dir());
    EXPECT_EQ(suite.name, name);
    EXPECT_FALSE(suite.worlds.empty());
    EXPECT_GE(suite.params.queries, 100) << "evaluation needs at least 100 queries";
    EXPECT_GE(suite.params.trials, 50) << "evaluation needs at least 50 trials";
  }
  EXPECT_THROW(load_suite("no_such_suite", omninav::testing::config_dir()), UsageError);
}

}  // namespace
}  // namespace omninav::evaluation
