#!/usr/bin/env bash
# CLI test: config/default.yaml documents every option with its default; it must equal what
# `gridslam --print-config` prints (regenerate it with that command after changing an option).
set -euo pipefail
bin="$1"
if ! diff <("$bin" --print-config) config/default.yaml; then
  echo "config/default.yaml is stale: regenerate with: gridslam --print-config > config/default.yaml"
  exit 1
fi
echo "cli_default_config: ok"
