#!/usr/bin/env bash
# CLI test of the map self-check (docs/self_check.md): `gridslam map` writes a quality block into
# report.json, a summary line and map_quality.png; a good map of a short office run passes, and a
# deliberately broken one (odometry with a strong heading drift, scan matching and loop closing
# off) is flagged suspect.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
field() {  # field KEY report.json: the value of "quality"."KEY" (report.json is indented by 2)
  sed -n "s/^    \"$1\": \(.*\),\{0,1\}$/\1/p" "$2" | sed 's/,$//' | head -1
}

cat > "$tmp/drift.yaml" <<'YAML'
simulation:
  odometry: {rotation_drift: 0.03}
YAML
cat > "$tmp/broken.yaml" <<'YAML'
front_end: {match: false}
loop_closure: {enabled: false}
YAML
"$bin" --config "$tmp/drift.yaml" simulate --world office --duration 400 -o "$tmp/sim" > /dev/null
"$bin" map "$tmp/sim/robot_0.clf" -o "$tmp/good" 2> "$tmp/good.txt"
"$bin" --config "$tmp/broken.yaml" map "$tmp/sim/robot_0.clf" -o "$tmp/bad" 2> "$tmp/bad.txt"
for d in good bad; do
  [ -s "$tmp/$d/map_quality.png" ] || { echo "missing $d/map_quality.png"; exit 1; }
  grep -q 'self-check: score' "$tmp/$d.txt" || { cat "$tmp/$d.txt"; exit 1; }
done
good=$(field score "$tmp/good/report.json")
bad=$(field score "$tmp/bad/report.json")
[ "$(field suspect "$tmp/good/report.json")" = "false" ] || { echo "good map suspect: $good"; exit 1; }
[ "$(field suspect "$tmp/bad/report.json")" = "true" ] || { echo "broken map passes: $bad"; exit 1; }
awk -v g="$good" -v b="$bad" 'BEGIN { exit !(g > 0.85 && g <= 1.0 && b >= 0.0 && b < g - 0.2) }' ||
  { echo "scores good $good bad $bad"; exit 1; }
echo "cli_map_quality: ok ($good vs $bad)"
