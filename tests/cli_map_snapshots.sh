#!/usr/bin/env bash
# CLI test of `gridslam map --snapshots S` (issue 13): a PNG every S seconds of log time in
# DIR/snapshots/, their count and cost in report.json, the same trajectory as without snapshots,
# and no snapshots folder when the log turns out bad (exit 2).
set -euo pipefail
bin="$1"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$bin" simulate --world office --duration 120 --seed 3 -o "$tmp/sim" > /dev/null
"$bin" map "$tmp/sim/robot_0.clf" -o "$tmp/plain" 2> /dev/null
"$bin" map "$tmp/sim/robot_0.clf" -o "$tmp/snap" --snapshots 20 2> /dev/null
cmp "$tmp/plain/trajectory.txt" "$tmp/snap/trajectory.txt"
count=$(ls "$tmp/snap/snapshots" | grep -c '^snapshot_[0-9]\{5\}\.png$')
[ "$count" -ge 4 ] && [ "$count" -le 6 ] || { echo "expected about 120/20 snapshots, got $count"; exit 1; }
[ ! -e "$tmp/snap/.snapshots.partial" ] || { echo "partial folder left behind"; exit 1; }
grep -q '"snapshots"' "$tmp/snap/report.json"
grep -q "\"count\": $count" "$tmp/snap/report.json"
[ ! -e "$tmp/plain/snapshots" ] || { echo "snapshots without --snapshots"; exit 1; }

# A log that fails part-way: exit 2, no snapshots folder.
{ head -n 2000 "$tmp/sim/robot_0.clf"; echo "FLASER 3 1.0 2.0"; } > "$tmp/bad.clf"
set +e
"$bin" map "$tmp/bad.clf" -o "$tmp/bad" --snapshots 5 2> "$tmp/bad.err"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "bad log: exit $code"; cat "$tmp/bad.err"; exit 1; }
[ ! -e "$tmp/bad/snapshots" ] && [ ! -e "$tmp/bad/.snapshots.partial" ] || {
  echo "snapshots written for a failed run"; exit 1; }
echo "cli_map_snapshots: ok"
