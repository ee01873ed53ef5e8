// omninav route and omninav navigate end to end, in-process: exit status, messages, output
// checked against the rendered grid's ground truth. The maps' lattices are set from the
// places' ground truth by the fixture (libs/lattice is tested on its own), so that these tests
// check planning and navigation whatever the lattice's accuracy.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "command_line_test.hpp"
#include "omninav/io/sequence.hpp"
#include "omninav/memory/map_store.hpp"

namespace omninav::cli {
namespace {

class RouteAndNavigate : public CommandLineTest {
 protected:
  // A 6 × 5 grid at 30 cm rendered into a BoB database and explored into a map.
  void make_map() {
    render_and_explore_grid();
    frames_ = io::read_all(*io::open_sequence(grid_));
  }

  // The places' lattice positions from their ground truth, in the lattice frame (origin at the
  // first place, its heading along +x).
  void set_truth_lattice() {
    memory::MapStore store(map_);
    memory::VisualMemory memory = store.load();
    const CameraPose first = *memory.place(0).truth;
    std::vector<Eigen::Vector2d> positions;
    for (std::size_t i = 0; i < memory.place_count(); ++i) {
      const CameraPose& truth = *memory.place(i).truth;
      const double dx = truth.x_m - first.x_m, dy = truth.y_m - first.y_m;
      const double c = std::cos(first.heading_rad), s = std::sin(first.heading_rad);
      positions.emplace_back(c * dx + s * dy, -s * dx + c * dy);
    }
    memory.set_lattice_positions(positions);
    store.save(memory);
  }

  // The frame whose true position is (x, y).
  const io::Frame& frame_at(double x_m, double y_m) const {
    for (const io::Frame& frame : frames_) {
      if (std::hypot(frame.truth->x_m - x_m, frame.truth->y_m - y_m) < 1e-6) return frame;
    }
    throw std::runtime_error("no grid frame there");
  }

  std::vector<io::Frame> frames_;
};

TEST_F(RouteAndNavigate, RouteGoesFromTheCurrentPlaceToTheGoalsOverNeighbours) {
  make_map();
  set_truth_lattice();
  const io::Frame& from = frame_at(1.2, 1.6);
  const io::Frame& to = frame_at(2.4, 2.2);
  ASSERT_EQ(run_omninav({"route", map_.string(), "--from", from.source, "--to", to.source,
                         "--format", "csv", "--plot", (folder_ / "route.png").string()}),
            0)
      << errors_;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "route.png"));
  const auto rows = csv_rows(output_);
  ASSERT_GE(rows.size(), 3u) << output_;
  EXPECT_EQ(rows[0][0], "step");
  // Truth columns: from the current image's position to the goal image's, each step to a
  // lattice neighbour (within 1.6 spacings), and no longer than the shortest route on the
  // 8-neighbour grid (2 diagonal steps and 2 straight: 1.45 m; furniture leaves the grid
  // 17 of its 30 points, but one such route).
  const auto truth = [&](std::size_t row) {
    return std::make_pair(parse_double(rows[row][8], "x"), parse_double(rows[row][9], "y"));
  };
  EXPECT_NEAR(truth(1).first, 1.2, 1e-6);
  EXPECT_NEAR(truth(1).second, 1.6, 1e-6);
  EXPECT_NEAR(truth(rows.size() - 1).first, 2.4, 1e-6);
  EXPECT_NEAR(truth(rows.size() - 1).second, 2.2, 1e-6);
  double length_m = 0.0;
  for (std::size_t row = 2; row < rows.size(); ++row) {
    const double step_m = std::hypot(truth(row).first - truth(row - 1).first,
                                     truth(row).second - truth(row - 1).second);
    EXPECT_LE(step_m, 1.6 * 0.3 + 1e-6);
    length_m += step_m;
  }
  EXPECT_LE(length_m, 2 * std::hypot(0.3, 0.3) + 2 * 0.3 + 1e-6);
  // The first row carries the turn from the robot's heading now; the goal row no direction.
  EXPECT_FALSE(rows[1][7].empty());
  EXPECT_TRUE(rows.back()[5].empty());

  ASSERT_EQ(run_omninav({"route", map_.string(), "--from", from.source, "--to", to.source,
                         "--format", "json", "--plot", (folder_ / "route.png").string()}),
            0)
      << errors_;
  EXPECT_NE(output_.find("\"route\""), std::string::npos) << output_;
  EXPECT_NE(output_.find("\"turn_from_robot_deg\""), std::string::npos) << output_;
  ASSERT_EQ(run_omninav({"route", map_.string(), "--from", from.source, "--to", to.source}), 0)
      << errors_;
  EXPECT_NE(output_.find("now: turn"), std::string::npos) << output_;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "grid.route.png"));
}

