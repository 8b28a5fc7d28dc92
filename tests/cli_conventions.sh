#!/usr/bin/env bash
# CLI test of the command-line conventions (docs/guide.md §5): --version, --set, --config in every
# command's help, a mistyped command, usage errors exit 2 (an -o that is not a folder), validation
# errors naming the file and line or the --set, stale outputs of an earlier map run removed,
# report.json's schema_version, trajectory.tum in ascending time, progress only on a terminal,
# pictures with axes.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "cli_conventions: $*"; exit 1; }
# expect CODE PATTERN CMD...: runs CMD, checks its exit code and that stderr matches PATTERN.
expect() {
  local code="$1" pattern="$2"
  shift 2
  set +e
  "$@" > "$tmp/out.txt" 2> "$tmp/err.txt"
  local got=$?
  set -e
  [ "$got" -eq "$code" ] || { cat "$tmp/err.txt"; fail "$* exited $got, expected $code"; }
  grep -q -- "$pattern" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "$*: no '$pattern' in stderr"; }
}

# --version
"$bin" --version > "$tmp/version.txt"
grep -Eq '^gridslam [0-9]+\.[0-9]+\.[0-9]+' "$tmp/version.txt" || fail "--version"

# A mistyped command: the nearest one and the list of commands, exit 2.
expect 2 "unknown command 'mapp'; did you mean 'map'?" "$bin" mapp x
grep -q "^  optimize " "$tmp/err.txt" || fail "the commands are not listed"
expect 2 "unknown command 'frobnicate'" "$bin" --log-level warn frobnicate
grep -q "did you mean" "$tmp/err.txt" && fail "suggested a command for a word far from all"

# --config and --set in every command's help.
for cmd in map track odometry eval optimize keymaps align-eval simulate split; do
  "$bin" "$cmd" --help > "$tmp/help.txt"
  grep -q -- "--config" "$tmp/help.txt" || fail "$cmd --help lacks --config"
  grep -q -- "--set" "$tmp/help.txt" || fail "$cmd --help lacks --set"
done

# --set overrides any option; the value is YAML; later ones win; applied after --config.
"$bin" --set fusion.resolution=0.1 --set log.laser_offset=[0.2,0,0.5] --print-config > "$tmp/c.yaml"
grep -q "^  resolution: 0.1$" "$tmp/c.yaml" || fail "--set fusion.resolution"
grep -q "laser_offset: \[0.2, 0.0, 0.5\]" "$tmp/c.yaml" || fail "--set of a list"
printf 'fusion:\n  resolution: 0.2\n' > "$tmp/mine.yaml"
"$bin" --config "$tmp/mine.yaml" --set fusion.resolution=0.3 --print-config > "$tmp/c.yaml"
grep -q "^  resolution: 0.3$" "$tmp/c.yaml" || fail "--set does not win over --config"
"$bin" --set fusion.resolution=0.2 --set fusion.resolution=0.4 --print-config > "$tmp/c.yaml"
grep -q "^  resolution: 0.4$" "$tmp/c.yaml" || fail "the last --set does not win"
expect 2 "\-\-set fusion.resolution=-1: invalid option: fusion.resolution in \[0.005, 10\] m" \
  "$bin" --set fusion.resolution=-1 --print-config
expect 2 "\-\-set fusion.resolutoin=1: unknown option 'fusion.resolutoin'" \
  "$bin" --set fusion.resolutoin=1 --print-config
expect 2 "expected KEY=VALUE" "$bin" --set fusion.resolution --print-config
expect 2 "cannot read a value" "$bin" --set fusion.resolution=abc --print-config

# Validation errors name the file and the line.
printf 'fusion: {resolution: -1}\n' > "$tmp/bad.yaml"
expect 2 "bad.yaml:1: invalid option: fusion.resolution in \[0.005, 10\] m" "$bin" --config "$tmp/bad.yaml" --print-config
printf 'log:\n  lenient: false\nloop_closure:\n  refinement:\n    max_points: 0\n' > "$tmp/bad2.yaml"
expect 2 "bad2.yaml:5: invalid option: refinement.max_points" "$bin" --config "$tmp/bad2.yaml" --print-config

# Usage errors exit 2: an -o that is a file, or lies under one.
"$bin" simulate --world office --seed 1 --duration 20 -o "$tmp/sim" 2> /dev/null
touch "$tmp/a_file"
expect 2 "not a folder" "$bin" map "$tmp/sim/robot_0.clf" -o "$tmp/a_file"
expect 2 "not a folder" "$bin" map "$tmp/sim/robot_0.clf" -o "$tmp/a_file/sub"
expect 2 "not a folder" "$bin" track "$tmp/sim/robot_0.clf" -o "$tmp/a_file"
expect 2 "" "$bin" map --no-such-flag

# A map run removes the outputs of an earlier run it does not rewrite; other files stay. Not on a
# terminal: no progress line.
out="$tmp/out"
mkdir -p "$out"
touch "$out/trajectory_2.txt" "$out/trajectory_0.tum" "$out/map_1.pgm" "$out/map_1_graph.png" \
  "$out/notes.txt"
"$bin" map "$tmp/sim/robot_0.clf" -o "$out" 2> "$tmp/err.txt"
for f in trajectory_2.txt trajectory_0.tum map_1.pgm map_1_graph.png; do
  [ ! -e "$out/$f" ] || fail "stale $f kept"
done
[ -e "$out/notes.txt" ] || fail "removed a file that is not an output"
[ -s "$out/trajectory.txt" ] && [ -s "$out/map.pgm" ] || fail "outputs missing"
grep -q "removed 4 file" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "no note of the removal"; }
grep -q "% of the log" "$tmp/err.txt" && fail "progress printed when stderr is not a terminal"

# report.json is versioned; trajectory.tum is in ascending time with one line per scan.
grep -q '"schema_version": 1' "$out/report.json" || fail "no schema_version"
sort -c -s -g -k1,1 "$out/trajectory.tum" || fail "trajectory.tum not ascending"
[ "$(wc -l < "$out/trajectory.tum")" -eq "$(wc -l < "$out/trajectory.txt")" ] || fail "tum/txt lines"

# map.png and map_graph.png carry axes and a scale bar in margins around the map: wider and
# taller than map.pgm by the margins (56 + 12, 8 + 34 pixels).
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8}'; }
read -r pgm_w pgm_h < <(head -c 64 "$out/map.pgm" | sed -n 3p)
for png in map.png map_graph.png; do
  read -r w h < <(png_size "$out/$png")
  [ "$w" -eq $((pgm_w + 68)) ] && [ "$h" -eq $((pgm_h + 42)) ] ||
    fail "$png is ${w}x${h}, map.pgm ${pgm_w}x${pgm_h}"
done

# On a terminal (script(1) provides one): a progress line with share, elapsed, ETA, scans/s.
if command -v script > /dev/null; then
  script -qec "'$bin' map '$tmp/sim/robot_0.clf' -o '$tmp/out2'" /dev/null > "$tmp/tty.txt" || true
  grep -q "% of the log, .* s elapsed, ETA .* scans/s" "$tmp/tty.txt" || { cat "$tmp/tty.txt"; fail "no progress on a terminal"; }
fi
echo "cli_conventions: ok"
