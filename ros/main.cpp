// gridslam_node: graph-SLAM on a live ROS 1 graph (docs/ros.md "Mapping live").
//   rosrun-style: gridslam_node _config:=my.yaml [_odom_topic:=odom] [scan:=/front/scan]
#include "gridslam_node.hpp"
#include <ros/ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "gridslam_node");
  gridslam::live::LogToStderr();
  gridslam::live::GridslamNode node{ros::NodeHandle(), ros::NodeHandle("~")};
  if (!node.Start()) {
    return 1;
  }
  ros::spin();  // one thread for every ROS callback; the mapping runs on the core's thread
  return 0;
}
