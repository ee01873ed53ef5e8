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

  std::filesystem::path folder_;
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
