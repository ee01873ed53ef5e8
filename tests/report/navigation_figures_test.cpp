#include "omninav/report/navigation_figures.hpp"

#include <gtest/gtest.h>

#include "omninav/measures/plot.hpp"

namespace omninav::report {
namespace {

// The pixels of `panel` in exactly `colour` in the middle band of rows (35% to 65% of the
// height: the plot area's middle, where points on one horizontal line are drawn, below the
// legend in the top right corner): how many, and their mean column.
struct ColourPixels {
  int count = 0;
  double mean_column = 0.0;
};

ColourPixels pixels_of(const cv::Mat& panel, const cv::Scalar& colour) {
  const cv::Vec3b bgr(static_cast<uchar>(colour[0]), static_cast<uchar>(colour[1]),
                      static_cast<uchar>(colour[2]));
  ColourPixels found;
  for (int row = panel.rows * 35 / 100; row < panel.rows * 65 / 100; ++row) {
    for (int column = 0; column < panel.cols; ++column) {
      if (panel.at<cv::Vec3b>(row, column) != bgr) continue;
      ++found.count;
      found.mean_column += column;
    }
  }
  if (found.count > 0) found.mean_column /= found.count;
  return found;
}

// Six places in a row on the lattice, a route planned along the first five from the west end
// to place 4, the sixth (east of them) linked to none; their true positions are the lattice
// mirrored (x → −x), so that the truth panel, if it draws the truth, shows the goal west of
// the start where the lattice panel shows it east. The figure adds its point sets in the
// order places, route, start, goal, and a PointsPlot gives the k-th set palette colour k
// (measures/plot.hpp): only the sixth place shows the places' colour (the route's markers cover the
// others), the start is drawn in colour 2, the goal in colour 3.
TEST(NavigationFigures, RoutePictureDrawsTheRouteOnTheLatticeAndOverTheTruth) {
  std::vector<navigation::PlaceNode> places;
  std::vector<Eigen::Vector2d> truth;
  std::vector<navigation::MeasuredLink> chain;
  for (int x = 0; x < 6; ++x) {
    places.push_back({Eigen::Vector2d(x, 0.0), 0.0});
    truth.emplace_back(-x, 0.0);
    if (x > 0 && x < 5) chain.push_back({{x - 1, x}, 1.0, 0.0, M_PI});
  }
  const navigation::RoutePlan plan = navigation::plan_to_goal(places, chain, 4);
  const cv::Mat lattice_only = route_figure(places, plan, 0, std::nullopt);
  const cv::Mat both = route_figure(places, plan, 0, truth);
  ASSERT_EQ(both.type(), CV_8UC3);
  ASSERT_EQ(both.rows, lattice_only.rows);
  ASSERT_EQ(both.cols, 2 * lattice_only.cols);
  const int width = lattice_only.cols;
  const cv::Mat lattice_panel = both.colRange(0, width);
  const cv::Mat truth_panel = both.colRange(width, 2 * width);

  // Without truth, the lattice panel alone.
  EXPECT_EQ(cv::norm(lattice_panel, lattice_only, cv::NORM_INF), 0.0);
  // Both panels show every point set: places, route, start and goal.
  for (std::size_t set = 0; set < 4; ++set) {
    EXPECT_GT(pixels_of(lattice_panel, measures::palette_colour(set)).count, 0) << "set " << set;
    EXPECT_GT(pixels_of(truth_panel, measures::palette_colour(set)).count, 0) << "set " << set;
  }
  // The goal east of the start on the lattice, west of it over the truth.
  const auto start_column = [](const cv::Mat& panel) {
    return pixels_of(panel, measures::palette_colour(2)).mean_column;
  };
  const auto goal_column = [](const cv::Mat& panel) {
    return pixels_of(panel, measures::palette_colour(3)).mean_column;
  };
  EXPECT_GT(goal_column(lattice_panel), start_column(lattice_panel) + 50.0);
  EXPECT_LT(goal_column(truth_panel), start_column(truth_panel) - 50.0);
  // The place off the route lies east of the goal on the lattice, west of it over the truth.
  const auto place_column = [](const cv::Mat& panel) {
    return pixels_of(panel, measures::palette_colour(0)).mean_column;
  };
  EXPECT_GT(place_column(lattice_panel), goal_column(lattice_panel) + 50.0);
  EXPECT_LT(place_column(truth_panel), goal_column(truth_panel) - 50.0);
}

// A run along five of six places in a row on the lattice (east), whose true positions are the
// lattice mirrored (x → −x): the robot starts at place 0 and stops at the goal, place 4. The
// lattice panel adds the sets places, goal (palette colours 0, 1); the true-path panel, with
// nothing of the scene but the map's truth, places (truth), goal place, start (0, 1, 2).
// Six places one metre apart along a line (the lattice's x, the truth's −x) and a run that
// matched the first five in turn while walking west over them.
struct WalkWest {
  std::vector<navigation::PlaceNode> places;
  memory::VisualMemory memory;
  navigation::NavigationResult result;
  WalkWest() {
    for (int x = 0; x < 6; ++x) {
      places.push_back({Eigen::Vector2d(x, 0.0), 0.0});
      memory::Place place;
      place.signature = {1, 1, 15, 32, std::vector<float>(15, 1.f), std::vector<float>(15, 0.f)};
      place.truth = CameraPose{-1.0 * x, 0.0, 1.0, 0.0, 0.0, 0.0};
      memory.add_place(std::move(place));
    }
    for (int x = 0; x < 5; ++x) {
      navigation::NavigationStep step;
      step.index = x;
      step.truth = CameraPose{-1.0 * x, 0.0, 1.0, 0.0, 0.0, 0.0};
      step.match = memory::PlaceMatch{};
      step.match->place = static_cast<memory::PlaceIndex>(x);
      result.steps.push_back(step);
    }
  }
  // The truth panel, the right half of the figure with `scene`.
  cv::Mat truth_panel(const NavigationScene& scene) const {
    const cv::Mat picture = navigation_path_figure(result, places, 4, memory, scene);
    return picture.colRange(picture.cols / 2, picture.cols).clone();
  }
};

TEST(NavigationFigures, PathPictureDrawsTheMatchesOnTheLatticeAndThePathOverTheTruth) {
  const WalkWest walk;
  const std::vector<navigation::PlaceNode>& places = walk.places;
  const memory::VisualMemory& memory = walk.memory;
  const navigation::NavigationResult& result = walk.result;
  const int goal = 4;
  const cv::Mat picture = navigation_path_figure(result, places, goal, memory, {});
  ASSERT_EQ(picture.type(), CV_8UC3);
  ASSERT_EQ(picture.cols % 2, 0);
  const int width = picture.cols / 2;
  const cv::Mat lattice_panel = picture.colRange(0, width);
  const cv::Mat truth_panel = picture.colRange(width, 2 * width);
  const auto column = [](const cv::Mat& panel, std::size_t set) {
    const ColourPixels found = pixels_of(panel, measures::palette_colour(set));
    EXPECT_GT(found.count, 0) << "set " << set;
    return found.mean_column;
  };
  // On the lattice the goal (x = 4) lies east of the other places' mean (x = 2.2).
  EXPECT_GT(column(lattice_panel, 1), column(lattice_panel, 0) + 50.0);
  // Over the truth the goal place (x = −4) lies west of the start (x = 0).
  EXPECT_LT(column(truth_panel, 1), column(truth_panel, 2) - 50.0);
  // Nothing in a fourth colour: no grid images and no goal pose were given.
  EXPECT_EQ(pixels_of(truth_panel, measures::palette_colour(3)).count, 0);
}

// A large world's far furniture (a field's tussocks 40 m away) is left out of the truth panel,
// which frames the path and the places: the goal place 4 m west of the start stays a third of
// the panel away from it, where a frame stretched to 41 m would put it 60 pixels away.
TEST(NavigationFigures, PathPictureFramesThePathAndThePlacesNotTheWholeWorld) {
  const WalkWest walk;
  NavigationScene scene;
  scene.obstacles = {{40.0, 0.0, 41.0, 1.0}, {0.5, -0.5, 1.0, 0.5}};
  const cv::Mat panel = walk.truth_panel(scene);
  const double goal_place = pixels_of(panel, measures::palette_colour(1)).mean_column;
  const double start = pixels_of(panel, measures::palette_colour(2)).mean_column;
  EXPECT_GT(start - goal_place, panel.cols / 3.0);
  // The box beside the path is drawn: grey outline pixels east of the start.
  const cv::Mat without = walk.truth_panel({});
  EXPECT_GT(cv::norm(panel, without, cv::NORM_L1), 0.0);
}

}  // namespace
}  // namespace omninav::report
