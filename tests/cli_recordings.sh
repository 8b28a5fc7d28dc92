#!/usr/bin/env bash
# CLI test of recording input (issues 14, 15): a file that is not a recording exits 2 and says
# what it looks like, writing nothing; bad bags (truncated, wrong magic, corrupt chunk, missing
# topic) exit 2 with a clear message; `info` describes a bag. The bag parts use temporary copies
# of the shared bags and are skipped (with a message) when GRIDSLAM_DATA has none.
set -euo pipefail
bin="$1"
root="$(cd "$(dirname "$0")/.." && pwd)"
data="${GRIDSLAM_DATA:-$root/../shared/data}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "cli_recordings: FAIL: $*"; exit 1; }

# expect_refused "what it should say" command...: exit 2, message on stderr, no output folder.
expect_refused() {
  local says="$1"
  shift
  rm -rf "$tmp/out"
  set +e
  "$@" > "$tmp/err.txt" 2>&1
  local code=$?
  set -e
  [ "$code" -eq 2 ] || { cat "$tmp/err.txt"; fail "$*: expected exit 2, got $code"; }
  grep -q -- "$says" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "$*: no '$says' in the message"; }
  [ ! -e "$tmp/out" ] || fail "$*: output written for a refused input"
}

printf 'VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n' > "$tmp/graph.g2o"
printf 'VERTEX2 0 0 0 0\nEDGE2 0 1 1 0 0 1 0 1 1 0 0\n' > "$tmp/graph.graph"
printf '\x89PNG\r\n\x1a\n\0\0\0\rIHDR' > "$tmp/map.png"
printf 'P5\n2 2\n255\n\0\0\0\0' > "$tmp/map.pgm"
printf '976052857.1 976052858.2 0.1 0 0 0 0 0.01\n976052859.1 976052860.2 0.1 0 0 0 0 0\n' \
  > "$tmp/intel.relations"
: > "$tmp/empty.clf"
printf 'ODOM 0 0 0 0 0 0 1.0 h 1.0\n' > "$tmp/odom_only.clf"
for cmd in map track keymaps; do
  expect_refused "looks like a g2o pose graph" "$bin" "$cmd" "$tmp/graph.g2o" -o "$tmp/out"
done
expect_refused "looks like a TORO pose graph" "$bin" map "$tmp/graph.graph" -o "$tmp/out"
expect_refused "looks like a PNG image" "$bin" map "$tmp/map.png" -o "$tmp/out"
expect_refused "looks like a PGM image" "$bin" map "$tmp/map.pgm" -o "$tmp/out"
expect_refused "looks like a relations file" "$bin" map "$tmp/intel.relations" -o "$tmp/out"
expect_refused "looks like an empty file" "$bin" map "$tmp/empty.clf" -o "$tmp/out"
expect_refused "no laser scan" "$bin" map "$tmp/odom_only.clf" -o "$tmp/out"
expect_refused "looks like a g2o pose graph" "$bin" odometry "$tmp/graph.g2o" -o "$tmp/out"
expect_refused "looks like a g2o pose graph" "$bin" info "$tmp/graph.g2o"

bag="$data/bags/fr079.orig.bag"
mcap="$data/bags/fr079.mcap"
if [ ! -f "$bag" ] || [ ! -f "$mcap" ]; then
  echo "cli_recordings: shared bags not found under $data/bags: bag checks skipped"
  exit 0
fi
size=$(stat -c %s "$bag")
head -c $((size / 2)) "$bag" > "$tmp/truncated.bag"
expect_refused "truncated" "$bin" map "$tmp/truncated.bag" -o "$tmp/out"
{ printf '#ROSBAG V3.0\n'; tail -c +14 "$bag"; } > "$tmp/magic.bag"
expect_refused "unsupported version" "$bin" map "$tmp/magic.bag" -o "$tmp/out"
cp "$bag" "$tmp/corrupt.bag"
chmod u+w "$tmp/corrupt.bag"
head -c 4096 /dev/zero | dd of="$tmp/corrupt.bag" bs=1 seek=$((size / 3)) conv=notrunc 2> /dev/null
expect_refused "chunk" "$bin" map "$tmp/corrupt.bag" -o "$tmp/out"
expect_refused "no sensor_msgs/LaserScan topic '/base_scan'" \
  "$bin" --scan-topic /base_scan map "$bag" -o "$tmp/out"
grep -q "/odom  nav_msgs/Odometry  8951 messages" "$tmp/err.txt" || fail "topic listing"
msize=$(stat -c %s "$mcap")
head -c $((msize * 2 / 3)) "$mcap" > "$tmp/truncated.mcap"
expect_refused "MCAP" "$bin" map "$tmp/truncated.mcap" -o "$tmp/out"

"$bin" info "$bag" > "$tmp/info.txt" 2> "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "info"; }
grep -q "/scan  sensor_msgs/LaserScan  4934 messages" "$tmp/info.txt" || { cat "$tmp/info.txt"; fail "info topics"; }
grep -q "360 beams" "$tmp/info.txt" || { cat "$tmp/info.txt"; fail "info geometry"; }
grep -q "x 0.0400 m" "$tmp/info.txt" || { cat "$tmp/info.txt"; fail "info mounting"; }
"$bin" info "$mcap" > "$tmp/info2.txt" 2> /dev/null || fail "info mcap"
grep -q "scans: 4934" "$tmp/info2.txt" || { cat "$tmp/info2.txt"; fail "info mcap scans"; }
echo "cli_recordings: ok"
