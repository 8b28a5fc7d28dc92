#include "tf_subscriber.hpp"

#include <utility>

#include "ros_conversions.hpp"

namespace gridslam::live {
namespace {

constexpr std::uint32_t kTfQueue = 100'000;  // messages: minutes of /tf at 20x playback

}  // namespace

TfSubscriber::TfSubscriber(tf2::BufferCore* buffer, std::string skip_parent, std::string skip_child,
                           Callback on_dynamic)
    : buffer_(buffer),
      skip_parent_(std::move(skip_parent)),
      skip_child_(std::move(skip_child)),
      on_dynamic_(std::move(on_dynamic)) {
  nh_.setCallbackQueue(&queue_);
  tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>(
      "/tf", kTfQueue,
      [this](const tf2_msgs::TFMessage::ConstPtr& msg) { Store(msg, /*is_static=*/false); },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  tf_static_sub_ = nh_.subscribe<tf2_msgs::TFMessage>(
      "/tf_static", kTfQueue,
      [this](const tf2_msgs::TFMessage::ConstPtr& msg) { Store(msg, /*is_static=*/true); });
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

TfSubscriber::~TfSubscriber() {
  spinner_->stop();
  tf_sub_.shutdown();
  tf_static_sub_.shutdown();
}

void TfSubscriber::Store(const tf2_msgs::TFMessage::ConstPtr& msg, bool is_static) {
  const ros::Time now = ros::Time::now();
  if (now + ros::Duration(1.0) < last_now_) {
    ROS_WARN("gridslam_node: ROS time jumped back %.1f s: TF buffer cleared",
             (last_now_ - now).toSec());
    buffer_->clear();
  }
  last_now_ = now;
  for (geometry_msgs::TransformStamped t : msg->transforms) {
    t.header.frame_id = StripSlash(t.header.frame_id);
    t.child_frame_id = StripSlash(t.child_frame_id);
    if (t.header.frame_id == skip_parent_ && t.child_frame_id == skip_child_) {
      continue;
    }
    try {
      buffer_->setTransform(t, "tf", is_static);
    } catch (const tf2::TransformException& e) {
      ROS_WARN_THROTTLE(5.0, "gridslam_node: transform refused by tf2: %s", e.what());
    }
    if (!is_static && on_dynamic_) {
      on_dynamic_(t);
    }
  }
}

}  // namespace gridslam::live
