#!/usr/bin/env bash
# End-to-end test of gridslam_node (issue 14; docs/ros.md "Mapping live"): a private roscore,
# the node, `rosbag play --clock` of a shared bag at GRIDSLAM_ROS_RATE (default 20) times real
# time; checks that /map, /trajectory and map -> odom were published, that ~save_map writes a
# map_server map and ~finish the outputs of `gridslam map`, and that the node's trajectory scores
# the relation error of `gridslam map` on the same messages within 5 %. Stops everything it
# started (by the PIDs it recorded). Skipped (exit 77) without the shared bags or ROS's tools.
#
# Bags: intel.orig.bag (TF odometry) and fr079.orig.bag (/odom topic, laser mounted 0.04 m ahead
# in /tf_static, laser-frame relations).
#
# Why the intel reference is `gridslam map intel.mcap --set log.repair_timestamps=false`: intel's
# stamps are broken (docs/ros.md "Timestamps"); `gridslam map intel.orig.bag` repairs them, which
# needs the bag's storage order. `rosbag play` publishes in log-time order instead, and a live node
# sees the stamps as they are. intel.mcap holds the same messages in log-time order: the CLI on it
# without the repair maps exactly the stream the node receives. The CLI on intel.orig.bag with the
# repair is printed beside it.
#
# Usage: tests/ros_node_test.sh GRIDSLAM_NODE GRIDSLAM
set -euo pipefail
node_bin="$1"
cli_bin="$2"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="${GRIDSLAM_DATA:-$root/../shared/data}"
rate="${GRIDSLAM_ROS_RATE:-20}"
fail() {
  echo "ros_node_test: FAIL: $*"
  exit 1
}
skip() {
  echo "ros_node_test: skipped: $*"
  exit 77
}

for f in bags/intel.orig.bag bags/intel.mcap bags/fr079.orig.bag relations/intel.relations \
  relations/fr079.relations; do
  [ -e "$data/$f" ] || skip "no $data/$f (set GRIDSLAM_DATA)"
done
for tool in roscore rosbag rosservice rosparam; do
  command -v "$tool" > /dev/null || skip "no $tool (scripts/setup installs ROS's tools)"
done

tmp=$(mktemp -d)
# shellcheck source=../scripts/lib/ros_session.sh
source "$root/scripts/lib/ros_session.sh"
cleanup() {
  ros_session_stop
  if [ "${GRIDSLAM_KEEP_TMP:-0}" = 1 ]; then echo "ros_node_test: kept $tmp"; else rm -rf "$tmp"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# metric NAME "eval output": the value of NAME=...
metric() { sed -n "s/.*$1=\([^ ]*\).*/\1/p" <<< "$2" | head -n 1; }

# within_5_percent NODE_VALUE CLI_VALUE
within_5_percent() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= 1.05 * b && a >= 0.95 * b) }'; }

show_log() {
  echo "---- $1 (last 30 lines)"
  tail -n 30 "$1" | grep -v "TF_REPEATED_DATA\|buffer_core.cpp" || true
}

