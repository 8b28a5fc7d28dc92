#!/usr/bin/env bash
# Outlier benchmark of the pose-graph optimizer (docs/robust_optimization.md), after Sünderhauf's
# Vertigo: wrong loop closures (random, local, group) are added to a graph, which is optimized
# from the odometry-chained guess; the metric is the mean position error against the clean
# graph's optimum (sgd+gn on the clean graph, same anchor: vertex 0 is fixed in both, so no
# alignment). Prints one markdown row per (graph, kind, count, method, seed).
#
# Usage: bench/robust_outliers.sh [GRIDSLAM] ; environment:
#   GRIDSLAM_DATA (required), GRAPHS="intel.g2o manhattan.g2o", KINDS="random local group",
#   COUNTS="10 100 1000", SEEDS="1", METHODS (';'-separated "label|flags" pairs, see below).
set -euo pipefail
BIN=${1:-build/apps/gridslam}
: "${GRIDSLAM_DATA:?set GRIDSLAM_DATA}"
GRAPHS=${GRAPHS:-"intel.g2o manhattan.g2o"}
KINDS=${KINDS:-"random local group"}
COUNTS=${COUNTS:-"10 100 1000"}
SEEDS=${SEEDS:-"1"}
METHODS=${METHODS:-"sgd+gn|;gn+cauchy (all edges)|--method gn --robust-kernel cauchy --robust-edges all;gn+gnc|--method gn --robust gnc;gn+dcs|--method gn --robust dcs"}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d.get(sys.argv[2], ''))" "$@"; }

echo "| graph | kind | wrong edges | method | seed | mean position error [m] | max [m] | rejected | χ² (kept edges) | CPU [s] |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for graph in $GRAPHS; do
  ref="$WORK/${graph%.g2o}_ref.g2o"
  "$BIN" optimize "$GRIDSLAM_DATA/graphs/$graph" -o "$ref" --init odometry --json > "$WORK/ref.json"
  echo "| $graph | clean optimum | 0 | sgd+gn | - | 0 | 0 | - | $(field "$WORK/ref.json" chi2_final) | $(field "$WORK/ref.json" cpu_seconds) |"
  for kind in $KINDS; do
    for count in $COUNTS; do
      for seed in $SEEDS; do
        IFS=';' read -ra methods <<< "$METHODS"
        for m in "${methods[@]}"; do
          label=${m%%|*}
          flags=${m#*|}
          # shellcheck disable=SC2086
          "$BIN" optimize "$GRIDSLAM_DATA/graphs/$graph" -o "$WORK/out.g2o" --init odometry \
            --add-outliers "$count" --outlier-kind "$kind" --seed "$seed" --reference "$ref" \
            $flags --json > "$WORK/run.json"
          printf "| %s | %s | %s | %s | %s | %.4f | %.3f | %s | %.6g | %.3f |\n" "$graph" "$kind" \
            "$count" "$label" "$seed" "$(field "$WORK/run.json" mean_position_error)" \
            "$(field "$WORK/run.json" max_position_error)" "$(field "$WORK/run.json" rejected_edges)" \
            "$(field "$WORK/run.json" chi2_inliers)" "$(field "$WORK/run.json" cpu_seconds)"
        done
      done
    done
  done
done
