#!/usr/bin/env bash
# CLI test: --print-config prints YAML that reads back; bad configuration exits 2.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" --print-config > "$tmp/config.yaml"
grep -q "max_usable_range" "$tmp/config.yaml"
"$bin" --config "$tmp/config.yaml" --print-config > "$tmp/again.yaml"
cmp "$tmp/config.yaml" "$tmp/again.yaml"
printf 'log:\n  no_such_key: 1\n' > "$tmp/bad.yaml"
set +e
"$bin" --config "$tmp/bad.yaml" --print-config 2> "$tmp/err.txt"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "expected exit 2, got $code"; exit 1; }
grep -q "bad.yaml:2" "$tmp/err.txt" || { cat "$tmp/err.txt"; exit 1; }
"$bin" --help > /dev/null
echo "cli_config: ok"
