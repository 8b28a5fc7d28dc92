#!/usr/bin/env bash
# CLI test of `gridslam align-eval` (issue 5; docs/design.md §3.2): on a simulated lap and a half
# around the office's south-west block it finds correct pairs and no false accept, prints the
# promised JSON keys, writes the per-pair file, and exits 2 on bad input.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '2.2 2.2\n25.0 2.2\n25.0 13.6\n2.2 13.6\n2.2 2.2\n' > "$tmp/loop.txt"
"$bin" simulate --world office --route "$tmp/loop.txt" --duration 200 --seed 3 -o "$tmp/sim" \
  > /dev/null
"$bin" align-eval "$tmp/sim/robot_0.clf" "$tmp/sim/robot_0.relations" --json --negatives 50 \
  --ground-truth "$tmp/sim/robot_0.gt.txt" --pairs "$tmp/pairs.tsv" > "$tmp/out.json"
value() {  # value KEY: the number after "KEY": in the JSON output
  sed -n "s/^  \"$1\": \([-0-9.e]*\),\{0,1\}$/\1/p" "$tmp/out.json"
}
for key in pairs accepted correct wrong precision recall median_error_m median_error_deg \
           ms_per_pair ms_per_keymap negatives false_accepts features_per_keymap; do
  [ -n "$(value $key)" ] || { echo "no key $key"; cat "$tmp/out.json"; exit 1; }
done
[ "$(value pairs)" -ge 5 ] || { echo "too few pairs"; exit 1; }
[ "$(value correct)" -ge $(( $(value pairs) / 2 )) ] || { echo "too few correct"; exit 1; }
[ "$(value wrong)" -eq 0 ] && [ "$(value false_accepts)" -eq 0 ] || { echo "wrong"; exit 1; }
[ "$(value negatives)" -eq 50 ] || { echo "negatives"; exit 1; }
[ "$(grep -c '^positive' "$tmp/pairs.tsv")" -ge 5 ]
"$bin" align-eval "$tmp/sim/robot_0.clf" "$tmp/sim/robot_0.relations" --detector sift \
  --descriptor-image obstacle --no-verify | grep -q '^pairs='
set +e
"$bin" align-eval "$tmp/sim/robot_0.clf" "$tmp/sim/robot_0.relations" --detector nope \
  2> /dev/null
code=$?
set -e
[ "$code" -eq 2 ] || { echo "expected exit 2 for a bad detector, got $code"; exit 1; }
echo "cli_align_eval: ok"
