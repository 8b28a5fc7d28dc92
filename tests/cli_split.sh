#!/usr/bin/env bash
# CLI test of `gridslam split` and of `gridslam eval` with several trajectories (issue 8): the
# files split promises, byte-identical output for a seed, relations partitioned without loss,
# ground truth cut like the log scoring zero within and between robots (with and without
# --index), a misplaced robot showing only in the between-robot relations, and exit code 2
# with nothing written on bad input.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metric() {  # metric NAME "eval output": the value of NAME=...
  echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | head -1
}

"$bin" simulate --world office --duration 90 --seed 3 -o "$tmp/sim" > /dev/null
log="$tmp/sim/robot_0.clf"
rel="$tmp/sim/robot_0.relations"
"$bin" split "$log" -n 3 --relations "$rel" --overlap 5 --seed 7 -o "$tmp/a" > /dev/null
"$bin" split "$log" -n 3 --relations "$rel" --overlap 5 --seed 7 -o "$tmp/b" > /dev/null
"$bin" split "$log" -n 3 --relations "$rel" --overlap 5 --seed 8 -o "$tmp/c" > /dev/null
for f in robot_0.clf robot_1.clf robot_2.clf index.txt within.relations between.relations \
         robot_0.relations robot_1.relations robot_2.relations split.json; do
  [ -s "$tmp/a/$f" ] || { echo "missing $f"; exit 1; }
  cmp "$tmp/a/$f" "$tmp/b/$f"
done
if cmp -s "$tmp/a/robot_1.clf" "$tmp/c/robot_1.clf"; then echo "seed has no effect"; exit 1; fi
# Printed timestamps are kept: every scan of the log is in the index once, with its home robot.
scans=$(grep -c '^RAWLASER1' "$log")
[ "$(wc -l < "$tmp/a/index.txt")" = "$scans" ] || { echo "index"; exit 1; }
[ "$(grep -c '^ROBOTLASER1' "$tmp/a/robot_0.clf")" -gt 10 ]
# The overlap: robot 1's log holds more scans than its home scans.
[ "$(grep -c '^ROBOTLASER1' "$tmp/a/robot_1.clf")" -gt "$(awk '$2 == 1' "$tmp/a/index.txt" | wc -l)" ]
# Relations: partitioned without loss, and robot_<i>.relations together are within.relations.
total=$(grep -vc '^#' "$rel")
within=$(grep -vc '^#' "$tmp/a/within.relations" || true)
between=$(grep -vc '^#' "$tmp/a/between.relations" || true)
[ $((within + between)) = "$total" ] || { echo "relations $within + $between != $total"; exit 1; }
[ "$between" -gt 0 ]
[ "$(cat "$tmp"/a/robot_?.relations | grep -vc '^#')" = "$within" ]

# Ground truth cut like the log: zero error within and between robots.
gt="$tmp/sim/robot_0.gt.txt"
for i in 0 1 2; do
  awk -v r="$i" 'NR == FNR { home[$1] = $2; next } home[$1] == r' "$tmp/a/index.txt" "$gt" > "$tmp/gt_$i.txt"
done
for set in within between; do
  for index in "--index $tmp/a/index.txt" ""; do
    # shellcheck disable=SC2086
    out=$("$bin" eval "$tmp/a/$set.relations" "$tmp/gt_0.txt" "$tmp/gt_1.txt" "$tmp/gt_2.txt" $index)
    [ "$(metric translation_mean "$out")" = "0.000000" ] || { echo "$set $index: $out"; exit 1; }
    [ "$(metric missing "$out")" = "0" ] || { echo "$set $index: $out"; exit 1; }
  done
done
# Robot 1 misplaced by 1 m: relations within robots still score zero, those between do not.
awk '{ printf "%s %.9f %s %s\n", $1, $2 + 1.0, $3, $4 }' "$tmp/gt_1.txt" > "$tmp/gt_1_moved.txt"
trajs=("$tmp/gt_0.txt" "$tmp/gt_1_moved.txt" "$tmp/gt_2.txt")
out=$("$bin" eval "$tmp/a/within.relations" "${trajs[@]}" --index "$tmp/a/index.txt")
[ "$(metric translation_mean "$out")" = "0.000000" ] || { echo "within moved: $out"; exit 1; }
out=$("$bin" eval "$tmp/a/between.relations" "${trajs[@]}" --index "$tmp/a/index.txt")
awk -v t="$(metric translation_mean "$out")" 'BEGIN { exit !(t > 0.1) }' || { echo "between moved: $out"; exit 1; }
# A single trajectory works as before.
out=$("$bin" eval "$rel" "$gt")
[ "$(metric translation_mean "$out")" = "0.000000" ] || { echo "single: $out"; exit 1; }

# Bad input: exit 2, nothing written.
printf '1 2 x\n' > "$tmp/bad.relations"
set +e
"$bin" split "$tmp/none.clf" -n 2 --seed 1 -o "$tmp/x1" 2> /dev/null; missing=$?
"$bin" split "$log" -n 0 --seed 1 -o "$tmp/x2" 2> /dev/null; zero=$?
"$bin" split "$log" -n 100000 --seed 1 -o "$tmp/x3" 2> /dev/null; too_many=$?
"$bin" split "$log" -n 2 --relations "$tmp/bad.relations" --seed 1 -o "$tmp/x4" 2> "$tmp/err.txt"; bad=$?
"$bin" split "$log" -n 2 --by distance --seed 1 -o "$tmp/x5" 2> /dev/null; by=$?
"$bin" eval "$rel" "$tmp/gt_0.txt" "$tmp/gt_1.txt" --index "$tmp/a/index.txt" 2> /dev/null; robots=$?
set -e
[ "$missing" -eq 2 ] && [ "$zero" -eq 2 ] && [ "$too_many" -eq 2 ] && [ "$bad" -eq 2 ] &&
  [ "$by" -eq 2 ] && [ "$robots" -eq 2 ] ||
  { echo "exit codes $missing $zero $too_many $bad $by $robots"; exit 1; }
grep -q 'bad.relations:1' "$tmp/err.txt" || { echo "no file:line: $(cat "$tmp/err.txt")"; exit 1; }
for x in x1 x2 x3 x4 x5; do
  [ ! -e "$tmp/$x" ] || { echo "$x written on bad input"; exit 1; }
done
echo "cli_split: ok"
