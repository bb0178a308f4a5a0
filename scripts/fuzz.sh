#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, `fuzz` preset) and runs each for SECONDS (default 20)
# from the seeds in fuzz/corpus, two at a time. A crash, leak, hang or sanitizer report fails.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds=${1:-20}
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target ply_fuzz off_fuzz stl_fuzz obj_fuzz
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {
  local format=$1
  mkdir -p "$work/$format"
  cp fuzz/corpus/"$format"/* "$work/$format/"
  if ! build/fuzz/fuzz/"${format}"_fuzz -max_total_time="$seconds" -max_len=4096 -timeout=10 \
      -rss_limit_mb=2048 -artifact_prefix="$work/$format-" "$work/$format" >"$work/$format.log" 2>&1; then
    echo "fuzz: $format parser failed:" >&2
    tail -40 "$work/$format.log" >&2
    return 1
  fi
  echo "fuzz: $format $(grep -o 'Done [0-9]* runs' "$work/$format.log")"
}
status=0
run ply & p1=$!; run off & p2=$!
wait $p1 || status=1; wait $p2 || status=1
run stl & p1=$!; run obj & p2=$!
wait $p1 || status=1; wait $p2 || status=1
exit $status
