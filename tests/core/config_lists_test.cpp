// ConfigReader's lists: lists of numbers, and lists of maps read like sections, both as strict
// as single values (the evaluation suites are read this way).
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"

namespace omninav {
namespace {

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(no ConfigError)";
}

TEST(ConfigLists, NumbersAreReadInOrderAndAbsentListsKeepTheDefault) {
  const ConfigReader config =
      ConfigReader::from_string("seeds: [3, 1, 2]\nheights: [0.1, 1.5]\n", "suite.yaml");
  std::vector<int> seeds{9};
  std::vector<double> heights;
  std::vector<double> absent{4.0};
  config.read("seeds", seeds, 0, 10);
  config.read("heights", heights, 0.0, 2.0);
  config.read("absent", absent, 0.0, 10.0);
  EXPECT_NO_THROW(config.require_all_known());
  EXPECT_EQ(seeds, (std::vector<int>{3, 1, 2}));
  EXPECT_EQ(heights, (std::vector<double>{0.1, 1.5}));
  EXPECT_EQ(absent, (std::vector<double>{4.0}));
}

TEST(ConfigLists, ABadItemNamesItsIndexAndAnEmptyListIsRefused) {
  const auto read_ints = [](const std::string& yaml) {
    return error_of([&] {
      std::vector<int> values;
      ConfigReader::from_string(yaml, "suite.yaml").read("seeds", values, 0, 10);
    });
  };
  EXPECT_NE(read_ints("seeds: [1, 11]").find("seeds[1]"), std::string::npos);
  EXPECT_NE(read_ints("seeds: [1, x]").find("seeds[1]"), std::string::npos);
  EXPECT_NE(read_ints("seeds: []").find("non-empty list"), std::string::npos);
  EXPECT_NE(read_ints("seeds: 3").find("'seeds'"), std::string::npos);
  EXPECT_NE(error_of([] {
              std::vector<double> values;
              ConfigReader::from_string("h: [1, .nan]", "s.yaml").read("h", values, 0.0, 9.0);
            }).find("h[1]"),
            std::string::npos);
}

TEST(ConfigLists, MapsOfAListAreSectionsWhoseUnknownKeysAreNamedByIndex) {
  const ConfigReader config = ConfigReader::from_string(
      "worlds:\n  - {world: room, seeds: [1]}\n  - {world: field, sedes: [2]}\n", "suite.yaml");
  const std::vector<ConfigReader> worlds = config.sections("worlds");
  ASSERT_EQ(worlds.size(), 2u);
  std::vector<std::string> specs;
  for (const ConfigReader& world : worlds) {
    std::string spec;
    std::vector<int> seeds;
    world.read("world", spec, {});
    world.read("seeds", seeds, 0, 10);
    specs.push_back(spec);
  }
  EXPECT_EQ(specs, (std::vector<std::string>{"room", "field"}));
  const std::string message = error_of([&] { config.require_all_known(); });
  EXPECT_NE(message.find("worlds[1].sedes"), std::string::npos) << message;
  EXPECT_NE(
      error_of([] { ConfigReader::from_string("w: [1, 2]", "s.yaml").sections("w"); }).find("w[0]"),
      std::string::npos);
}

TEST(ConfigLists, AKeyWrittenTwiceInAMapOfAListIsRefused) {
  EXPECT_NE(error_of([] {
              ConfigReader::from_string("worlds:\n  - {world: a, world: b}\n", "suite.yaml");
            }).find("twice"),
            std::string::npos);
}

}  // namespace
}  // namespace omninav
