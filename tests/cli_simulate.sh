#!/usr/bin/env bash
# CLI test of `gridslam simulate` (issue 3): the files it promises, byte-identical output for a
# seed, ground truth scoring zero against its relations, odometry scoring clearly above zero,
# several robots with between-robot relations, PNG floor plans with a waypoints file, and exit
# code 2 on bad input.
set -euo pipefail
bin="$1"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metric() {  # metric NAME "eval output": the value of NAME=...
  echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | head -1
}

"$bin" simulate --world office --duration 120 --seed 3 -o "$tmp/a" > /dev/null
"$bin" simulate --world office --duration 120 --seed 3 -o "$tmp/b" > /dev/null
"$bin" simulate --world office --duration 120 --seed 4 -o "$tmp/c" > /dev/null
for f in robot_0.clf robot_0.gt.txt robot_0.relations world.png world.yaml overview.png config.yaml; do
  [ -s "$tmp/a/$f" ] || { echo "missing $f"; exit 1; }
  cmp "$tmp/a/$f" "$tmp/b/$f"
done
if cmp -s "$tmp/a/robot_0.clf" "$tmp/c/robot_0.clf"; then echo "seed has no effect"; exit 1; fi
grep -q '^RAWLASER1 0 -1.570796 3.141593 0.017453 30.000000 ' "$tmp/a/robot_0.clf"
grep -q '^ODOM 0.000000 0.000000 0.000000 ' "$tmp/a/robot_0.clf"
grep -q '^image: world.png$' "$tmp/a/world.yaml"

truth=$("$bin" eval "$tmp/a/robot_0.relations" "$tmp/a/robot_0.gt.txt")
[ "$(metric translation_mean "$truth")" = "0.000000" ] || { echo "truth: $truth"; exit 1; }
[ "$(metric rotation_mean_deg "$truth")" = "0.000000" ] || { echo "truth: $truth"; exit 1; }
[ "$(metric missing "$truth")" = "0" ] || { echo "truth: $truth"; exit 1; }
"$bin" odometry "$tmp/a/robot_0.clf" -o "$tmp/a/odometry.txt" 2> /dev/null
odometry=$("$bin" eval "$tmp/a/robot_0.relations" "$tmp/a/odometry.txt")
awk -v t="$(metric translation_mean "$odometry")" 'BEGIN { exit !(t > 0.005) }' ||
  { echo "odometry: $odometry"; exit 1; }

"$bin" simulate --world ambiguous --robots 3 --duration 250 -o "$tmp/m" > /dev/null
for f in robot_0.clf robot_1.clf robot_2.clf between.relations within.relations index.txt; do
  [ -s "$tmp/m/$f" ] || { echo "missing $f"; exit 1; }
done
[ "$(cut -d' ' -f1 "$tmp/m/index.txt" | sort | uniq -d | wc -l)" = "0" ]
[ "$(wc -l < "$tmp/m/index.txt")" = "$(cat "$tmp"/m/robot_*.gt.txt | wc -l)" ]
cat "$tmp"/m/robot_*.gt.txt > "$tmp/m/all.gt.txt"
between=$("$bin" eval "$tmp/m/between.relations" "$tmp/m/all.gt.txt")
[ "$(metric translation_mean "$between")" = "0.000000" ] || { echo "between: $between"; exit 1; }
[ "$(metric relations "$between")" -gt 10 ] || { echo "between: $between"; exit 1; }

"$bin" simulate --world "$root/data/worlds/example.png" --resolution 0.1 \
  --route "$root/data/worlds/example_route.txt" -o "$tmp/png" > /dev/null
[ -s "$tmp/png/robot_0.clf" ]

set +e
"$bin" simulate --world nowhere -o "$tmp/x" 2> /dev/null; unknown=$?
"$bin" simulate --world "$root/data/worlds/example.png" -o "$tmp/x" 2> /dev/null; no_route=$?
"$bin" simulate --world office --robots 5 -o "$tmp/x" 2> /dev/null; too_many=$?
set -e
[ "$unknown" -eq 2 ] && [ "$no_route" -eq 2 ] && [ "$too_many" -eq 2 ] ||
  { echo "exit codes $unknown $no_route $too_many"; exit 1; }
echo "cli_simulate: ok"
