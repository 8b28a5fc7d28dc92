#include "gridslam_node.hpp"

#include <algorithm>
#include <string>

#include "ros_conversions.hpp"
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>

namespace gridslam::live {
namespace {

// A map -> odom at a scan's stamp more than this older than the newest one published is not sent:
// TF listeners (tf2's default cache: 10 s) would drop it as data from the past. Happens only
// while the mapping lags behind ROS time (a burst of loop closures during fast playback).
constexpr std::int64_t kTfLagWindowNs = 5'000'000'000;

// Raises `newest` to `stamp`; returns the previous value.
std::int64_t RaiseTo(std::atomic<std::int64_t>& newest, std::int64_t stamp) {
  std::int64_t previous = newest.load();
  while (previous < stamp && !newest.compare_exchange_weak(previous, stamp)) {
  }
  return previous;
}

}  // namespace

GridslamNode::GridslamNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
    : nh_(nh), private_nh_(private_nh) {}

GridslamNode::~GridslamNode() {
  tf_subscriber_.reset();
  scan_sub_.shutdown();
  odom_sub_.shutdown();
  tf_timer_.stop();
  core_.reset();
}

bool GridslamNode::Start() {
  std::string error;
  if (!ReadNodeParams(private_nh_, &params_, &error)) {
    ROS_FATAL("gridslam_node: %s", error.c_str());
    return false;
  }
  params_.map_frame = StripSlash(params_.map_frame);
  params_.odom_frame = StripSlash(params_.odom_frame);
  params_.base_frame = StripSlash(params_.base_frame);
  CoreCallbacks callbacks;
  callbacks.on_pose = [this](std::int64_t stamp_ns, const PlanarPose& pose) {
    PublishPose(stamp_ns, pose);
  };
  callbacks.on_map = [this](const GridOutput& map, const std::vector<StampedPose>& path) {
    PublishMap(map, path);
  };
  // Publishers first: the core's thread may call back as soon as scans arrive.
  map_pub_ = nh_.advertise<nav_msgs::OccupancyGrid>("map", 1, /*latch=*/true);
  path_pub_ = nh_.advertise<nav_msgs::Path>("trajectory", 1, /*latch=*/true);
  core_ = MappingCore::Create(params_.core, std::move(callbacks), &error);
  if (!core_) {
    ROS_FATAL("gridslam_node: configuration: %s", error.c_str());
    return false;
  }
  TfSubscriber::Callback on_dynamic;
  if (params_.core.odometry == OdometrySource::kTf) {
    on_dynamic = [this](const geometry_msgs::TransformStamped& t) { OnTfOdometry(t); };
  }
  tf_subscriber_ = std::make_unique<TfSubscriber>(&tf_buffer_, params_.map_frame, ChildFrame(),
                                                  std::move(on_dynamic));
  scan_sub_ = nh_.subscribe(params_.scan_topic, static_cast<std::uint32_t>(params_.scan_queue_size),
                            &GridslamNode::OnScan, this);
  const char* odometry = "TF";
  if (params_.core.odometry == OdometrySource::kTopic) {
    odom_sub_ = nh_.subscribe(params_.odom_topic, 1000, &GridslamNode::OnOdometry, this);
    odometry = "topic";
  } else if (params_.core.odometry == OdometrySource::kNone) {
    odometry = "none (scan matching alone)";
  }
  save_map_srv_ = private_nh_.advertiseService("save_map", &GridslamNode::OnSaveMap, this);
  finish_srv_ = private_nh_.advertiseService("finish", &GridslamNode::OnFinish, this);
  if (params_.tf_publish_period > 0.0) {
    tf_timer_ = nh_.createWallTimer(ros::WallDuration(params_.tf_publish_period),
                                    &GridslamNode::OnTfTimer, this);
  }
  ROS_INFO("gridslam_node: scans on %s, odometry %s%s%s, publishing %s -> %s; config %s",
           scan_sub_.getTopic().c_str(), odometry,
           params_.core.odometry == OdometrySource::kTopic ? " " : "",
           params_.core.odometry == OdometrySource::kTopic ? odom_sub_.getTopic().c_str() : "",
           params_.map_frame.c_str(), ChildFrame().c_str(),
           params_.core.config_path.empty() ? "(defaults)" : params_.core.config_path.c_str());
  return true;
}

const std::string& GridslamNode::ChildFrame() const {
  return params_.core.odometry == OdometrySource::kNone ? params_.base_frame : params_.odom_frame;
}

std::optional<Transform3D> GridslamNode::WaitForTransform(const std::string& target,
                                                          const std::string& source,
                                                          const ros::Time& stamp, double timeout) {
  // Wall time, not ROS time: under a paused or fast /clock a ROS-time timeout means nothing.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!tf_buffer_.canTransform(target, source, stamp)) {
    if (ros::WallTime::now() >= deadline || !ros::ok()) {
      return std::nullopt;
    }
    ros::WallDuration(0.001).sleep();
  }
  try {
    return ToTransform3D(tf_buffer_.lookupTransform(target, source, stamp).transform);
  } catch (const tf2::TransformException& e) {
    ROS_WARN_THROTTLE(5.0, "gridslam_node: %s", e.what());
    return std::nullopt;
  }
}

