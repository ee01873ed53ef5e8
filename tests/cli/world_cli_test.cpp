// World specs on the command line: every family renders through `omninav render`, and a bad
// spec is a usage error on one line naming the key and its range.
#include <algorithm>

#include "cli.hpp"
#include "command_line_test.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::cli {
namespace {

using WorldCommandLine = CommandLineTest;

TEST_F(WorldCommandLine, EveryFamilyRendersAWanderInItsFreeSpaceAndAPlan) {
  for (const std::string spec :
       {"room:seed=3,size_x_m=9,boxes=12,walls=plain", "house:rooms=3,texture_px_per_m=20",
        "office:rows=2", "field:tussocks=500,size_m=10,texture_px_per_m=10"}) {
    const std::filesystem::path out = folder_ / spec.substr(0, spec.find(':'));
    ASSERT_EQ(
        run_omninav({"render", "--world", spec, "--trajectory", "wander:length_m=3,fps=2,z_m=0.3",
                     "--out", out.string(), "--width", "90", "--height", "12"}),
        0)
        << spec << ": " << errors_;
    EXPECT_TRUE(std::filesystem::exists(out / "plan.png")) << spec;
    const sim::World world = sim::load_world(spec, sim::WorldsConfig{});
    const std::unique_ptr<io::SequenceReader> reader = io::open_sequence(out);
    const std::vector<io::Frame> frames = io::read_all(*reader);
    ASSERT_EQ(frames.size(), 31u) << spec;  // 3 m at 0.2 m/s, 2 frames a second
    for (const io::Frame& frame : frames) {
      ASSERT_TRUE(frame.truth.has_value());
      EXPECT_TRUE(world.is_free(frame.truth->x_m, frame.truth->y_m, 0.2)) << spec;
      EXPECT_NEAR(frame.truth->z_m, 0.3, 1e-9);
    }
  }
}

TEST_F(WorldCommandLine, BadSpecIsAUsageErrorOnOneLine) {
  EXPECT_EQ(run_omninav({"render", "--world", "house:rooms=12", "--trajectory", "rotate", "--out",
                         (folder_ / "x").string()}),
            2);
  EXPECT_NE(errors_.find("rooms = 12 is out of range (valid: [2, 10])"), std::string::npos)
      << errors_;
  EXPECT_EQ(std::count(errors_.begin(), errors_.end(), '\n'), 1) << errors_;
  EXPECT_FALSE(std::filesystem::exists(folder_ / "x" / "database_entries.csv"));
}

}  // namespace
}  // namespace omninav::cli
