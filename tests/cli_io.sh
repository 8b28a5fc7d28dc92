#!/usr/bin/env bash
# CLI test of the readers, `odometry` and `eval`: a malformed log exits 2 naming file:line and
# writes nothing; unknown message types warn once per type; --lenient skips and says how many;
# eval on a tiny constructed trajectory/relations pair gives the known numbers.
set -euo pipefail
bin="$1"
fixtures="$(cd "$(dirname "$0")" && pwd)/data"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "cli_io: FAIL: $*"; exit 1; }

# Malformed RAWLASER1 on line 9: exit 2, file:line and field in the message, no output file.
set +e
"$bin" odometry "$fixtures/carmen_bad_input.clf" -o "$tmp/odo.txt" > "$tmp/err.txt" 2>&1
code=$?
set -e
[ "$code" -eq 2 ] || fail "malformed log: expected exit 2, got $code"
grep -q "carmen_bad_input.clf:9: RAWLASER1: field 'range\[1\]'" "$tmp/err.txt" \
  || { cat "$tmp/err.txt"; fail "no file:line:field message"; }
[ ! -e "$tmp/odo.txt" ] || fail "a half output file was written"
[ -z "$(ls "$tmp" | grep -v err.txt)" ] || fail "temporary files left behind: $(ls "$tmp")"

# --lenient: skips and counts; unknown types warned once each.
# (spdlog's default logger may print to stdout: read both streams.)
"$bin" --lenient odometry "$fixtures/carmen_bad_input.clf" -o "$tmp/odo.txt" > "$tmp/err.txt" 2>&1
grep -q "1 malformed lines skipped" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "lenient count"; }
[ "$(grep -c "unknown message type 'GPSNMEA'" "$tmp/err.txt")" -eq 1 ] || fail "GPSNMEA warnings"
[ "$(grep -c "unknown message type 'NEFF'" "$tmp/err.txt")" -eq 1 ] || fail "NEFF warning"
[ "$(wc -l < "$tmp/odo.txt")" -eq 2 ] || fail "expected 2 scans"
grep -q "^30.100000 0.5 0 0$" "$tmp/odo.txt" || { cat "$tmp/odo.txt"; fail "interpolated pose"; }

# TUM output by extension.
"$bin" odometry "$fixtures/carmen_interpolation.clf" -o "$tmp/odo.tum" 2> /dev/null
[ "$(head -1 "$tmp/odo.tum" | wc -w)" -eq 8 ] || fail "TUM line"

# eval on a constructed pair with known answers (errors 0.1 m and 0.3 m; one relation missing).
printf '1.000000 0 0 0\n2.000000 1 0 0\n3.000000 2 0 0\n' > "$tmp/traj.txt"
printf '# t1 t2 x y z roll pitch yaw\n1.000000 2.000000 1.1 0 0 0 0 0\n' > "$tmp/rel.relations"
printf '2.000000 3.000000 1.3 0 0 0 0 0\n1.000000 9.000000 1 0 0 0 0 0\n' >> "$tmp/rel.relations"
"$bin" eval "$tmp/rel.relations" "$tmp/traj.txt" > "$tmp/eval.txt" 2> "$tmp/err.txt"
grep -q "^translation_mean=0.200000 translation_std=0.141421 rotation_mean_deg=0.000000 rotation_std_deg=0.000000 relations=2$" "$tmp/eval.txt" \
  || { cat "$tmp/eval.txt"; fail "eval line"; }
grep -q "missing=1" "$tmp/eval.txt" || fail "missing count"
grep -q "1 of 3 relations not scored" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "missing warning"; }
"$bin" eval "$tmp/rel.relations" "$tmp/traj.txt" --json > "$tmp/eval.json" 2> /dev/null
for key in translation_mean translation_std rotation_mean_deg rotation_std_deg translation_sq_mean \
           rotation_sq_mean_deg2 relations missing; do
  grep -q "\"$key\"" "$tmp/eval.json" || fail "JSON key $key"
done
"$bin" eval "$tmp/rel.relations" "$tmp/traj.txt" --max-dt 1.5 | grep -q "relations=2 *$\|relations=2$" \
  || fail "--max-dt"

# Bad relations file: exit 2 with file:line.
printf '1.0 2.0 0.1\n' > "$tmp/bad.relations"
set +e
"$bin" eval "$tmp/bad.relations" "$tmp/traj.txt" 2> "$tmp/err.txt"
code=$?
set -e
[ "$code" -eq 2 ] || fail "bad relations: expected exit 2, got $code"
grep -q "bad.relations:1:" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "relations file:line"; }
echo "cli_io: ok"