void GridslamNode::OnTfOdometry(const geometry_msgs::TransformStamped& t) {
  if (t.header.frame_id != params_.odom_frame) {
    return;
  }
  const std::string& child = t.child_frame_id;
  OdometryInput sample{ToNanoseconds(t.header.stamp), ToTransform3D(t.transform), std::nullopt};
  if (child != params_.base_frame) {
    auto chain = odometry_chains_.find(child);
    if (chain == odometry_chains_.end()) {
      std::optional<Transform3D> T_child_base;
      try {  // fixed transforms only: /tf_static has arrived by the time odometry flows
        T_child_base = ToTransform3D(
            tf_buffer_.lookupTransform(child, params_.base_frame, ros::Time(0)).transform);
        ROS_INFO("gridslam_node: TF odometry %s -> %s, completed to %s by fixed transforms",
                 params_.odom_frame.c_str(), child.c_str(), params_.base_frame.c_str());
      } catch (const tf2::TransformException& /*e*/) {
        // not a frame on the way to the base
      }
      chain = odometry_chains_.emplace(child, T_child_base).first;
    }
    if (!chain->second) {
      return;
    }
    sample.T_child_base = chain->second;
  }
  core_->AddOdometry(sample);
}

Transform3D GridslamNode::Mounting(const std::string& laser_frame) {
  const auto known = mountings_.find(laser_frame);
  if (known != mountings_.end()) {
    return known->second;
  }
  Transform3D T_base_laser;
  if (laser_frame != params_.base_frame) {
    if (auto found = WaitForTransform(params_.base_frame, laser_frame, ros::Time(0),
                                      params_.mounting_timeout)) {
      T_base_laser = *found;
      ROS_INFO("gridslam_node: laser mounting %s -> %s: x %.4f m, y %.4f m",
               params_.base_frame.c_str(), laser_frame.c_str(), T_base_laser.x, T_base_laser.y);
    } else {
      ROS_WARN("gridslam_node: no TF %s -> %s after %.1f s: laser assumed at the robot centre",
               params_.base_frame.c_str(), laser_frame.c_str(), params_.mounting_timeout);
    }
  }
  mountings_[laser_frame] = T_base_laser;
  return T_base_laser;
}

void GridslamNode::CountLostScans(std::uint32_t seq) {
  const long lost = sequence_gaps_.Add(seq);
  if (lost > scans_lost_) {
    scans_lost_ = lost;
    ROS_WARN_THROTTLE(5.0,
                      "gridslam_node: %ld scans lost before the node saw them (gaps in "
                      "header.seq): a queue overflowed (raise ~scan_queue_size; playing a bag "
                      "fast: rosbag play --queue)",
                      lost);
  }
}

