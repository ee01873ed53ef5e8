// Every evaluation suite shipped in config/suites/ loads strictly.
#include <gtest/gtest.h>

#include <filesystem>

#include "omninav/evaluation/suite.hpp"
#include "support/shared_data.hpp"

namespace omninav::evaluation {
namespace {

TEST(ShippedConfig, EverySuiteLoadsStrictly) {
  int suites = 0;
  for (const std::filesystem::directory_entry& entry :
       std::filesystem::directory_iterator(omninav::testing::config_dir() / "suites")) {
    EXPECT_EQ(entry.path().extension(), ".yaml") << entry.path();
    EXPECT_NO_THROW(load_suite(entry.path().string(), {})) << entry.path();
    ++suites;
  }
  EXPECT_GE(suites, 2) << "the quick and full suites";
}

}  // namespace
}  // namespace omninav::evaluation
