#!/usr/bin/env bash
# CI slice of the robustness matrix (issue 16 part 7; scripts/bench_robustness, docs/robustness.md):
# the first 300 s of intel, clean and with a 25-85 deg odometry yaw glitch every 20 s mapped with
# scan matching disabled (front_end.match: false, so nothing repairs the glitches). The map
# self-check (report.json `quality`) must pass the clean map and flag the broken one as suspect,
# with a lower score; the relation error confirms which map is broken. Skipped (exit 77) without
# the shared data or python3.
set -euo pipefail
bin="$1"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="${GRIDSLAM_DATA:-$root/../shared/data}"
log="$data/logs/intel.reconstructed.clf"
rel="$data/relations/intel.relations"
[ -f "$log" ] && [ -f "$rel" ] || { echo "skipped: no $log (set GRIDSLAM_DATA)"; exit 77; }
command -v python3 > /dev/null || { echo "skipped: no python3"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metric() {  # metric NAME "eval output": the value of NAME=...
  echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | head -1
}
quality() {  # quality REPORT KEY: report.json's quality.KEY (fails when there is no quality block)
  python3 - "$1" "$2" << 'PY'
import json, sys
q = json.load(open(sys.argv[1])).get("quality")
if not isinstance(q, dict) or sys.argv[2] not in q:
    sys.exit("%s: no quality.%s (the map self-check of issue 16)" % (sys.argv[1], sys.argv[2]))
v = q[sys.argv[2]]
print(str(v).lower() if isinstance(v, bool) else v)
PY
}

"$bin" perturb "$log" -o "$tmp/clean.clf" --duration 300 > /dev/null
"$bin" perturb "$log" -o "$tmp/broken.clf" --duration 300 --glitch-period 20 \
  --glitch-yaw-fraction 1 --seed 1 > /dev/null
printf 'front_end:\n  match: false\n' > "$tmp/no_matching.yaml"
"$bin" map "$tmp/clean.clf" -o "$tmp/clean" 2> "$tmp/clean.err" || { cat "$tmp/clean.err"; exit 1; }
"$bin" --config "$tmp/no_matching.yaml" map "$tmp/broken.clf" -o "$tmp/broken" 2> "$tmp/broken.err" ||
  { cat "$tmp/broken.err"; exit 1; }

# The broken map is broken: its rotation error is many times the clean map's.
clean=$("$bin" eval "$rel" "$tmp/clean/trajectory.txt" 2> /dev/null)
broken=$("$bin" eval "$rel" "$tmp/broken/trajectory.txt" 2> /dev/null)
awk -v a="$(metric rotation_mean_deg "$clean")" -v b="$(metric rotation_mean_deg "$broken")" \
  'BEGIN { exit !(b > 5 * a) }' || { echo "not broken: $clean / $broken"; exit 1; }

# The self-check sees it without ground truth.
clean_suspect=$(quality "$tmp/clean/report.json" suspect)
broken_suspect=$(quality "$tmp/broken/report.json" suspect)
clean_score=$(quality "$tmp/clean/report.json" score)
broken_score=$(quality "$tmp/broken/report.json" score)
echo "clean: score $clean_score suspect $clean_suspect; broken: score $broken_score suspect $broken_suspect"
[ "$clean_suspect" = "false" ] || { echo "the clean map is flagged suspect"; exit 1; }
[ "$broken_suspect" = "true" ] || { echo "the broken map is not flagged suspect"; exit 1; }
awk -v a="$clean_score" -v b="$broken_score" 'BEGIN { exit !(a > b && a >= 0 && a <= 1 && b >= 0) }' ||
  { echo "scores: clean $clean_score, broken $broken_score"; exit 1; }

# With the default front end the same glitches are caught and matched away (issue 18): the map
# is as good as the clean one, and the run says how many increments it replaced.
"$bin" map "$tmp/broken.clf" -o "$tmp/repaired" 2> "$tmp/repaired.err" ||
  { cat "$tmp/repaired.err"; exit 1; }
grep -q "odometry increments were implausible" "$tmp/repaired.err" ||
  { cat "$tmp/repaired.err"; echo "no glitch warning"; exit 1; }
repaired=$("$bin" eval "$rel" "$tmp/repaired/trajectory.txt" 2> /dev/null)
awk -v a="$(metric translation_mean "$clean")" -v b="$(metric translation_mean "$repaired")" \
  'BEGIN { exit !(b < 1.5 * a + 0.005) }' || { echo "glitches not repaired: $clean / $repaired"; exit 1; }
overruled=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['odometry']['overruled'])" \
  "$tmp/repaired/report.json")
[ "$overruled" -ge 10 ] || { echo "only $overruled increments overruled"; exit 1; }
[ "$(quality "$tmp/repaired/report.json" suspect)" = "false" ] || { echo "repaired map suspect"; exit 1; }
echo "cli_robustness_slice: ok"
