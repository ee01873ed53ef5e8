// The robust pose graph against poses known by construction: a robot's path round a block,
// measured exactly, with drift, and with wrong revisits among right ones.
#include "omninav/lattice/pose_graph.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "omninav/core/errors.hpp"

namespace omninav::lattice {
namespace {

// The true poses of a robot driving `laps` times round a 3 × 2 m rectangle, a pose every
// 0.25 m, turning on the corner poses; heading along its path.
std::vector<Eigen::Vector3d> laps_of_a_rectangle(int laps) {
  std::vector<Eigen::Vector3d> poses;
  const double width = 3.0, height = 2.0, step = 0.25;
  const Eigen::Vector2d corners[] = {{0, 0}, {width, 0}, {width, height}, {0, height}};
  for (int lap = 0; lap < laps; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d from = corners[side], to = corners[(side + 1) % 4];
      const double heading = std::atan2(to.y() - from.y(), to.x() - from.x());
      const int steps = static_cast<int>(std::lround((to - from).norm() / step));
      for (int k = 0; k < steps; ++k) {
        const Eigen::Vector2d at = from + (to - from) * (static_cast<double>(k) / steps);
        poses.emplace_back(at.x(), at.y(), heading);
      }
    }
  }
  return poses;
}

// The exact pose of b in a's frame, with the given uncertainty.
RelativePoseMeasurement exact(const std::vector<Eigen::Vector3d>& poses, int a, int b,
                              double stddev_m, double turn_stddev_rad) {
  const double c = std::cos(poses[a].z()), s = std::sin(poses[a].z());
  const Eigen::Vector2d d = poses[b].head<2>() - poses[a].head<2>();
  RelativePoseMeasurement m;
  m.from = a;
  m.to = b;
  m.translation_m = {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
  m.turn_rad = std::remainder(poses[b].z() - poses[a].z(), 2.0 * M_PI);
  m.along_stddev_m = m.across_stddev_m = stddev_m;
  m.turn_stddev_rad = turn_stddev_rad;
  return m;
}

// The largest distance between a solved position and the truth, both in place 0's frame
// (the truth's place 0 is at the origin facing +x, as the solver's is).
double worst_error_m(const std::vector<Eigen::Vector3d>& truth, const PoseGraphResult& solved) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, (truth[i].head<2>() - solved.poses[i].head<2>()).norm());
  }
  return worst;
}

// The odometry of the path: each step's exact relative pose with a turn `turn_short` short
// (3 %) and a distance 2 % long, so that dead reckoning drifts (a robot's usual biased wheels),
// with standard deviations `noise` of the step's length and turn, as the driven lattice's.
std::vector<RelativePoseMeasurement> biased_odometry(const std::vector<Eigen::Vector3d>& poses,
                                                     double turn_short = 0.03,
                                                     double noise = 0.05) {
  std::vector<RelativePoseMeasurement> steps;
  for (int i = 0; i + 1 < static_cast<int>(poses.size()); ++i) {
    RelativePoseMeasurement m = exact(poses, i, i + 1, 0.0125, 0.01);
    m.translation_m *= 1.02;
    m.turn_rad *= 1.0 - turn_short;
    m.along_stddev_m = m.across_stddev_m = noise * (m.translation_m.norm() + 0.025);
    m.turn_stddev_rad = noise * (std::abs(m.turn_rad) + 0.1);
    steps.push_back(m);
  }
  return steps;
}

// Revisits between the same point of consecutive laps, exactly measured.
void add_true_revisits(const std::vector<Eigen::Vector3d>& poses, int per_lap,
                       std::vector<RelativePoseMeasurement>& measurements) {
  for (int i = 0; i + per_lap < static_cast<int>(poses.size()); i += 3) {
    RelativePoseMeasurement m = exact(poses, i, i + per_lap, 0.25, 0.09);
    m.switchable = true;
    measurements.push_back(m);
  }
}

TEST(PoseGraph, ExactMeasurementsGiveTheTruth) {
  const std::vector<Eigen::Vector3d> truth = laps_of_a_rectangle(1);
  std::vector<RelativePoseMeasurement> measurements;
  for (int i = 0; i + 1 < static_cast<int>(truth.size()); ++i) {
    measurements.push_back(exact(truth, i, i + 1, 0.01, 0.01));
  }
  const PoseGraphResult solved =
      solve_pose_graph(static_cast<int>(truth.size()), measurements, {}, {}, {});
  EXPECT_LT(worst_error_m(truth, solved), 1e-6);
  EXPECT_EQ(solved.pieces, 1);
  EXPECT_TRUE(solved.switches.empty());
}

TEST(PoseGraph, TrueRevisitsUndoTheDrift) {
  const std::vector<Eigen::Vector3d> truth = laps_of_a_rectangle(3);
  const int per_lap = static_cast<int>(truth.size()) / 3;
  std::vector<RelativePoseMeasurement> measurements = biased_odometry(truth);
  const PoseGraphResult dead_reckoning =
      solve_pose_graph(static_cast<int>(truth.size()), measurements, {}, {}, {});
  add_true_revisits(truth, per_lap, measurements);
  const PoseGraphResult closed =
      solve_pose_graph(static_cast<int>(truth.size()), measurements, {}, {}, {});
  std::cout << "three laps: worst error " << worst_error_m(truth, dead_reckoning)
            << " m by odometry alone, " << worst_error_m(truth, closed) << " m with revisits\n";
  EXPECT_GT(worst_error_m(truth, dead_reckoning), 1.0);  // the drift is real
  EXPECT_LT(worst_error_m(truth, closed), 0.25);         // within one step
  for (double on : closed.switches) EXPECT_GT(on, 0.5);  // no true revisit is switched off
}

