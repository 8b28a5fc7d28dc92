// gridslam_node (docs/ros.md "Mapping live"): subscribes to a sensor_msgs/LaserScan topic and the
// odometry (the TF odom -> base_link samples, or a nav_msgs/Odometry topic; the core interpolates
// them at each scan's stamp), looks up the laser mounting (base -> laser) in TF, and feeds the
// mapping core (mapping_core.hpp). Publishes /map (nav_msgs/OccupancyGrid, latched), /trajectory
// (nav_msgs/Path, latched) and the TF map -> odom (at each scan's stamp and every
// ~tf_publish_period); serves ~save_map and ~finish (std_srvs/Trigger). ROS callbacks run on one
// spinner thread, /tf on its own (tf_subscriber.hpp), the mapping on the core's.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "mapping_core.hpp"
#include "node_params.hpp"
#include "sequence_gaps.hpp"
#include "tf_subscriber.hpp"
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Trigger.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_ros/transform_broadcaster.h>

namespace gridslam::live {

class GridslamNode {
 public:
  GridslamNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);
  /// Stops the TF thread first (it feeds the core), then the core.
  ~GridslamNode();
  GridslamNode(const GridslamNode&) = delete;
  GridslamNode& operator=(const GridslamNode&) = delete;
  GridslamNode(GridslamNode&&) = delete;
  GridslamNode& operator=(GridslamNode&&) = delete;
  /// Reads the parameters and the gridslam configuration, subscribes and advertises. False (with
  /// a ROS_FATAL message) when the configuration is unusable.
  bool Start();

 private:
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& msg);
  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void OnTfTimer(const ros::WallTimerEvent& event);
  bool OnSaveMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool OnFinish(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  /// Core thread: publish map -> odom at a scan's stamp / a new map and trajectory.
  void PublishPose(std::int64_t stamp_ns, const PlanarPose& T_map_odom);
  void PublishMap(const GridOutput& map, const std::vector<StampedPose>& path);

  /// TF thread: an odom -> X transform becomes an odometry sample when X is the base frame or
  /// reaches it through fixed transforms (looked up once per X).
  void OnTfOdometry(const geometry_msgs::TransformStamped& t);
  /// target <- source at `stamp`, waiting up to `timeout` seconds of wall time for TF to have it.
  std::optional<Transform3D> WaitForTransform(const std::string& target, const std::string& source,
                                              const ros::Time& stamp, double timeout);
  /// base -> laser (static), looked up once per laser frame; identity with a warning if absent.
  Transform3D Mounting(const std::string& laser_frame);
  /// Counts the scans that never reached OnScan; warns when there are new ones.
  void CountLostScans(std::uint32_t seq);
  /// The child frame of the published transform: odom, or base without odometry.
  [[nodiscard]] const std::string& ChildFrame() const;

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  NodeParams params_;
  tf2::BufferCore tf_buffer_;  ///< For the mounting and fixed chains (static transforms).
  std::unique_ptr<TfSubscriber> tf_subscriber_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Subscriber scan_sub_;
  ros::Subscriber odom_sub_;
  ros::Publisher map_pub_;
  ros::Publisher path_pub_;
  ros::ServiceServer save_map_srv_;
  ros::ServiceServer finish_srv_;
  ros::WallTimer tf_timer_;
  std::map<std::string, Transform3D> mountings_;
  /// TF thread: per child of odom, T_child_base (nullopt: no fixed chain to the base frame).
  std::map<std::string, std::optional<Transform3D>> odometry_chains_;
  std::atomic<std::int64_t> newest_tf_ns_{0};  ///< Newest stamp of a published map -> odom.
  // Scans lost before OnScan (the subscriber queue overflowed), from the gaps in header.seq.
  SequenceGaps sequence_gaps_;
  std::atomic<long> scans_lost_{0};
  // Last, so that it goes first: its thread calls the publishers above until it is joined.
  std::unique_ptr<MappingCore> core_;
};

}  // namespace gridslam::live
