#include "omninav/report/lattice_figures.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace omninav::report {
namespace {

// Four places on a 1 m square, their lattice the truth turned a quarter, springs round it.
memory::VisualMemory square() {
  memory::VisualMemory memory;
  const std::vector<Eigen::Vector2d> corners = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Eigen::Vector2d& corner : corners) {
    memory::Place place;
    place.signature = {1, 1, 15, 32, std::vector<float>(15, 1.f), std::vector<float>(15, 0.f)};
    place.truth = CameraPose{corner.x(), corner.y(), 1.0, 0.0, 0.0, 0.0};
    place.lattice_position = Eigen::Vector2d(-corner.y(), corner.x());
    memory.add_place(std::move(place));
  }
  return memory;
}

lattice::OrganiseResult springs_round(const memory::VisualMemory& memory) {
  lattice::OrganiseResult organised;
  organised.calibration.correlation_range_m = 2.0;
  for (int a = 0; a < static_cast<int>(memory.place_count()); ++a) {
    organised.springs.push_back({a, (a + 1) % 4, 1.0, false});
  }
  return organised;
}

// The columns [from, to) of `picture`.
cv::Mat columns(const cv::Mat& picture, int from, int to) {
  return picture(cv::Range::all(), cv::Range(from, to));
}

TEST(LatticePicture, TheTruthPanelStandsBesideTheLatticeAndShowsTheFolds) {
  const memory::VisualMemory memory = square();
  const lattice::OrganiseResult organised = springs_round(memory);
  const cv::Mat lattice_only = lattice_picture(memory, organised);

  LatticeOverTruth truth;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    truth.aligned.push_back(memory.place(i).truth->floor_position());
  }
  const cv::Mat with_truth = lattice_picture(memory, organised, &truth);
  ASSERT_EQ(with_truth.rows, lattice_only.rows);
  ASSERT_EQ(with_truth.cols, 2 * lattice_only.cols);
  // The left panel is the lattice, drawn the same with or without the truth.
  EXPECT_EQ(cv::norm(columns(with_truth, 0, lattice_only.cols), lattice_only, cv::NORM_INF), 0.0);

  // A fold marks its places in the truth panel, and changes nothing in the lattice's.
  LatticeOverTruth folded = truth;
  folded.folded.push_back({0, 1, 2});
  const cv::Mat with_fold = lattice_picture(memory, organised, &folded);
  EXPECT_EQ(cv::norm(columns(with_fold, 0, lattice_only.cols), lattice_only, cv::NORM_INF), 0.0);
  const int right = with_fold.cols;
  EXPECT_GT(cv::norm(columns(with_fold, lattice_only.cols, right),
                     columns(with_truth, lattice_only.cols, right), cv::NORM_L1),
            0.0);
}

}  // namespace
}  // namespace omninav::report