TEST_F(RouteAndNavigate, RouteErrorsAreClear) {
  make_map();
  const std::string image = frames_.front().source;
  // No lattice yet: a usage error saying what to run.
  EXPECT_EQ(run_omninav({"route", map_.string(), "--from", image, "--to", image}), 2);
  EXPECT_NE(errors_.find("omninav organise"), std::string::npos) << errors_;

  // An empty map: an input error.
  const std::filesystem::path empty = folder_ / "empty.vmem";
  memory::VisualMemory nothing;
  memory::MapStore(empty).save(nothing);
  EXPECT_EQ(run_omninav({"route", empty.string(), "--from", image, "--to", image}), 1);
  EXPECT_NE(errors_.find("no places"), std::string::npos) << errors_;

  set_truth_lattice();
  // An image that is no image, and one that matches no place: input errors naming the file.
  const std::filesystem::path broken = folder_ / "broken.png";
  std::ofstream(broken, std::ios::binary) << "not a png";
  EXPECT_EQ(run_omninav({"route", map_.string(), "--from", broken.string(), "--to", image}), 1);
  EXPECT_NE(errors_.find("broken.png"), std::string::npos) << errors_;
  cv::Mat noise(24, 180, CV_8UC3);
  cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 256);
  const std::filesystem::path elsewhere = folder_ / "noise.png";
  cv::imwrite(elsewhere.string(), noise);
  EXPECT_EQ(run_omninav({"route", map_.string(), "--from", image, "--to", elsewhere.string()}), 1);
  EXPECT_NE(errors_.find("noise.png: matches no place"), std::string::npos) << errors_;
  EXPECT_EQ(std::count(errors_.begin(), errors_.end(), '\n'), 1) << errors_;
  // Usage: a missing --to, an unknown format.
  EXPECT_EQ(run_omninav({"route", map_.string(), "--from", image}), 2);
  EXPECT_EQ(
      run_omninav({"route", map_.string(), "--from", image, "--to", image, "--format", "xml"}), 2);
}

TEST_F(RouteAndNavigate, NavigateOnAGridDatabaseReachesTheGoalImage) {
  make_map();
  set_truth_lattice();
  const io::Frame& goal = frame_at(2.4, 2.2);
  const std::filesystem::path out = folder_ / "nav";
  ASSERT_EQ(run_omninav({"navigate", map_.string(), "--database", grid_.string(), "--start",
                         "1.25,1.05,-120", "--goal", goal.source, "--out", out.string()}),
            0)
      << errors_;
  EXPECT_NE(output_.find("reached the goal"), std::string::npos) << output_;
  std::ifstream steps(out / "steps.csv");
  std::stringstream text;
  text << steps.rdbuf();
  const auto rows = csv_rows(text.str());
  ASSERT_GE(rows.size(), 3u);
  // The robot stands on grid images only (it starts on the one nearest to --start), and stops
  // on the goal's.
  EXPECT_NEAR(parse_double(rows[1][1], "x"), 1.2, 1e-6);
  EXPECT_NEAR(parse_double(rows[1][2], "y"), 1.6, 1e-6);
  EXPECT_NEAR(parse_double(rows.back()[1], "x"), 2.4, 1e-6);
  EXPECT_NEAR(parse_double(rows.back()[2], "y"), 2.2, 1e-6);
  EXPECT_TRUE(std::filesystem::exists(out / "path.png"));
}

TEST_F(RouteAndNavigate, NavigateTrialsWriteTheirScores) {
  make_map();
  set_truth_lattice();
  const std::filesystem::path out = folder_ / "trials";
  ASSERT_EQ(run_omninav(
                {"navigate", map_.string(), "--trials", "2", "--seed", "3", "--out", out.string()}),
            0)
      << errors_;
  EXPECT_NE(output_.find("reached 2 of 2 goals"), std::string::npos) << output_;
  std::ifstream csv(out / "trials.csv");
  std::stringstream text;
  text << csv.rdbuf();
  EXPECT_EQ(csv_rows(text.str()).size(), 3u);
  // Usage errors: trials need a rendered world; a single run needs --start and --goal.
  EXPECT_EQ(run_omninav({"navigate", map_.string(), "--trials", "2", "--database", grid_.string(),
                         "--out", out.string()}),
            2);
  EXPECT_EQ(run_omninav({"navigate", map_.string(), "--out", out.string()}), 2);
}

}  // namespace
}  // namespace omninav::cli
