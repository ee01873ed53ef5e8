#pragma once
// The fixture of the command-line tests: omninav run in-process with the shipped config, each
// test in a fresh temporary folder, what it printed kept for the test to check.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "omninav/core/parse.hpp"
#include "support/shared_data.hpp"

namespace omninav::cli {

class CommandLineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = std::filesystem::temp_directory_path() /
              ("omninav_cli_" + std::to_string(::getpid()) + "_" + test->test_suite_name() + "_" +
               test->name());
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  // Runs omninav with `args`; returns the exit status and keeps what it printed.
  int run_omninav(std::vector<std::string> args) {
    args.insert(args.begin(), {"--config-dir", config_dir_.string()});
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    const int status = run(args);
    output_ = ::testing::internal::GetCapturedStdout();
    errors_ = ::testing::internal::GetCapturedStderr();
    return status;
  }

  // A 6 × 5 grid at 30 cm of the built-in room (180 × 24 panoramas) rendered into the BoB
  // database folder_/grid and explored into the map folder_/grid.vmem.
  void render_and_explore_grid() {
    grid_ = folder_ / "grid";
    ASSERT_EQ(run_omninav({"render", "--trajectory", "grid:x0=1.2,y0=1.0,nx=6,ny=5,spacing_m=0.3",
                           "--out", grid_.string(), "--width", "180", "--height", "24"}),
              0)
        << errors_;
    map_ = folder_ / "grid.vmem";
    ASSERT_EQ(run_omninav({"explore", "--input", grid_.string(), "--out", map_.string()}), 0)
        << errors_;
  }

  std::filesystem::path folder_;
  std::filesystem::path grid_, map_;  // render_and_explore_grid's
  std::filesystem::path config_dir_ = omninav::testing::config_dir();
  std::string output_, errors_;  // standard output and standard error of the last run
};

// The rows of a CSV text, each split at commas (the commands quote nothing they write).
inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) rows.push_back(split(line, ','));
  return rows;
}

}  // namespace omninav::cli
