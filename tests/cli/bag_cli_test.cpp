// Bags on the command line: a ROS 2 bag gives the compass the headings its database gives, with
// its poses as ground truth; topics chosen, or refused with the reason.

#include <gtest/gtest.h>

#include "command_line_test.hpp"
#include "omninav/core/csv.hpp"

namespace omninav::cli {
namespace {

using CommandLine = CommandLineTest;

const std::filesystem::path kBags =
    std::filesystem::path(OMNINAV_CONFIG_DIR).parent_path() / "tests" / "io" / "bags";

std::vector<double> column(const std::filesystem::path& csv, const std::string& name) {
  const CsvTable table = CsvTable::read(csv);
  const std::size_t index = table.require_column(name);
  std::vector<double> values;
  for (const CsvTable::Row& row : table.rows()) values.push_back(std::stod(row.fields[index]));
  return values;
}

TEST_F(CommandLine, CompassOverABagMatchesItsDatabaseWithThePosesAsTruth) {
  const std::filesystem::path from_database = folder_ / "database.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", (kBags / "route").string(), "--truth", "--out",
                         from_database.string()}),
            0)
      << errors_;
  const std::filesystem::path from_bag = folder_ / "bag.csv";
  ASSERT_EQ(run_omninav({"compass", "--input", (kBags / "route_zstd.mcap").string(), "--pose-topic",
                         "/pose", "--truth", "--out", from_bag.string()}),
            0)
      << errors_;
  for (const std::string name : {"heading_deg", "truth_heading_deg"}) {
    SCOPED_TRACE(name);
    const std::vector<double> expected = column(from_database, name);
    const std::vector<double> got = column(from_bag, name);
    ASSERT_EQ(expected.size(), 9u);
    ASSERT_EQ(got.size(), expected.size());
    // The same pixels and, from the poses' quaternions, the same true headings to rounding.
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], expected[i], 1e-6) << i;
  }
}

TEST_F(CommandLine, BagTopicsChosenOrRefusedWithTheReason) {
  const std::string bag = (kBags / "route_lz4.mcap").string();
  EXPECT_EQ(run_omninav({"compass", "--input", bag, "--out", "-"}), 1);
  EXPECT_NE(errors_.find("several image topics: /camera/image_raw (sensor_msgs/msg/Image), "
                         "/camera2/image_raw (sensor_msgs/msg/Image); choose one with --topic"),
            std::string::npos)
      << errors_;
  EXPECT_EQ(run_omninav({"compass", "--input", bag, "--topic", "/camera2/image_raw", "--out",
                         (folder_ / "c.csv").string()}),
            0)
      << errors_;
  EXPECT_EQ(run_omninav({"compass", "--input", (kBags / "route").string(), "--topic", "/camera",
                         "--out", "-"}),
            2);
  EXPECT_NE(errors_.find("--topic and --pose-topic are for bags"), std::string::npos) << errors_;
}

}  // namespace
}  // namespace omninav::cli
