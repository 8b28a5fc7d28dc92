# shellcheck shell=bash
# A private ROS 1 graph for scripts and tests (sourced by scripts/ros_demo and
# tests/ros_node_test.sh): its own roscore on 127.0.0.1 and a free port, its own ROS_HOME and
# ROS_LOG_DIR, /use_sim_time on (bags are played with --clock). Every process it starts runs in a
# process group of its own; ros_session_stop ends exactly those groups, by the PIDs it recorded.
#
#   ros_session_start DIR               roscore; logs and ROS_HOME under DIR
#   ros_session_spawn LOG CMD...        CMD in the background, output to LOG; sets ROS_SESSION_PID
#   ros_session_wait_service NAME SECS  until the service exists (1 on timeout)
#   ros_session_play_all LOG BAG RATE SCANS SECS
#                                       plays BAG until gridslam_node has every one of its SCANS
#                                       scans (1, with the reason, if not within SECS s)
#   ros_session_stop                    SIGINT, then SIGKILL after 10 s, to everything started

ROS_SESSION_PIDS=()
ROS_SESSION_PID=""
ROS_SESSION_PYTHON=/usr/bin/python3  # Debian's ROS Python modules live in the system Python

ros_session_spawn() {
  local log="$1"
  shift
  setsid "$@" > "$log" 2>&1 < /dev/null &
  ROS_SESSION_PID=$!
  ROS_SESSION_PIDS+=("$ROS_SESSION_PID")
}

ros_session_start() {
  local dir="$1"
  mkdir -p "$dir/ros_home" "$dir/ros_log"
  local port
  port=$("$ROS_SESSION_PYTHON" -c \
    'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI="http://127.0.0.1:$port" ROS_HOSTNAME=127.0.0.1 ROS_IP=127.0.0.1
  export ROS_HOME="$dir/ros_home" ROS_LOG_DIR="$dir/ros_log"
  ros_session_spawn "$dir/roscore.log" roscore -p "$port"
  local roscore_pid="$ROS_SESSION_PID"
  for _ in $(seq 1 120); do
    if timeout 10 rosparam get /run_id > /dev/null 2>&1; then
      timeout 10 rosparam set /use_sim_time true
      echo "ros_session: roscore (pid $roscore_pid) on $ROS_MASTER_URI, logs in $dir"
      return 0
    fi
    if ! kill -0 "$roscore_pid" 2> /dev/null; then
      echo "ros_session: roscore exited:"
      tail -n 20 "$dir/roscore.log"
      return 1
    fi
    sleep 0.5
  done
  echo "ros_session: roscore did not answer on $ROS_MASTER_URI within 60 s"
  return 1
}

ros_session_wait_service() {
  local name="$1" seconds="$2"
  local end=$((SECONDS + seconds))
  while [ "$SECONDS" -lt "$end" ]; do
    if timeout 10 rosservice list 2> /dev/null | grep -qx "$name"; then
      return 0
    fi
    sleep 0.5
  done
  return 1
}

# Every scan must reach the node, however loaded the machine is: the player waits 5 s after
# advertising a topic (-d; its default 0.2 s lost the bag's first scans to a subscriber that
# connected late), and stays alive after the bag's end (-k: a player that exits drops what its
# queue still holds for a subscriber that fell behind). The node has them all once ~save_map
# reports as many scans received as the bag holds ("N scans received; ..."); the player is
# stopped then. Polled from the bag's playing time (SECS = its duration / RATE) on, for at most
# 300 s more. Sets ROS_SESSION_RECEIVED to the last count read.
ros_session_play_all() {
  local log="$1" bag="$2" rate="$3" scans="$4" playing="$5"
  ros_session_spawn "$log" rosbag play -k -d 5 --clock -q --queue=100000 -r "$rate" "$bag"
  local play_pid="$ROS_SESSION_PID" start=$SECONDS reply
  ROS_SESSION_RECEIVED=""
  sleep "$playing"
  while :; do
    reply=$(timeout 120 rosservice call /gridslam_node/save_map 2>&1) ||
      { echo "$reply"; echo "ros_session: ~save_map call failed"; return 1; }
    grep -q "success: True" <<< "$reply" ||
      { echo "$reply"; echo "ros_session: ~save_map failed"; return 1; }
    # rosservice may fold a long message, with backslashes
    ROS_SESSION_RECEIVED=$(tr -d '\\' <<< "$reply" | tr -s ' \n' '  ' |
      sed -n 's/.*message: "\([0-9]*\) scans received;.*/\1/p')
    [ "$ROS_SESSION_RECEIVED" = "$scans" ] && break
    if ! kill -0 "$play_pid" 2> /dev/null; then
      tail -n 20 "$log"
      echo "ros_session: rosbag play exited ($ROS_SESSION_RECEIVED of $scans scans)"
      return 1
    fi
    if [ $((SECONDS - start)) -ge $((playing + 300)) ]; then
      echo "ros_session: the node received $ROS_SESSION_RECEIVED of the bag's $scans scans"
      return 1
    fi
    sleep 2
  done
  ros_session_end "$play_pid"
}

# Ends one recorded process group: SIGINT (ROS shuts down cleanly), SIGKILL after 10 s.
ros_session_end() {
  local pid="$1"
  if kill -0 "$pid" 2> /dev/null; then
    kill -INT -- "-$pid" 2> /dev/null || true
    for _ in $(seq 1 20); do
      kill -0 "$pid" 2> /dev/null || break
      sleep 0.5
    done
    kill -KILL -- "-$pid" 2> /dev/null || true
  fi
  wait "$pid" 2> /dev/null || true
}

ros_session_stop() {
  local i
  for ((i = ${#ROS_SESSION_PIDS[@]} - 1; i >= 0; i--)); do
    ros_session_end "${ROS_SESSION_PIDS[$i]}"
  done
  ROS_SESSION_PIDS=()
}
