// `omninav completion bash`: the script, loaded into a real bash, completes commands, each
// command's own options and file names, as a user pressing Tab would see them.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>

#include "command_line_test.hpp"

namespace omninav::cli {
namespace {

class Completion : public CommandLineTest {
 protected:
  // What bash offers for the words of `line` (the last one being completed), the script loaded.
  std::string complete(const std::filesystem::path& script, const std::string& line) {
    const std::filesystem::path program = folder_ / "complete.sh";
    std::ofstream(program) << "source '" << script.string() << "'\n"
                           << "COMP_WORDS=(" << line << ")\n"
                           << "COMP_CWORD=$((${#COMP_WORDS[@]} - 1))\n"
                           << "cd '" << folder_.string() << "'\n"
                           << "_omninav\n"
                           << "printf '%s\\n' \"${COMPREPLY[@]}\"\n";
    std::string offered;
    FILE* bash = ::popen(("bash " + program.string() + " 2>&1").c_str(), "r");
    if (bash == nullptr) return "bash did not start";
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), bash) != nullptr) offered += buffer.data();
    ::pclose(bash);
    return offered;
  }
};

TEST_F(Completion, BashCompletesCommandsTheirOptionsAndFiles) {
  ASSERT_EQ(run_omninav({"completion", "bash"}), 0) << errors_;
  const std::filesystem::path script = folder_ / "omninav.bash";
  std::ofstream(script) << output_;

  const std::string commands = complete(script, "omninav co");
  EXPECT_NE(commands.find("compass\n"), std::string::npos) << commands;
  EXPECT_NE(commands.find("completion\n"), std::string::npos) << commands;
  EXPECT_EQ(commands.find("explore"), std::string::npos) << commands;

  // The compass's own options, not another command's; the global options before the command.
  const std::string compass = complete(script, "omninav -q compass --");
  EXPECT_NE(compass.find("--format\n"), std::string::npos) << compass;
  EXPECT_NE(compass.find("--truth\n"), std::string::npos) << compass;
  EXPECT_EQ(compass.find("--trials"), std::string::npos) << "navigate's option" << compass;
  const std::string explore = complete(script, "omninav explore --");
  EXPECT_NE(explore.find("--force\n"), std::string::npos) << explore;
  EXPECT_EQ(explore.find("--overwrite"), std::string::npos) << "an old spelling" << explore;
  const std::string global = complete(script, "omninav --config-dir /tmp --q");
  EXPECT_EQ(global, "--quiet\n");

  // A value: a file name.
  std::ofstream(folder_ / "route.bag") << "x";
  const std::string file = complete(script, "omninav compass --input rou");
  EXPECT_EQ(file, "route.bag\n");

  EXPECT_EQ(run_omninav({"completion", "zsh"}), 2);
}

}  // namespace
}  // namespace omninav::cli
