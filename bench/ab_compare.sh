#!/usr/bin/env bash
# Compares two builds of one Google Benchmark binary on this machine, whose timings drift by
# ±15–30 % between runs: the two binaries run alternately, A B A B ..., and each benchmark's best
# (minimum) and median real time per binary are printed with the ratio B/A of the minima. A
# single run of either binary cannot show a 5–10 % change; the interleaved minima can.
#
# Usage: bench/ab_compare.sh BINARY_A BINARY_B [ROUNDS] [extra Google Benchmark flags...]
# Example (a worktree of the last commit as A):
#   git worktree add /tmp/base HEAD && (cd /tmp/base && cmake --preset release &&
#     cmake --build --preset release --target genflow_hausdorff_bench)
#   bench/ab_compare.sh /tmp/base/build/release/bench/genflow_hausdorff_bench \
#     build/release/bench/genflow_hausdorff_bench 15 --benchmark_filter='Aligned$'
set -euo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: bench/ab_compare.sh BINARY_A BINARY_B [ROUNDS] [benchmark flags...]" >&2
  exit 2
fi
binary_a=$1
binary_b=$2
shift 2
rounds=10
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then
  rounds=$1
  shift
fi
for binary in "$binary_a" "$binary_b"; do
  if [[ ! -x "$binary" ]]; then
    echo "ab_compare.sh: $binary is not an executable" >&2
    exit 2
  fi
done
if [[ $rounds -lt 1 ]]; then
  echo "ab_compare.sh: ROUNDS must be at least 1" >&2
  exit 2
fi

samples=$(mktemp)
trap 'rm -f "$samples"' EXIT
for ((round = 0; round < rounds; ++round)); do
  for side in A B; do
    binary=$binary_a
    [[ $side == B ]] && binary=$binary_b
    # CSV: name,iterations,real_time,cpu_time,time_unit,...; the header and error rows are skipped.
    "$binary" --benchmark_format=csv "$@" 2>/dev/null |
      awk -F, -v side="$side" '$1 !~ /^"?name/ && NF > 4 && $3 != "" {
        gsub(/"/, "", $1); print side, $1, $3, $5 }' >>"$samples"
  done
done

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u +%Y-%m-%d)"
echo "A: $binary_a"
echo "B: $binary_b"
echo "$rounds interleaved rounds"
echo
echo "| benchmark | A best | A median | B best | B median | B/A (best) |"
echo "|---|---:|---:|---:|---:|---:|"
sort -k2,2 -k1,1 -k3,3g "$samples" | awk '
  function median(list, count,   sorted, n) { n = split(list, sorted, " ");
    return n % 2 ? sorted[(n + 1) / 2] : (sorted[n / 2] + sorted[n / 2 + 1]) / 2 }
  { key = $2; unit[key] = $4; values[$1, key] = values[$1, key] " " $3
    if (!(key in seen)) { seen[key] = 1; order[++names] = key }
    if (!(($1, key) in best)) best[$1, key] = $3 }
  END {
    for (k = 1; k <= names; ++k) {
      key = order[k]
      if (!(("A", key) in best) || !(("B", key) in best)) continue
      printf "| %s | %.2f %s | %.2f %s | %.2f %s | %.2f %s | %.3f |\n", key,
        best["A", key], unit[key], median(values["A", key]), unit[key],
        best["B", key], unit[key], median(values["B", key]), unit[key],
        best["B", key] / best["A", key]
    }
  }'