void GridslamNode::OnScan(const sensor_msgs::LaserScan::ConstPtr& msg) {
  CountLostScans(msg->header.seq);
  ScanInput scan = ToScanInput(*msg);
  scan.T_base_laser = Mounting(StripSlash(msg->header.frame_id));
  core_->AddScan(std::move(scan));
}

void GridslamNode::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  core_->AddOdometry(
      {ToNanoseconds(msg->header.stamp), ToTransform3D(msg->pose.pose), std::nullopt});
}

void GridslamNode::OnTfTimer(const ros::WallTimerEvent& /*event*/) {
  PlanarPose pose;
  const ros::Time now = ros::Time::now();
  if (now.isZero() || !core_->LatestPose(&pose)) {  // no /clock yet, or nothing mapped yet
    return;
  }
  const ros::Time stamp = now + ros::Duration(params_.transform_tolerance);
  if (RaiseTo(newest_tf_ns_, ToNanoseconds(stamp)) >= ToNanoseconds(stamp)) {
    return;  // the clock stands still (paused or ended playback): nothing new to say
  }
  tf_broadcaster_.sendTransform(ToTransformStamped(pose, params_.map_frame, ChildFrame(), stamp));
}

void GridslamNode::PublishPose(std::int64_t stamp_ns, const PlanarPose& T_map_odom) {
  if (RaiseTo(newest_tf_ns_, stamp_ns) - kTfLagWindowNs < stamp_ns) {
    tf_broadcaster_.sendTransform(
        ToTransformStamped(T_map_odom, params_.map_frame, ChildFrame(), ToRosTime(stamp_ns)));
  }
  const CoreProgress s = core_->Progress();
  if (s.scans_mapped % 1000 == 0) {
    ROS_INFO(
        "gridslam_node: %ld scans mapped (%ld queued, %ld dropped, %ld lost, %ld with clamped "
        "odometry), %ld key maps, %ld loop closures",
        s.scans_mapped, s.scans_queued, s.scans_dropped, scans_lost_.load(),
        s.scans_without_odometry, s.key_maps, s.loop_closures);
  }
}

void GridslamNode::PublishMap(const GridOutput& map, const std::vector<StampedPose>& path) {
  map_pub_.publish(ToOccupancyGrid(map, params_.map_frame));
  path_pub_.publish(ToPath(path, params_.map_frame));
}

bool GridslamNode::OnSaveMap(std_srvs::Trigger::Request& /*request*/,
                             std_srvs::Trigger::Response& response) {
  std::string message;
  response.success = core_->SaveMap(OutputDir(private_nh_, params_), &message) ? 1 : 0;
  // The count lets a caller (tests/ros_node_test.sh) tell that every scan it sent has arrived.
  response.message =
      std::to_string(core_->Progress().scans_received) + " scans received; " + message;
  ROS_INFO("gridslam_node: save_map: %s", response.message.c_str());
  return true;
}

bool GridslamNode::OnFinish(std_srvs::Trigger::Request& /*request*/,
                            std_srvs::Trigger::Response& response) {
  std::string message;
  response.success = core_->Finish(OutputDir(private_nh_, params_), &message) ? 1 : 0;
  response.message = message;
  const CoreProgress s = core_->Progress();
  ROS_INFO(
      "gridslam_node: finish: %s (%ld scans received, %ld mapped, %ld dropped, %ld lost, %ld "
      "with clamped odometry; %ld key maps, %ld loop closures)",
      message.c_str(), s.scans_received, s.scans_mapped, s.scans_dropped, scans_lost_.load(),
      s.scans_without_odometry, s.key_maps, s.loop_closures);
  return true;
}

}  // namespace gridslam::live
