#!/usr/bin/env bash
# CLI test of `gridslam map --align-map`: a simulated office (walls along the world axes) recorded
# by a robot whose start is rotated by an unknown angle (`gridslam split -n 1`: 43 degrees for seed
# 4) gives a map tilted by that angle; --align-map rotates the map frame so that the walls lie
# along its axes again: the robot's heading then equals its true heading modulo 90 degrees.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "cli_align_map: $*"; exit 1; }
"$bin" simulate --world office --seed 1 --duration 60 -o "$tmp/sim" > /dev/null 2>&1
"$bin" split "$tmp/sim/robot_0.clf" -n 1 --seed 4 -o "$tmp/split" > /dev/null 2>&1
"$bin" map "$tmp/split/robot_0.clf" -o "$tmp/tilted" 2> /dev/null
"$bin" map "$tmp/split/robot_0.clf" --align-map -o "$tmp/aligned" 2> /dev/null
# |heading - true heading| folded modulo 90 degrees, in degrees, at the first scan.
offset() {
  awk 'NR == FNR { if (FNR == 1) truth = $4; next }
       FNR == 1 { pi = atan2(0, -1); q = pi / 2; d = $4 - truth;
                  d = d - q * int(d / q + (d >= 0 ? 0.5 : -0.5));
                  printf "%.3f\n", (d < 0 ? -d : d) * 180 / pi }' "$tmp/sim/robot_0.gt.txt" "$1"
}
tilted=$(offset "$tmp/tilted/trajectory.txt")
aligned=$(offset "$tmp/aligned/trajectory.txt")
awk -v t="$tilted" 'BEGIN { exit !(t > 10) }' || fail "the test's map is not tilted ($tilted deg)"
awk -v a="$aligned" 'BEGIN { exit !(a < 0.5) }' || fail "aligned map off by $aligned deg"
grep -q '"map_rotation_rad"' "$tmp/aligned/report.json" || fail "no map_rotation_rad in report.json"
grep -q '"map_rotation_rad"' "$tmp/tilted/report.json" && fail "map_rotation_rad without --align-map"
# Relative quantities do not change: the same relation errors either way.
"$bin" eval "$tmp/sim/robot_0.relations" "$tmp/tilted/trajectory.txt" | head -1 > "$tmp/e1.txt"
"$bin" eval "$tmp/sim/robot_0.relations" "$tmp/aligned/trajectory.txt" | head -1 > "$tmp/e2.txt"
cmp -s "$tmp/e1.txt" "$tmp/e2.txt" || { cat "$tmp/e1.txt" "$tmp/e2.txt"; fail "relation errors changed"; }
echo "cli_align_map: ok (tilted $tilted deg, aligned $aligned deg)"
