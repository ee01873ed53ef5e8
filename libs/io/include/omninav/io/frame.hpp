#pragma once
// One image of an input sequence, with what the source knows about it.

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "omninav/core/pose.hpp"

namespace omninav::io {

struct Frame {
  int index = 0;                    // position in the sequence, from 0
  std::optional<double> time_s;     // capture time, when the source knows it
  cv::Mat image;                    // 8-bit BGR (or grey), as OpenCV reads it
  std::optional<CameraPose> truth;  // ground-truth pose, when the source has one
  std::string source;               // file (or "video.mp4#frame 12") the image came from
  // What the robot's own odometry measured (wheel odometry, dead reckoning), when the source
  // records it: a BoB database's Odometry columns, a CSV's odometry_* columns, a bag's
  // --pose-topic (a robot's pose topic is its odometry).
  std::optional<CameraPose> odometry;
};

}  // namespace omninav::io
