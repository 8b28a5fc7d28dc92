#!/usr/bin/env bash
# CLI test of the large simulated worlds (issue 16 part 5): campus and corridors simulate with
# exact ground truth and relations, and the cheap 360-degree lidar preset
# (config/sensors/lidar360_cheap.yaml) writes 360-beam, 10 m, 7 Hz scans.
set -euo pipefail
bin="$1"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metric() {  # metric NAME "eval output": the value of NAME=...
  echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | head -1
}

"$bin" --config "$root/config/sensors/lidar360_cheap.yaml" simulate --world corridors \
  --duration 100 -o "$tmp/c" > /dev/null
for f in robot_0.clf robot_0.gt.txt robot_0.relations world.png world.yaml; do
  [ -s "$tmp/c/$f" ] || { echo "missing $f"; exit 1; }
done
# 360 beams from -179.5 deg in 1 deg steps, 10 m range; 7 Hz (on the 10 ms control clock: 0.14 s).
grep -q '^RAWLASER1 0 -3.132866 6.265732 0.017453 10.000000 ' "$tmp/c/robot_0.clf" ||
  { grep -m1 '^RAWLASER1' "$tmp/c/robot_0.clf" | cut -c1-80; exit 1; }
[ "$(grep -m1 '^RAWLASER1' "$tmp/c/robot_0.clf" | cut -d' ' -f9)" = "360" ]
scans=$(grep -c '^RAWLASER1' "$tmp/c/robot_0.clf")
[ "$scans" -ge 695 ] && [ "$scans" -le 720 ] || { echo "scans at 7 Hz over 100 s: $scans"; exit 1; }
truth=$("$bin" eval "$tmp/c/robot_0.relations" "$tmp/c/robot_0.gt.txt")
[ "$(metric translation_mean "$truth")" = "0.000000" ] || { echo "truth: $truth"; exit 1; }

"$bin" simulate --world campus --duration 60 -o "$tmp/k" > /dev/null
truth=$("$bin" eval "$tmp/k/robot_0.relations" "$tmp/k/robot_0.gt.txt")
[ "$(metric translation_mean "$truth")" = "0.000000" ] || { echo "truth: $truth"; exit 1; }
[ "$(metric relations "$truth")" -gt 10 ] || { echo "truth: $truth"; exit 1; }
# The campus is 250 x 170 m at 0.05 m.
grep -q '^resolution: 0.05' "$tmp/k/world.yaml"
size=$(od -An -tu1 -j16 -N8 "$tmp/k/world.png" |
  awk '{ printf "%d %d", (($1 * 256 + $2) * 256 + $3) * 256 + $4, (($5 * 256 + $6) * 256 + $7) * 256 + $8 }')
[ "$size" = "5000 3400" ] || { echo "campus world.png is $size pixels"; exit 1; }
echo "cli_simulate_worlds: ok"