TEST(PoseGraph, WrongRevisitsAreSwitchedOffAndRightOnesKept) {
  const std::vector<Eigen::Vector3d> truth = laps_of_a_rectangle(3);
  const int count = static_cast<int>(truth.size());
  const int per_lap = count / 3;
  std::vector<RelativePoseMeasurement> measurements = biased_odometry(truth);
  add_true_revisits(truth, per_lap, measurements);
  const std::size_t right = measurements.size() - (count - 1);
  // Look-alikes: places metres apart claimed to be the same spot, as a revisit claims.
  std::mt19937 random(7);
  std::uniform_int_distribution<int> place(0, count - 1);
  int wrong = 0;
  while (wrong < 15) {
    const int a = place(random), b = place(random);
    if ((truth[a].head<2>() - truth[b].head<2>()).norm() < 1.5) continue;
    RelativePoseMeasurement m;
    m.from = a;
    m.to = b;
    m.along_stddev_m = m.across_stddev_m = 0.25;
    m.turn_stddev_rad = 0.09;
    m.switchable = true;
    measurements.push_back(m);
    ++wrong;
  }
  const PoseGraphResult solved = solve_pose_graph(count, measurements, {}, {}, {});
  int right_kept = 0, wrong_off = 0;
  for (std::size_t i = 0; i < solved.switches.size(); ++i) {
    if (i < right)
      right_kept += solved.switches[i] >= 0.5 ? 1 : 0;
    else
      wrong_off += solved.switches[i] < 0.5 ? 1 : 0;
  }
  std::cout << "switches: " << right_kept << " of " << right << " true revisits kept, " << wrong_off
            << " of " << wrong << " wrong ones off; worst error " << worst_error_m(truth, solved)
            << " m\n";
  EXPECT_EQ(wrong_off, wrong);
  EXPECT_GE(right_kept, static_cast<int>(right) - 1);
  EXPECT_LT(worst_error_m(truth, solved), 0.25);

  // The same wrong revisits unswitchable wreck the map: the switches are what saves it.
  for (RelativePoseMeasurement& m : measurements) m.switchable = false;
  const PoseGraphResult plain = solve_pose_graph(count, measurements, {}, {}, {});
  EXPECT_GT(worst_error_m(truth, plain), 0.5);
}

TEST(PoseGraph, OdometryHundredsOfDegreesOffStillClosesOntoItsRevisits) {
  // Eight laps whose odometry loses a quarter of every turn: 720° by the end, so that dead
  // reckoning lays the laps over each other turned every way; the driven lattice's noise (30 %).
  const std::vector<Eigen::Vector3d> truth = laps_of_a_rectangle(8);
  const int count = static_cast<int>(truth.size());
  std::vector<RelativePoseMeasurement> measurements = biased_odometry(truth, 0.25, 0.3);
  add_true_revisits(truth, count / 8, measurements);
  const PoseGraphResult solved = solve_pose_graph(count, measurements, {}, {}, {});
  int off = 0;
  for (double on : solved.switches) off += on < 0.5 ? 1 : 0;
  std::cout << "eight laps, a quarter of each turn lost: worst error "
            << worst_error_m(truth, solved) << " m, " << off << " of " << solved.switches.size()
            << " true revisits switched off\n";
  EXPECT_LT(worst_error_m(truth, solved), 0.25);  // within one step
  EXPECT_EQ(off, 0);
}

TEST(PoseGraph, PiecesKeepTheirOwnGauge) {
  const std::vector<Eigen::Vector3d> truth = laps_of_a_rectangle(1);
  std::vector<RelativePoseMeasurement> measurements;
  const int half = static_cast<int>(truth.size()) / 2;
  for (int i = 0; i + 1 < static_cast<int>(truth.size()); ++i) {
    if (i + 1 != half) measurements.push_back(exact(truth, i, i + 1, 0.01, 0.01));
  }
  const PoseGraphResult solved =
      solve_pose_graph(static_cast<int>(truth.size()), measurements, {}, {}, {});
  EXPECT_EQ(solved.pieces, 2);
  // The second piece's first place starts a piece: at the origin, facing +x.
  EXPECT_NEAR(solved.poses[half].norm(), 0.0, 1e-9);
  EXPECT_NEAR(solved.poses[0].norm(), 0.0, 1e-9);
}

TEST(PoseGraph, BadMeasurementsAreRefused) {
  RelativePoseMeasurement outside;
  outside.from = 0;
  outside.to = 5;
  EXPECT_THROW(solve_pose_graph(3, {outside}, {}, {}, {}), UsageError);
  RelativePoseMeasurement certain;
  certain.from = 0;
  certain.to = 1;
  certain.turn_stddev_rad = 0.0;
  EXPECT_THROW(solve_pose_graph(3, {certain}, {}, {}, {}), UsageError);
  PoseGraphParams params;
  params.switch_prior_stddev = -1.0;
  EXPECT_THROW(solve_pose_graph(3, {}, {}, {}, params), UsageError);
}

}  // namespace
}  // namespace omninav::lattice
