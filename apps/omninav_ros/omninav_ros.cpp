// omninav_ros: the live session (libs/navigation/.../live_session.hpp) as a ROS 1 node, a thin
// adapter: messages in, the session's outputs out (navigating, its command as a Twist on
// cmd_vel), the session's commands as services.
// docs/ros.md documents its topics, services and parameters. Compiled as C++17: ROS 1's
// generated message headers use std::allocator<void>::rebind, which C++20 removed.

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Float64MultiArray.h>
#include <std_msgs/UInt32.h>
#include <std_srvs/Trigger.h>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <exception>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "omninav/io/ros_image.hpp"
#include "ros_session.hpp"

namespace omninav::ros_node {
namespace {

// The fields of ~place, in order (its layout's label says them too).
constexpr const char* kPlaceFields =
    "place,similarity,dissimilarity_per_value,probability,confidence,lost";
// The fields of ~navigation, in order (state: 0 driving, 1 reached, 2 failed).
constexpr const char* kNavigationFields = "state,step,place,turn_rad,distance_m,homing,lost";
// The covariance of the parts of ~heading the node does not measure (position, roll, pitch):
// unknown, as robot_localization and REP 145 read a huge variance.
constexpr double kUnknownVariance = 1e9;

// A Float64MultiArray of one dimension whose label names its fields.
std_msgs::Float64MultiArray labelled(const char* fields, std::vector<double> data) {
  std_msgs::Float64MultiArray array;
  array.layout.dim.resize(1);
  array.layout.dim[0].label = fields;
  array.layout.dim[0].size = static_cast<std::uint32_t>(data.size());
  array.layout.dim[0].stride = static_cast<std::uint32_t>(data.size());
  array.data = std::move(data);
  return array;
}

class Node {
 public:
  Node(ros::NodeHandle& node, ros::NodeHandle& private_node) {
    const std::string config_dir = private_node.param<std::string>("config_dir", "");
    const std::string map = private_node.param<std::string>("map", "");
    use_odometry_ = private_node.param("use_odometry", false);
    const int queue = private_node.param("queue_size", 100);
    frame_id_ = private_node.param<std::string>("frame_id", "odom");
    max_linear_m_s_ = speed(private_node, "max_linear_speed", 0.2, 10.0);
    max_angular_rad_s_ = speed(private_node, "max_angular_speed", 0.5, 20.0);
    session_ = std::make_unique<RosSession>(config_dir, map, use_odometry_,
                                            static_cast<std::size_t>(std::max(queue, 1)));
    if (!session_->no_belief_reason().empty()) {
      ROS_WARN_STREAM("no places are recognised: " << session_->no_belief_reason());
    }
    heading_ = private_node.advertise<geometry_msgs::PoseWithCovarianceStamped>("heading", queue);
    place_ = private_node.advertise<std_msgs::Float64MultiArray>("place", queue);
    new_place_ = private_node.advertise<std_msgs::UInt32>("new_place", queue);
    navigation_ = private_node.advertise<std_msgs::Float64MultiArray>("navigation", queue);
    // In the node's namespace, not private: where a base controller listens (move_base's name).
    cmd_vel_ = node.advertise<geometry_msgs::Twist>("cmd_vel", queue);
    const uint32_t size = static_cast<uint32_t>(std::max(queue, 1));
    if (private_node.param("compressed", false)) {
      // As image_transport names it: the raw topic's name (after remapping) + "/compressed".
      image_ = node.subscribe(node.resolveName("image") + "/compressed", size, &Node::on_compressed,
                              this);
    } else {
      image_ = node.subscribe("image", size, &Node::on_image, this);
    }
    if (use_odometry_) odometry_ = node.subscribe("odom", size, &Node::on_odometry, this);
    services_.push_back(private_node.advertiseService("start_exploring", &Node::start, this));
    services_.push_back(private_node.advertiseService("stop_exploring", &Node::stop, this));
    services_.push_back(private_node.advertiseService("save_map", &Node::save, this));
    services_.push_back(private_node.advertiseService("navigate", &Node::navigate, this));
    services_.push_back(
        private_node.advertiseService("stop_navigating", &Node::stop_navigating, this));
    if (private_node.param("explore", false)) session_->start_exploring();
    ROS_INFO_STREAM("omninav: listening on "
                    << image_.getTopic()
                    << (use_odometry_ ? " and " + odometry_.getTopic() : std::string()));
  }

