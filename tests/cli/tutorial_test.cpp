// docs/tutorial.md, run as a newcomer runs it: its command-line block, word for word but for
// where the program and the arena frames are, in a fresh folder; then what it made is checked.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "command_line_test.hpp"
#include "omninav/memory/map_store.hpp"

namespace omninav::cli {
namespace {

// The lines of the first ```sh block of `file`.
std::vector<std::string> first_shell_block(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```sh") {
      inside = true;
    } else if (inside && line.rfind("```", 0) == 0) {
      break;
    } else if (inside) {
      lines.push_back(line);
    }
  }
  return lines;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Tutorial : public CommandLineTest {};

TEST_F(Tutorial, TheCommandLineWalkThroughRunsOnTheArenaFrames) {
  OMNINAV_REQUIRE_SHARED_DATA("real/ftl-arena/route");
  const std::filesystem::path source = config_dir_.parent_path();
  const std::vector<std::string> block = first_shell_block(source / "docs" / "tutorial.md");
  ASSERT_GE(block.size(), 4u) << "no command-line block in docs/tutorial.md";

  // The block as written, but for two lines that say where things are: the program (this
  // build's) and the frames (the shared data this test found).
  std::ofstream script(folder_ / "tutorial.sh");
  script << "set -euo pipefail\n";
  for (const std::string& line : block) {
    if (line.rfind("export PATH=", 0) == 0) {
      script << "export PATH='" << std::filesystem::path(OMNINAV_PROGRAM).parent_path().string()
             << "':$PATH\n";
    } else if (line.rfind("ARENA=", 0) == 0) {
      script << "ARENA='" << (omninav::testing::shared_data_dir() / "real/ftl-arena").string()
             << "'\n";
    } else {
      script << line << "\n";
    }
  }
  script.close();
  const std::string command = "cd '" + folder_.string() + "' && bash tutorial.sh > log.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(folder_ / "log.txt");

  const memory::VisualMemory map = memory::load_map(folder_ / "arena.vmem");
  EXPECT_GE(map.place_count(), 5u) << "130 frames along a route through the arena";
  EXPECT_LE(map.place_count(), 130u);
  EXPECT_EQ(csv_rows(read_text(folder_ / "plants.csv")).size(), 1u + 7u) << "7 plant frames";
  EXPECT_EQ(csv_rows(read_text(folder_ / "compass.csv")).size(), 1u + 130u);
  EXPECT_EQ(csv_rows(read_text(folder_ / "places.csv")).size(), 1u + map.place_count());
  EXPECT_EQ(read_text(folder_ / "compass.png").substr(0, 4), "\x89PNG");
}

}  // namespace
}  // namespace omninav::cli
