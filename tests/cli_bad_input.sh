#!/usr/bin/env bash
# CLI regression test of issue 17's bad-input reproducers: every case exits with the documented
# code (2 bad input, 1 runtime), names the file (and line, where there is one), and leaves an
# earlier result in the output folder exactly as it was (transactional outputs, lock file).
set -euo pipefail
bin="$1"
fixtures="$(cd "$(dirname "$0")" && pwd)/data"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "cli_bad_input: FAIL: $*"; exit 1; }
good="$fixtures/carmen_interpolation.clf"

# expect CODE PATTERN CMD...: runs CMD, checks its exit code and that PATTERN is in its output.
expect() {
  local want="$1" pattern="$2"
  shift 2
  set +e
  "$@" > "$tmp/out.txt" 2>&1
  local code=$?
  set -e
  [ "$code" -eq "$want" ] || { cat "$tmp/out.txt"; fail "$*: exit $code, expected $want"; }
  grep -q -- "$pattern" "$tmp/out.txt" || { cat "$tmp/out.txt"; fail "$*: no '$pattern' in the message"; }
  if grep -q "fatal" "$tmp/out.txt"; then cat "$tmp/out.txt"; fail "$*: uncaught exception"; fi
}
# tree DIR: a fingerprint of every file (hidden ones too) and its contents.
tree() { (cd "$1" && find . -type f | sort | xargs -r md5sum); }
# no_leftovers DIR: nothing of a staging folder or temporary file beside or inside DIR.
no_leftovers() {
  local parent; parent="$(dirname "$1")"
  if ls -a "$parent" | grep -E '\.tmp|\.old-' > /dev/null; then ls -a "$parent"; fail "staging left in $parent"; fi
  if [ -d "$1" ] && find "$1" -name '*.tmp*' | grep -q .; then fail "temporary files left in $1"; fi
}

# --- earlier results of every folder command, which failed runs must leave untouched --------
"$bin" track "$good" -o "$tmp/track" 2> /dev/null
"$bin" keymaps "$good" -o "$tmp/keymaps" 2> /dev/null
"$bin" map "$good" -o "$tmp/map" 2> /dev/null
[ -s "$tmp/track/report.json" ] && [ -s "$tmp/map/map.pgm" ] && [ -s "$tmp/keymaps/keymaps.txt" ] \
  || fail "the good runs wrote nothing"
for d in track keymaps map; do tree "$tmp/$d" > "$tmp/$d.before"; done
unchanged() {
  for d in track keymaps map; do
    tree "$tmp/$d" | cmp -s - "$tmp/$d.before" || fail "$1: the earlier $d result was changed"
    no_leftovers "$tmp/$d"
  done
}

# --- degenerate logs: exit 2, a clear message, nothing overwritten ---------------------------
: > "$tmp/empty.clf"
printf '# only comments\n\n# here\n' > "$tmp/comments.clf"
printf 'ODOM 0 0 0 0 0 0 100.0 h 0\nODOM 1 0 0 0 0 0 100.5 h 0\n' > "$tmp/odom_only.clf"
printf 'GPSNMEA a b c 100.0 h 0\nNEFF 1 2 100.1 h 0\n' > "$tmp/unknown.clf"
head -c 4096 /dev/urandom | tr -d '\n' > "$tmp/binary.clf"
printf '\0\0\0\n' >> "$tmp/binary.clf"
for log in empty comments odom_only unknown; do
  for cmd in track keymaps map; do
    # The content sniffer or the CARMEN reader refuses it, naming the file.
    expect 2 "$log.clf: .*\(no laser scan\|not a recording\)" "$bin" "$cmd" "$tmp/$log.clf" -o "$tmp/$cmd"
  done
  expect 2 "no laser scan\|not a recording" "$bin" odometry "$tmp/$log.clf" -o "$tmp/odo.txt"
  expect 2 "no laser scan\|not a recording" "$bin" split "$tmp/$log.clf" -n 2 -o "$tmp/split"