  // What was skipped, logged when the node stops.
  void log_summary() const {
    ROS_INFO_STREAM("omninav: skipped " << skipped_ << " frames the session refused, "
                                        << undecodable_ << " that could not be decoded, " << failed_
                                        << " that failed");
  }

 private:
  void on_image(const sensor_msgs::ImageConstPtr& message) {
    io::RawImage raw{message->height, message->width, message->encoding, message->is_bigendian != 0,
                     message->step,   message->data};
    take(message->header.stamp.toSec(), image_.getTopic(),
         [&raw](const std::string& where) { return io::decode_raw_image(std::move(raw), where); });
  }

  void on_compressed(const sensor_msgs::CompressedImageConstPtr& message) {
    take(message->header.stamp.toSec(), image_.getTopic(), [&message](const std::string& where) {
      return io::decode_compressed_image(message->data, message->format, where);
    });
  }

  // Decodes an image message, skipping (and counting) one that cannot be; pushes the picture.
  template <typename Decode>
  void take(double stamp_s, const std::string& topic, Decode decode) {
    cv::Mat picture;
    try {
      picture = decode(topic);
    } catch (const std::exception& error) {
      ++undecodable_;
      warn_once("decode", std::string(error.what()) + " (skipped; further ones counted)");
      return;
    }
    guarded(topic, [&] { publish(session_->image(picture, stamp_s)); });
  }

  // Runs the session on a message: what it throws (exploring refused a frame) is logged once and
  // counted, never the end of the node; then the first skip of each kind is logged (the session
  // counts them all).
  template <typename Work>
  void guarded(const std::string& topic, Work work) {
    try {
      work();
    } catch (const std::exception& error) {
      ++failed_;
      warn_once("failed", topic + ": " + error.what() + " (further failures counted)");
    }
    const int skipped = session_->skipped();
    if (skipped > skipped_) {
      skipped_ = skipped;
      warn_once(session_->last_skip_reason(), image_.getTopic() + ": " +
                                                  session_->last_skip_message() +
                                                  " (skipped; further ones counted)");
    }
  }

  void on_odometry(const nav_msgs::OdometryConstPtr& message) {
    const geometry_msgs::Pose& pose = message->pose.pose;
    guarded(odometry_.getTopic(), [&] {
      std::vector<FrameOutputs> completed;
      if (!session_->odometry(
              {message->header.stamp.toSec(), pose.position.x, pose.position.y, pose.position.z,
               pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w},
              completed)) {
        warn_once("odometry", odometry_.getTopic() +
                                  ": a stamp not after the last one's (ignored; further ones too)");
      }
      publish(completed);
    });
  }

  void publish(const std::vector<FrameOutputs>& frames) {
    for (const FrameOutputs& frame : frames) {
      geometry_msgs::PoseWithCovarianceStamped heading;
      heading.header.stamp = ros::Time(frame.stamp_s);
      heading.header.frame_id = frame_id_;
      heading.pose.pose.orientation.z = std::sin(frame.heading_rad / 2.0);
      heading.pose.pose.orientation.w = std::cos(frame.heading_rad / 2.0);
      for (int i = 0; i < 5; ++i) heading.pose.covariance[i * 7] = kUnknownVariance;
      heading.pose.covariance[35] = frame.heading_sigma_rad * frame.heading_sigma_rad;
      heading_.publish(heading);
      if (frame.has_place) {
        place_.publish(labelled(kPlaceFields, {static_cast<double>(frame.place), frame.similarity,
                                               frame.dissimilarity_per_value, frame.probability,
                                               frame.confidence, frame.lost ? 1.0 : 0.0}));
      }
      if (frame.new_place) {
        std_msgs::UInt32 added;
        added.data = *frame.new_place;
        new_place_.publish(added);
      }
      if (frame.navigating) publish_navigation(frame);
    }
  }

