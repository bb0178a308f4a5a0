#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, `fuzz` preset) and runs each for SECONDS (default 10)
# from the seeds in fuzz/corpus, two at a time. A crash, leak, hang or sanitizer report fails.
# CI runs it briefly; before a release, run it for 600 s a target (docs/building.md).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds=${1:-10}
targets=(ply off stl obj xyz_points ply_points landmarks reference_points part_tree part_labels
         part_weights correspondences pairs)
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target "${targets[@]/%/_fuzz}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {
  local target=$1
  mkdir -p "$work/$target"
  cp fuzz/corpus/"$target"/* "$work/$target/"
  if ! TMPDIR="$work" build/fuzz/fuzz/"${target}"_fuzz -max_total_time="$seconds" -max_len=4096 \
      -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$work/$target-" "$work/$target" \
      >"$work/$target.log" 2>&1; then
    echo "fuzz: $target failed:" >&2
    tail -40 "$work/$target.log" >&2
    return 1
  fi
  echo "fuzz: $target $(grep -o 'Done [0-9]* runs' "$work/$target.log")"
}
status=0
for ((k = 0; k < ${#targets[@]}; k += 2)); do
  run "${targets[k]}" & first=$!
  if ((k + 1 < ${#targets[@]})); then
    run "${targets[k + 1]}" & second=$!
    wait $second || status=1
  fi
  wait $first || status=1
done
exit $status