done
expect 2 "unknown types (GPSNMEA, NEFF)" "$bin" map "$tmp/unknown.clf" -o "$tmp/map"
for cmd in track keymaps map; do
  expect 2 "binary.clf\(:1: a NUL byte\|: not a recording.*binary data\)" "$bin" "$cmd" "$tmp/binary.clf" -o "$tmp/$cmd"
done
unchanged "degenerate logs"
[ ! -e "$tmp/odo.txt" ] && [ ! -e "$tmp/split" ] || fail "a failed run created its output"

# --- non-finite and huge numbers (crashes before issue 17) -----------------------------------
make_log() {  # make_log NAME ODOM_X: the good fixture with its second ODOM x replaced
  awk -v x="$2" '/^ODOM/ && ++n == 2 { $2 = x } { print }' "$good" > "$tmp/$1.clf"
}
line="$(grep -n '^ODOM' "$good" | sed -n 2p | cut -d: -f1)"
for x in nan inf -inf 1e308; do
  make_log "odom_$x" "$x"
  for cmd in track keymaps map; do
    expect 2 "odom_$x.clf:$line: ODOM: field 'odom_x'" "$bin" "$cmd" "$tmp/odom_$x.clf" -o "$tmp/$cmd"
  done
done
{ echo "PARAM robot_frontlaser_offset 1e308 nohost 0"; cat "$good"; } > "$tmp/param.clf"
expect 2 "param.clf:1: PARAM robot_frontlaser_offset" "$bin" map "$tmp/param.clf" -o "$tmp/map"
awk '/^RAWLASER1/ && ++n == 2 { $(NF-2) = "20000000000.000000" } { print }' "$good" > "$tmp/time.clf"
expect 2 "time.clf:[0-9]*: RAWLASER1: field 'ipc_timestamp'" "$bin" track "$tmp/time.clf" -o "$tmp/track"
awk '/^RAWLASER1/ && ++n == 2 { $(NF-2) = "1e308" } { print }' "$good" > "$tmp/time2.clf"
expect 2 "field 'ipc_timestamp'" "$bin" split "$tmp/time2.clf" -n 2 -o "$tmp/split"
unchanged "numbers"

# split --max-offset 1e308 read stack bytes into the logs (carmen_writer.cpp:30).
expect 2 "split.max_translation" "$bin" split "$good" -n 2 --max-offset 1e308 -o "$tmp/split"
expect 2 "split.max_translation" "$bin" split "$good" -n 2 --max-offset nan -o "$tmp/split"
[ ! -e "$tmp/split" ] || fail "split wrote output for a bad --max-offset"
for k in $(seq 0 39); do  # a longer log: split needs 10 scans per piece
  printf 'ODOM %d.0 0 0 0 0 0 %d.0 h 0\n' "$k" "$((100 + k))"
  printf 'RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 5 1.00 1.00 1.00 1.00 1.00 0 %d.5 h 0\n' "$((100 + k))"
done > "$tmp/long.clf"
"$bin" split "$tmp/long.clf" -n 2 --max-offset 9999 -o "$tmp/split" > "$tmp/out.txt" 2>&1 \
  || { cat "$tmp/out.txt"; fail "split"; }
for f in "$tmp"/split/robot_*.clf; do
  LC_ALL=C grep -q -P '[^\x09\x0a\x20-\x7e]' "$f" && fail "non-text bytes in $f"
  "$bin" odometry "$f" -o "$tmp/split_odo.txt" 2> /dev/null || fail "$f does not read back"
done