  // The frame's command as a Twist (velocity_for), and where navigating stands.
  void publish_navigation(const FrameOutputs& frame) {
    const Velocity velocity = velocity_for(frame, max_linear_m_s_, max_angular_rad_s_);
    geometry_msgs::Twist twist;
    twist.linear.x = velocity.linear_m_s;
    twist.angular.z = velocity.angular_rad_s;
    cmd_vel_.publish(twist);
    navigation_.publish(
        labelled(kNavigationFields,
                 {static_cast<double>(frame.navigation_state), static_cast<double>(frame.step),
                  static_cast<double>(frame.acted_on), frame.turn_rad, frame.distance_m,
                  frame.homing ? 1.0 : 0.0, frame.navigation_lost ? 1.0 : 0.0}));
  }

  // A top speed parameter: in (0, `most`], else the node does not start.
  static double speed(ros::NodeHandle& private_node, const std::string& name, double fallback,
                      double most) {
    const double value = private_node.param(name, fallback);
    if (!(value > 0.0 && value <= most)) {
      throw std::runtime_error("~" + name + " is " + std::to_string(value) +
                               ", out of its range (0, " + std::to_string(most) + "]");
    }
    return value;
  }

  // Navigates to the panorama in the file ~goal_image names, read at the call.
  bool navigate(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    std::string goal;
    if (!use_odometry_) {
      // Without it every frame would be the navigator's next view, the last command counted as
      // carried out whole: a robot driving between frames does not do that (docs/ros.md).
      response.success = false;
      response.message = "navigating needs ~use_odometry";
      return true;
    }
    if (!ros::param::get("~goal_image", goal) || goal.empty()) {
      response.success = false;
      response.message = "set ~goal_image to the goal panorama's file first";
      return true;
    }
    try {
      const std::uint32_t place = session_->navigate_to(goal);
      response.success = true;
      response.message = "navigating to " + goal + ", place " + std::to_string(place);
      ROS_INFO_STREAM("omninav: " << response.message);
    } catch (const std::exception& error) {
      response.success = false;
      response.message = error.what();
      ROS_ERROR_STREAM("navigate: " << error.what());
    }
    return true;
  }

  // Stops navigating: the robot is told to stand still at once.
  bool stop_navigating(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    const bool was = session_->navigating();
    session_->stop_navigating();
    cmd_vel_.publish(geometry_msgs::Twist());
    response.success = true;
    response.message = was ? "stopped navigating" : "was not navigating";
    return true;
  }

  bool start(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    session_->start_exploring();
    response.success = true;
    response.message = "exploring: " + std::to_string(session_->place_count()) + " places";
    return true;
  }

  bool stop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    session_->stop_exploring();
    response.success = true;
    response.message = "stopped exploring: " + std::to_string(session_->place_count()) + " places";
    return true;
  }

  bool save(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    try {
      session_->save();
      response.success = true;
      response.message = "saved " + std::to_string(session_->place_count()) + " places";
    } catch (const std::exception& error) {
      response.success = false;
      response.message = error.what();
      ROS_ERROR_STREAM("save_map: " << error.what());
    }
    return true;
  }

  // Each kind of bad input is logged once; the session counts them.
  void warn_once(const std::string& kind, const std::string& message) {
    if (warned_.insert(kind).second) ROS_WARN_STREAM(message);
  }

  std::unique_ptr<RosSession> session_;
  std::string frame_id_;
  bool use_odometry_ = false;
  double max_linear_m_s_ = 0.0;
  double max_angular_rad_s_ = 0.0;
  ros::Publisher heading_, place_, new_place_, navigation_, cmd_vel_;
  ros::Subscriber image_, odometry_;
  std::vector<ros::ServiceServer> services_;
  std::set<std::string> warned_;
  int skipped_ = 0;
  int undecodable_ = 0;
  int failed_ = 0;
};

}  // namespace
}  // namespace omninav::ros_node

namespace {
volatile std::sig_atomic_t stop_requested = 0;
}

int main(int argc, char** argv) {
  // Ctrl-C (and roslaunch's SIGINT) ends the loop below rather than ROS at once, so that the
  // node can still log what it skipped.
  ros::init(argc, argv, "omninav", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, [](int) { stop_requested = 1; });
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  try {
    omninav::ros_node::Node adapter(node, private_node);
    while (ros::ok() && !stop_requested) {
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.1));
    }
    adapter.log_summary();
  } catch (const std::exception& error) {
    ROS_FATAL_STREAM("omninav: " << error.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}
