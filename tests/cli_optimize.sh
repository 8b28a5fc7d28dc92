#!/usr/bin/env bash
# CLI test of `gridslam optimize` (docs/design.md §2): g2o and TORO in and out, --json fields, chi^2
# lowered, and bad input exiting 2 with file:line and no output written.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# A square loop with a wrong initial guess and one loop closure.
cat > "$tmp/square.g2o" <<'G2O'
VERTEX_SE2 0 0 0 0
VERTEX_SE2 1 1.2 0.1 1.5
VERTEX_SE2 2 0.9 1.3 3.0
VERTEX_SE2 3 -0.2 0.8 -1.4
EDGE_SE2 0 1 1 0 1.5707963 100 0 0 100 0 1000
EDGE_SE2 1 2 1 0 1.5707963 100 0 0 100 0 1000
EDGE_SE2 2 3 1 0 1.5707963 100 0 0 100 0 1000
EDGE_SE2 3 0 1.05 0 1.5707963 100 0 0 100 0 1000
G2O

for method in sgd gn lm sgd+gn; do
  "$bin" optimize "$tmp/square.g2o" -o "$tmp/out_$method.g2o" --method "$method" --json \
    > "$tmp/$method.json"
  for key in chi2_initial chi2_final iterations seconds; do
    grep -q "\"$key\"" "$tmp/$method.json" || { echo "no $key"; cat "$tmp/$method.json"; exit 1; }
  done
  value() { sed -n "s/^ *\"$1\": *\([^,]*\),*$/\1/p" "$tmp/$method.json"; }
  awk -v a="$(value chi2_final)" -v b="$(value chi2_initial)" 'BEGIN { exit !(a < 0.01 * b) }' ||
    { echo "$method did not lower chi2"; cat "$tmp/$method.json"; exit 1; }
  [ "$(value vertices)" = 4 ] && [ "$(value edges)" = 4 ] || { cat "$tmp/$method.json"; exit 1; }
  grep -q "^FIX" "$tmp/out_$method.g2o" && { echo "FIX written for an unfixed graph"; exit 1; }
  [ "$(grep -c '^VERTEX_SE2' "$tmp/out_$method.g2o")" -eq 4 ]
done

# TORO output, read back as input; human-readable output with --verbose.
"$bin" optimize "$tmp/square.g2o" -o "$tmp/out.graph" > /dev/null
grep -q "^EDGE2 0 1" "$tmp/out.graph"
"$bin" optimize "$tmp/out.graph" -o "$tmp/again.g2o" --method gn --verbose > "$tmp/verbose.txt"
grep -q "^chi2_initial=" "$tmp/verbose.txt"
grep -q "^gn " "$tmp/verbose.txt"
grep -q "^chi2_final=" "$tmp/verbose.txt"

# Bad input: exit 2, file:line in the message, nothing written.
sed 's/^EDGE_SE2 2 3 1 0 /EDGE_SE2 2 3 1 zero /' "$tmp/square.g2o" > "$tmp/bad.g2o"
set +e
"$bin" optimize "$tmp/bad.g2o" -o "$tmp/bad_out.g2o" 2> "$tmp/err.txt"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "expected exit 2, got $code"; exit 1; }
grep -q "bad.g2o:7" "$tmp/err.txt" || { cat "$tmp/err.txt"; exit 1; }
[ ! -e "$tmp/bad_out.g2o" ] || { echo "output written for bad input"; exit 1; }
set +e
"$bin" optimize "$tmp/square.g2o" -o "$tmp/out.txt" 2> /dev/null
code=$?
"$bin" optimize "$tmp/missing.g2o" -o "$tmp/out.g2o" 2> /dev/null
code_missing=$?
set -e
[ "$code" -eq 2 ] || { echo "bad output extension: expected exit 2, got $code"; exit 1; }
[ "$code_missing" -eq 2 ] || { echo "missing input: expected exit 2, got $code_missing"; exit 1; }
# Outlier benchmark options (docs/robust_optimization.md): wrong edges added, the error against a
# reference reported; a reference with other vertices exits 2.
"$bin" optimize "$tmp/square.g2o" -o "$tmp/outliers.g2o" --method gn --robust dcs \
  --initialization chordal --add-outliers 2 --outlier-kind random --seed 3 \
  --reference "$tmp/out_gn.g2o" --json > "$tmp/outliers.json"
for key in mean_position_error max_position_error rejected_edges chi2_inliers; do
  grep -q "\"$key\"" "$tmp/outliers.json" || { echo "no $key"; cat "$tmp/outliers.json"; exit 1; }
done
[ "$(grep -c '^EDGE_SE2' "$tmp/outliers.g2o")" -eq 6 ] || { echo "outliers not added"; exit 1; }
head -3 "$tmp/square.g2o" > "$tmp/three.g2o"
set +e
"$bin" optimize "$tmp/square.g2o" -o "$tmp/ref_out.g2o" --reference "$tmp/three.g2o" 2> /dev/null
code=$?
set -e
[ "$code" -eq 2 ] || { echo "reference mismatch: expected exit 2, got $code"; exit 1; }
[ ! -e "$tmp/ref_out.g2o" ] || { echo "output written for a bad reference"; exit 1; }
echo "cli_optimize: ok"
