#!/usr/bin/env bash
# CLI test of `gridslam perturb` (issue 16): without faults the log reads back as it was; every
# printed laser timestamp is kept; glitches are seeded (byte-identical for a seed, different for
# another), documented in the log's comments and worsen the odometry; keep-every, range limit and
# odometry removal do what they say; `eval` interpolates the relations of a decimated log; logs
# without timestamps are read with synthesized times (--rate); bad input exits 2 and writes
# nothing.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metric() {  # metric NAME "eval output": the value of NAME=...
  echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | head -1
}

"$bin" simulate --world office --duration 120 --seed 3 -o "$tmp/sim" > /dev/null
log="$tmp/sim/robot_0.clf"
rel="$tmp/sim/robot_0.relations"
"$bin" odometry "$log" -o "$tmp/odom.txt" 2> /dev/null

# No faults: the same scans, timestamps and odometry (to the writer's 6 decimals).
"$bin" perturb "$log" -o "$tmp/copy.clf" > /dev/null
"$bin" odometry "$tmp/copy.clf" -o "$tmp/copy_odom.txt" 2> /dev/null
[ "$(wc -l < "$tmp/copy_odom.txt")" = "$(wc -l < "$tmp/odom.txt")" ]
paste "$tmp/odom.txt" "$tmp/copy_odom.txt" | awk '
  $1 != $5 { print "time " NR; exit 1 }
  { for (i = 2; i <= 4; ++i) {
      d = $i - $(i + 4); if (d < 0) d = -d; if (i == 4 && d > 3.14159) d = 6.283185307 - d
      if (d > 2e-6) { print "pose " NR; exit 1 } } }'
grep -q '^# gridslam perturb: a fault variant of' "$tmp/copy.clf"
grep -q '^ROBOTLASER1 ' "$tmp/copy.clf"
[ "$(grep -c '^ODOM ' "$tmp/copy.clf")" = "$(grep -c '^ROBOTLASER1 ' "$tmp/copy.clf")" ]

# Glitches: seeded, documented, timestamps kept, odometry worse.
"$bin" perturb "$log" -o "$tmp/g1.clf" --glitch-period 10 --glitch-yaw-fraction 1 --seed 5 > /dev/null
"$bin" perturb "$log" -o "$tmp/g2.clf" --glitch-period 10 --glitch-yaw-fraction 1 --seed 5 > /dev/null
"$bin" perturb "$log" -o "$tmp/g3.clf" --glitch-period 10 --glitch-yaw-fraction 1 --seed 6 > /dev/null
cmp "$tmp/g1.clf" "$tmp/g2.clf"
if cmp -s "$tmp/g1.clf" "$tmp/g3.clf"; then echo "seed has no effect"; exit 1; fi
[ "$(grep -c '^# glitch at .*: yaw jump' "$tmp/g1.clf")" -ge 3 ]
grep -q '^# glitch_period: 10' "$tmp/g1.clf"
"$bin" odometry "$tmp/g1.clf" -o "$tmp/g1_odom.txt" 2> /dev/null
cmp <(cut -d' ' -f1 "$tmp/odom.txt") <(cut -d' ' -f1 "$tmp/g1_odom.txt")
# (The simulator's relations span 1 s, so a yaw jump shows in the rotation error.)
clean=$(metric rotation_mean_deg "$("$bin" eval "$rel" "$tmp/odom.txt")")
glitched=$(metric rotation_mean_deg "$("$bin" eval "$rel" "$tmp/g1_odom.txt")")
awk -v a="$clean" -v b="$glitched" 'BEGIN { exit !(b > 5 * a) }' || { echo "glitch $clean -> $glitched"; exit 1; }

# Every 3rd scan: a third of the scans, their timestamps unchanged; eval interpolates the rest.
"$bin" perturb "$log" -o "$tmp/k3.clf" --keep-every 3 > /dev/null
"$bin" odometry "$tmp/k3.clf" -o "$tmp/k3_odom.txt" 2> /dev/null
[ "$(wc -l < "$tmp/k3_odom.txt")" = "$(( ($(wc -l < "$tmp/odom.txt") + 2) / 3 ))" ]
cmp <(cut -d' ' -f1 "$tmp/odom.txt" | awk 'NR % 3 == 1') <(cut -d' ' -f1 "$tmp/k3_odom.txt")
out=$("$bin" eval "$rel" "$tmp/k3_odom.txt" 2> /dev/null)
[ "$(metric interpolated "$out")" -gt 0 ] || { echo "k3: $out"; exit 1; }
[ "$(metric missing "$out")" = "0" ] || { echo "k3: $out"; exit 1; }
out=$("$bin" eval "$rel" "$tmp/k3_odom.txt" --no-interpolate 2> /dev/null || true)  # none scored: exit 2
[ "$(metric interpolated "$out")" = "0" ] && [ "$(metric missing "$out")" -gt 0 ] || { echo "k3 exact: $out"; exit 1; }