# map_bag NAME BAG RELATIONS CLI_REFERENCE_DIR [ros params...]
map_bag() {
  local name="$1" bag="$2" relations="$3" reference="$4"
  shift 4
  local dir="$tmp/$name"
  mkdir -p "$dir"
  local info scans duration
  info=$("$cli_bin" info "$bag" 2> /dev/null)
  scans=$(sed -n 's/^  scans: \([0-9]*\) over.*/\1/p' <<< "$info")
  duration=$(sed -n 's/^  duration: \([0-9]*\).*/\1/p' <<< "$info")
  [ -n "$scans" ] || fail "$name: cannot count the scans of $bag"

  # Nothing may depend on the machine's load (ctest runs other tests beside this one): generous
  # waits for the odometry after a scan's stamp (wall time; intel's odometry pauses for up to
  # 3.1 s of bag time near its end) and queues that never overflow (rosbag play's --queue too).
  ros_session_spawn "$dir/node.log" "$node_bin" _output_dir:="$dir/out" \
    _map_publish_period:=30 _tf_timeout:=10.0 _odom_timeout:=10.0 _scan_queue_size:=100000 "$@"
  local node_pid="$ROS_SESSION_PID"
  ros_session_wait_service /gridslam_node/finish 60 ||
    { show_log "$dir/node.log"; fail "$name: gridslam_node's services did not appear within 60 s"; }
  ros_session_spawn "$dir/check.log" "$ROS_SESSION_PYTHON" "$root/tests/ros_node_check.py" \
    "$dir/check.json"
  local check_pid="$ROS_SESSION_PID"
  for _ in $(seq 1 60); do
    grep -q "listening" "$dir/check.log" 2> /dev/null && break
    sleep 0.5
  done
  grep -q "listening" "$dir/check.log" || { show_log "$dir/check.log"; fail "$name: checker"; }

  echo "ros_node_test: $name: rosbag play -r $rate $(basename "$bag") ($scans scans)"
  local start=$SECONDS
  # every scan must reach the node (scripts/lib/ros_session.sh); a failure's cleanup stops the
  # player
  ros_session_play_all "$dir/play.log" "$bag" "$rate" "$scans" $(( ${duration:-0} / rate )) ||
    fail "$name: not every scan reached the node"
  echo "ros_node_test: $name: played in $((SECONDS - start)) s, every scan received"
  [ -s "$dir/out/map.pgm" ] && grep -q "^image: map.pgm" "$dir/out/map.yaml" ||
    fail "$name: ~save_map wrote no map.pgm + map.yaml"
  reply=$(timeout 300 rosservice call /gridslam_node/finish 2>&1) ||
    { echo "$reply"; show_log "$dir/node.log"; fail "$name: ~finish call"; }
  grep -q "success: True" <<< "$reply" || { echo "$reply"; fail "$name: ~finish failed"; }
  for f in map.pgm map.yaml map.png map_graph.png trajectory.txt trajectory.tum graph.g2o \
    config.yaml report.json; do
    [ -s "$dir/out/$f" ] || fail "$name: ~finish wrote no $f"
  done
  sleep 2  # the final map reaches the checker
  ros_session_end "$check_pid"
  [ -s "$dir/check.json" ] || { show_log "$dir/check.log"; fail "$name: the checker wrote nothing"; }
  ros_session_end "$node_pid"

  # What was published.
  local last_stamp
  last_stamp=$(tail -n 1 "$dir/out/trajectory.txt" | cut -d ' ' -f 1)
  "$ROS_SESSION_PYTHON" - "$dir/check.json" "$dir/out/report.json" "$scans" "$last_stamp" \
    << 'PY' ||
import json, sys
check = json.load(open(sys.argv[1]))
report = json.load(open(sys.argv[2]))
scans = int(sys.argv[3])
last_scan = float(sys.argv[4])
problems = []
if check["maps"] < 2 or "map" not in check:
    problems.append("/map received %d times" % check["maps"])
elif check["map"]["occupied"] < 1000 or check["map"]["free"] < 10 * check["map"]["occupied"]:
    problems.append("the last /map has %d occupied and %d free cells" %
                    (check["map"]["occupied"], check["map"]["free"]))
if check["paths"] < 2 or check["path_poses"] != scans:
    problems.append("/trajectory received %d times, the last with %d of %d poses" %
                    (check["paths"], check["path_poses"], scans))
# One per scan (but while the mapping lags far behind) and every ~tf_publish_period.
if check["map_to_odom"] < scans // 2 or (check["last_map_to_odom_stamp"] or 0) < last_scan:
    problems.append("map -> odom published %d times for %d scans, the last at %s (last scan %f)" %
                    (check["map_to_odom"], scans, check["last_map_to_odom_stamp"], last_scan))
if report["frames"] != scans:
    problems.append("the node mapped %d of the bag's %d scans (%s)" %
                    (report["frames"], scans, report["node"]))
print("ros_node_test: published: %d maps (last %dx%d, %d occupied cells), %d paths, "
      "%d map->odom transforms; mapped %d of %d scans" %
      (check["maps"], check.get("map", {}).get("width", 0), check.get("map", {}).get("height", 0),
       check.get("map", {}).get("occupied", 0), check["paths"], check["map_to_odom"],
       report["frames"], scans))
for p in problems:
    print("ros_node_test: FAIL: " + p)
sys.exit(1 if problems else 0)
PY
    { show_log "$dir/node.log"; fail "$name: outputs"; }

  # The relation error against the CLI's.
  local node_eval cli_eval
  node_eval=$("$cli_bin" eval "$relations" "$dir/out/trajectory.txt" 2> /dev/null) ||
    fail "$name: gridslam eval of the node's trajectory"
  cli_eval=$("$cli_bin" eval "$relations" "$reference/trajectory.txt" 2> /dev/null) ||
    fail "$name: gridslam eval of the CLI's trajectory"
  local nt ct nr cr
  nt=$(metric translation_mean "$node_eval")
  ct=$(metric translation_mean "$cli_eval")
  nr=$(metric rotation_mean_deg "$node_eval")
  cr=$(metric rotation_mean_deg "$cli_eval")
  echo "ros_node_test: $name: relation error node $nt m / $nr deg, gridslam map $ct m / $cr deg"
  within_5_percent "$nt" "$ct" || fail "$name: node's translation error $nt m not within 5 % of $ct m"
  within_5_percent "$nr" "$cr" || fail "$name: node's rotation error $nr deg not within 5 % of $cr"
}

echo "ros_node_test: gridslam map on the same bags"
"$cli_bin" --set log.repair_timestamps=false map "$data/bags/intel.mcap" -o "$tmp/cli_intel" \
  2> "$tmp/cli_intel.log" || { cat "$tmp/cli_intel.log"; fail "gridslam map intel.mcap"; }
"$cli_bin" map "$data/bags/intel.orig.bag" -o "$tmp/cli_intel_repaired" 2> /dev/null ||
  fail "gridslam map intel.orig.bag"
repaired=$("$cli_bin" eval "$data/relations/intel.relations" \
  "$tmp/cli_intel_repaired/trajectory.txt" 2> /dev/null)
echo "ros_node_test: for reference: gridslam map intel.orig.bag (storage order, stamps repaired):" \
  "$(metric translation_mean "$repaired") m / $(metric rotation_mean_deg "$repaired") deg"
"$cli_bin" --set eval.trajectory_frame=laser map "$data/bags/fr079.orig.bag" -o "$tmp/cli_fr079" \
  2> "$tmp/cli_fr079.log" || { cat "$tmp/cli_fr079.log"; fail "gridslam map fr079.orig.bag"; }

ros_session_start "$tmp" || fail "roscore"
map_bag intel "$data/bags/intel.orig.bag" "$data/relations/intel.relations" "$tmp/cli_intel"
map_bag fr079 "$data/bags/fr079.orig.bag" "$data/relations/fr079.relations" "$tmp/cli_fr079" \
  _odom_topic:=odom _set:=eval.trajectory_frame=laser
echo "ros_node_test: ok"
