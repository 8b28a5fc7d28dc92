#!/usr/bin/env bash
# CLI test of the program re-executing itself for huge pages (apps/app_huge_pages.hpp): the
# re-executed program gets the same arguments and gives the same outputs and exit codes as one
# that does not re-execute (GRIDSLAM_HUGE_PAGES=0) and as one whose user set GLIBC_TUNABLES.
set -euo pipefail
bin="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "cli_huge_pages: $*"; exit 1; }

"$bin" --log-level warn simulate --world office --seed 3 --duration 60 -o "$tmp/sim"
log="$tmp/sim/robot_0.clf"
"$bin" --log-level warn map "$log" -o "$tmp/default"
GRIDSLAM_HUGE_PAGES=0 "$bin" --log-level warn map "$log" -o "$tmp/off"
GLIBC_TUNABLES=glibc.malloc.hugetlb=0 "$bin" --log-level warn map "$log" -o "$tmp/user"
for f in trajectory.txt map.pgm graph.g2o; do
  cmp -s "$tmp/default/$f" "$tmp/off/$f" || fail "$f differs with GRIDSLAM_HUGE_PAGES=0"
  cmp -s "$tmp/default/$f" "$tmp/user/$f" || fail "$f differs with GLIBC_TUNABLES set"
done

# Exit codes and messages pass through the re-execution.
for env in "" "GRIDSLAM_HUGE_PAGES=0"; do
  set +e
  env $env "$bin" map "$tmp/no-such-log.clf" -o "$tmp/x" 2> "$tmp/err.txt"
  code=$?
  set -e
  [ "$code" -eq 2 ] || fail "a missing log exited $code (${env:-default})"
  grep -q "no-such-log.clf" "$tmp/err.txt" || fail "the error does not name the log (${env:-default})"
done
echo "cli_huge_pages: ok"
