#!/usr/bin/python3
"""Listens to gridslam_node's outputs until SIGINT, then writes what it saw as JSON.

Usage: ros_node_check.py OUT.json [MAP_FRAME ODOM_FRAME]
  /map (nav_msgs/OccupancyGrid): count, size and occupied cells of the last one;
  /trajectory (nav_msgs/Path): count, poses of the last one;
  /tf: map -> odom transforms (count, first and last stamp).
Wall-clock waits only: under /use_sim_time the clock stops when a bag ends.
"""
import json
import sys
import threading
import time

import rospy
from nav_msgs.msg import OccupancyGrid, Path
from tf2_msgs.msg import TFMessage


def main():
    out = sys.argv[1]
    map_frame = sys.argv[2] if len(sys.argv) > 2 else "map"
    odom_frame = sys.argv[3] if len(sys.argv) > 3 else "odom"
    lock = threading.Lock()
    seen = {"maps": 0, "paths": 0, "map_to_odom": 0, "path_poses": 0}
    last = {"map": None, "first_tf": None, "last_tf": None}

    def on_map(msg):
        with lock:
            seen["maps"] += 1
            last["map"] = msg

    def on_path(msg):
        with lock:
            seen["paths"] += 1
            seen["path_poses"] = len(msg.poses)

    def on_tf(msg):
        with lock:
            for t in msg.transforms:
                if t.header.frame_id.lstrip("/") == map_frame and \
                        t.child_frame_id.lstrip("/") == odom_frame:
                    seen["map_to_odom"] += 1
                    stamp = t.header.stamp.to_sec()
                    last["first_tf"] = last["first_tf"] or stamp
                    last["last_tf"] = stamp

    rospy.init_node("gridslam_node_check", anonymous=True)
    rospy.Subscriber("map", OccupancyGrid, on_map, queue_size=2)
    rospy.Subscriber("trajectory", Path, on_path, queue_size=2)
    rospy.Subscriber("tf", TFMessage, on_tf, queue_size=1000)
    print("ros_node_check: listening", flush=True)
    while not rospy.is_shutdown():
        time.sleep(0.1)
    with lock:
        result = dict(seen)
        result["first_map_to_odom_stamp"] = last["first_tf"]
        result["last_map_to_odom_stamp"] = last["last_tf"]
        grid = last["map"]
        if grid is not None:
            result["map"] = {
                "frame_id": grid.header.frame_id,
                "width": grid.info.width,
                "height": grid.info.height,
                "resolution": grid.info.resolution,
                "occupied": sum(1 for v in grid.data if v == 100),
                "free": sum(1 for v in grid.data if v == 0),
            }
    with open(out, "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