# --- pose graphs ------------------------------------------------------------------------------
v='VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n'
printf "${v}EDGE_SE2 0 1 1e308 0 0 1 0 0 1 0 1\n" > "$tmp/huge.g2o"
printf "${v}EDGE_SE2 0 5 1 0 0 1 0 0 1 0 1\n" > "$tmp/undeclared.g2o"
printf "${v}EDGE_SE2 0 1 1 0 0 0 0 0 0 0 0\n" > "$tmp/zero.g2o"
printf "${v}EDGE_SE2 0 1 1 0 0 1 2 0 1 0 1\n" > "$tmp/indefinite.g2o"
printf 'VERTEX2 0 0 0 0\nVERTEX2 1 1 0 0\nEDGE2 0 1 1 0 0 1 1 1 1 0 0\n' > "$tmp/singular.graph"
expect 2 "huge.g2o:3: EDGE_SE2 field 3 (dx)" "$bin" optimize "$tmp/huge.g2o" -o "$tmp/opt.g2o"
expect 2 "undeclared.g2o:3: edge to vertex 5" "$bin" optimize "$tmp/undeclared.g2o" -o "$tmp/opt.g2o"
expect 2 "zero.g2o:3: information matrix is not positive definite" "$bin" optimize "$tmp/zero.g2o" -o "$tmp/opt.g2o"
expect 2 "indefinite.g2o:3: information matrix" "$bin" optimize "$tmp/indefinite.g2o" -o "$tmp/opt.g2o"
expect 2 "singular.graph:3: information matrix" "$bin" optimize "$tmp/singular.graph" -o "$tmp/opt.g2o"
[ ! -e "$tmp/opt.g2o" ] || fail "optimize wrote a graph from bad input"

# --- YAML configuration ------------------------------------------------------------------------
printf 'fusion:\n  resolution: 0.1\n  resolution: 0.2\n' > "$tmp/dup.yaml"
expect 2 "dup.yaml:3: option 'fusion.resolution' given twice" "$bin" --config "$tmp/dup.yaml" --print-config
printf '? [a, b]\n: 1\n' > "$tmp/key.yaml"
expect 2 "key.yaml:1: a key in 'the top level' is not a plain name" "$bin" --config "$tmp/key.yaml" --print-config
printf 'log:\n  max_usable_range: .inf\n' > "$tmp/inf.yaml"
"$bin" --config "$tmp/inf.yaml" --print-config > "$tmp/printed.yaml" || fail "inf config"
grep -q "max_usable_range: .inf" "$tmp/printed.yaml" || fail "inf not printed as .inf"
"$bin" --config "$tmp/printed.yaml" --print-config > /dev/null || fail "printed config does not read back"
# Options that ended in bad_alloc after the run had started: rejected up front, with file:line.
printf 'fusion:\n  resolution: 1e-7\n' > "$tmp/res.yaml"
printf 'fusion:\n  margin: 1e6\n' > "$tmp/margin.yaml"
printf 'simulation:\n  laser:\n    num_beams: 2000000000\n' > "$tmp/beams.yaml"
printf 'simulation:\n  duration: 1e9\n' > "$tmp/duration.yaml"
expect 2 "res.yaml:2: invalid option: fusion.resolution" "$bin" --config "$tmp/res.yaml" map "$good" -o "$tmp/map"
expect 2 "margin.yaml:2: invalid option: fusion.margin" "$bin" --config "$tmp/margin.yaml" map "$good" -o "$tmp/map"
expect 2 "beams.yaml:3: invalid option: simulation.laser.num_beams" "$bin" --config "$tmp/beams.yaml" simulate -o "$tmp/sim"
expect 2 "duration.yaml:2: invalid option: simulation.duration" "$bin" --config "$tmp/duration.yaml" simulate -o "$tmp/sim"
expect 2 "invalid option: simulation.duration" "$bin" simulate --duration 1e9 -o "$tmp/sim"
unchanged "options"

