#pragma once
// Where the tests find ../shared/data (the third-party data of shared/data/README.md). It is
// never copied into the repository; a test that needs it calls OMNINAV_REQUIRE_SHARED_DATA,
// which skips the test with a message when the data is absent.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

namespace omninav::testing {

// OMNINAV_SHARED_DATA overrides the location compiled in from the source tree.
inline std::filesystem::path shared_data_dir() {
  if (const char* from_env = std::getenv("OMNINAV_SHARED_DATA")) return from_env;
  return OMNINAV_SHARED_DATA_DIR;
}

inline std::filesystem::path config_dir() { return OMNINAV_CONFIG_DIR; }

}  // namespace omninav::testing

// Skips the current test unless shared/data/<relative> exists.
#define OMNINAV_REQUIRE_SHARED_DATA(relative)                                             \
  do {                                                                                    \
    if (!std::filesystem::exists(::omninav::testing::shared_data_dir() / (relative))) {   \
      GTEST_SKIP() << "shared data " << (relative) << " is absent (looked in "            \
                   << ::omninav::testing::shared_data_dir() << ")";                       \
    }                                                                                     \
  } while (false)
