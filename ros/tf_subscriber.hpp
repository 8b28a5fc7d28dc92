// Fills a tf2 buffer from /tf and /tf_static on a thread of its own (C++17 side of gridslam_node).
// Instead of tf2_ros::TransformListener, whose /tf queue of 100 messages overflows when a bag is
// played fast on a busy machine (a lost odometry sample changes the interpolated odometry, and the
// map): the queues here hold minutes of messages. Every dynamic transform is also handed to a
// callback (the node takes its odometry samples from it). The node's own map -> odom is neither
// stored nor handed on. As the listener does, the buffer is cleared when ROS time jumps back (a
// bag played again).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

namespace gridslam::live {

class TfSubscriber {
 public:
  using Callback = std::function<void(const geometry_msgs::TransformStamped&)>;
  /// Subscribes; `skip_parent` -> `skip_child` transforms (the node's own) are ignored.
  /// `on_dynamic` gets every /tf transform after it was stored (frame ids without '/'), on the
  /// subscriber's thread.
  TfSubscriber(tf2::BufferCore* buffer, std::string skip_parent, std::string skip_child,
               Callback on_dynamic);
  ~TfSubscriber();
  TfSubscriber(const TfSubscriber&) = delete;
  TfSubscriber& operator=(const TfSubscriber&) = delete;
  TfSubscriber(TfSubscriber&&) = delete;
  TfSubscriber& operator=(TfSubscriber&&) = delete;

 private:
  void Store(const tf2_msgs::TFMessage::ConstPtr& msg, bool is_static);

  tf2::BufferCore* buffer_;
  ros::Time last_now_;  ///< For clearing the buffer when the clock jumps back (a bag replayed).
  std::string skip_parent_;
  std::string skip_child_;
  Callback on_dynamic_;
  ros::CallbackQueue queue_;
  ros::NodeHandle nh_;
  ros::Subscriber tf_sub_;
  ros::Subscriber tf_static_sub_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

}  // namespace gridslam::live