# --- worlds and routes --------------------------------------------------------------------------
# A 19-byte PNG whose header claims 65535 x 65535 pixels (allocated 4.1 GB before issue 17).
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00\xff\xff\x00\x00\xff' > "$tmp/short.png"
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00\xff\xff\x00\x00\xff\xff\x08\x00\x00\x00\x00' > "$tmp/huge.png"
expect 2 "short.png: truncated PNG header" "$bin" simulate --world "$tmp/short.png" -o "$tmp/sim"
expect 2 "huge.png: image header announces 65535 x 65535 pixels" "$bin" simulate --world "$tmp/huge.png" -o "$tmp/sim"
printf 'P5\n60000 60000\n255\nxx' > "$tmp/huge.pgm"
expect 2 "huge.pgm: image header announces 60000 x 60000" "$bin" simulate --world "$tmp/huge.pgm" -o "$tmp/sim"
printf '1 1\n' > "$tmp/route.txt"
expect 2 "route.txt: route waypoint 0 (1.000, 1.000) is closer than the robot radius" "$bin" simulate --route "$tmp/route.txt" -o "$tmp/sim"
printf '1 1\n1e308 2\n' > "$tmp/route2.txt"
expect 2 "route2.txt:2: waypoint coordinates must be finite" "$bin" simulate --route "$tmp/route2.txt" -o "$tmp/sim"
[ ! -e "$tmp/sim" ] || fail "simulate wrote output for bad input"

# --- a log failing at line 8 must not half-replace keymaps/ ---------------------------------
awk 'NR == 8 { print "RAWLASER1 0 bad"; next } { print }' "$good" > "$tmp/line8.clf"
expect 2 "line8.clf:8: RAWLASER1" "$bin" keymaps "$tmp/line8.clf" -o "$tmp/keymaps"
unchanged "keymaps at line 8"

# --- concurrent runs: the second refuses while the first holds the lock ---------------------
if command -v flock > /dev/null; then
  # -o: the lock belongs to flock itself, so killing it releases the lock.
  flock -o "$tmp/.map.lock" sleep 20 > /dev/null 2>&1 &
  holder=$!
  sleep 0.5
  expect 1 "another gridslam run is writing into" "$bin" map "$good" -o "$tmp/map"
  kill "$holder" 2> /dev/null || true
  wait "$holder" 2> /dev/null || true
  unchanged "concurrent run"
fi

# --- a full disk (a file-size limit: writes fail with EFBIG): exit 1, old result kept ------
set +e
(trap '' XFSZ; ulimit -f 2; exec "$bin" track "$good" -o "$tmp/track") > "$tmp/out.txt" 2>&1
code=$?
(trap '' XFSZ; ulimit -f 2; exec "$bin" map "$good" -o "$tmp/map") >> "$tmp/out.txt" 2>&1
code2=$?
set -e
[ "$code" -eq 1 ] && [ "$code2" -eq 1 ] || { cat "$tmp/out.txt"; fail "full disk: exit $code/$code2, expected 1"; }
grep -q "cannot write" "$tmp/out.txt" || { cat "$tmp/out.txt"; fail "full disk: no message"; }
unchanged "full disk"
printf "${v}EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n" > "$tmp/ok.g2o"
set +e
(trap "" XFSZ; ulimit -f 0; exec "$bin" optimize "$tmp/ok.g2o" -o "$tmp/opt.g2o") > "$tmp/out.txt" 2>&1
code=$?
set -e
[ "$code" -eq 1 ] || { cat "$tmp/out.txt"; fail "optimize on a full disk: exit $code"; }
ls "$tmp" | grep -q "opt.g2o" && fail "optimize on a full disk left $(ls "$tmp" | grep opt.g2o)"
expect 1 "cannot write '/dev/full' (write failed)" "$bin" odometry "$good" -o /dev/full
[ -c /dev/full ] || fail "/dev/full was replaced"

# --- a successful run replaces the earlier result whole ------------------------------------
touch "$tmp/keymaps/stale_from_an_old_run.png"  # not in the manifest: the user's file, kept
"$bin" keymaps "$good" -o "$tmp/keymaps" 2> /dev/null
[ -e "$tmp/keymaps/stale_from_an_old_run.png" ] || fail "a file the run did not write was removed"
"$bin" track "$good" -o "$tmp/track" 2> /dev/null
[ -s "$tmp/track/report.json" ] || fail "rerun"
no_leftovers "$tmp/track"
echo "cli_bad_input: ok"