# Range limit: maximum_range is the limit, no reading beyond it, fewer returns.
"$bin" perturb "$log" -o "$tmp/r5.clf" --max-range 5 > /dev/null
awk '/^ROBOTLASER1/ { if ($6 != "5.000000") { print "max " $6; exit 1 }
                      n = $9; for (i = 10; i < 10 + n; ++i) if ($i + 0 > 5.0) { print "range " $i; exit 1 } }' "$tmp/r5.clf"

# Odometry removed: no ODOM lines, pose-less laser lines, identity odometry.
"$bin" perturb "$log" -o "$tmp/no.clf" --no-odometry > /dev/null
! grep -q '^ODOM ' "$tmp/no.clf"
[ "$(grep -c '^RAWLASER1 ' "$tmp/no.clf")" = "$(wc -l < "$tmp/odom.txt")" ]
"$bin" odometry "$tmp/no.clf" -o "$tmp/no_odom.txt" 2> /dev/null
awk '$2 != 0 || $3 != 0 || $4 != 0 { exit 1 }' "$tmp/no_odom.txt"

# A cut: 30 s from 20 s on.
"$bin" perturb "$log" -o "$tmp/cut.clf" --start 20 --duration 30 > /dev/null
"$bin" odometry "$tmp/cut.clf" -o "$tmp/cut_odom.txt" 2> /dev/null
awk -v t0="$(head -1 "$tmp/odom.txt" | cut -d' ' -f1)" '
  { d = $1 - t0; if (d < 20 - 1e-6 || d > 50 + 1e-6) { print "cut " d; exit 1 } }' "$tmp/cut_odom.txt"

# A log without timestamp fields (laserazos): times synthesized at --rate, with a warning.
printf 'FLASER 3 1.0 2.0 3.0 0.5 0.0 0.1 0.5 0.0 0.1\nFLASER 3 1.0 2.0 3.0 0.6 0.0 0.1 0.6 0.0 0.1\n' > "$tmp/untimed.log"
"$bin" --rate 5 odometry "$tmp/untimed.log" -o "$tmp/untimed.txt" 2> "$tmp/untimed.err"
grep -q 'synthesized' "$tmp/untimed.err"
[ "$(cut -d' ' -f1 "$tmp/untimed.txt" | tr '\n' ' ')" = "0.000000 0.200000 " ] || { cat "$tmp/untimed.txt"; exit 1; }

# Fault options from YAML (the keys of the log's own comment block); flags override them.
printf 'keep_every: 2\nmax_range: 6.0\n' > "$tmp/faults.yaml"
"$bin" perturb "$log" -o "$tmp/y.clf" --faults "$tmp/faults.yaml" --max-range 4 > /dev/null
grep -q '^# keep_every: 2$' "$tmp/y.clf"
grep -q '^# max_range: 4.0$' "$tmp/y.clf"
[ "$(grep -c '^ROBOTLASER1 ' "$tmp/y.clf")" = "$(( ($(wc -l < "$tmp/odom.txt") + 1) / 2 ))" ]

# Bad input: exit 2, nothing written.
set +e
"$bin" perturb "$log" -o "$tmp/bad.clf" --keep-every 0 2> /dev/null; rc1=$?
"$bin" perturb "$tmp/none.clf" -o "$tmp/bad.clf" 2> /dev/null; rc2=$?
"$bin" perturb "$log" -o "$tmp/bad.clf" --start 100000 2> /dev/null; rc3=$?
printf 'keep_evry: 2\n' > "$tmp/typo.yaml"
"$bin" perturb "$log" -o "$tmp/bad.clf" --faults "$tmp/typo.yaml" 2> /dev/null; rc4=$?
set -e
[ "$rc1" = 2 ] && [ "$rc2" = 2 ] && [ "$rc3" = 2 ] && [ "$rc4" = 2 ] ||
  { echo "exit codes $rc1 $rc2 $rc3 $rc4"; exit 1; }
[ ! -e "$tmp/bad.clf" ]
echo "cli_perturb: ok"
