#!/usr/bin/env bash
# Runs the genflow benchmarks and prints a Markdown table (name, time per iteration, iterations).
# Usage: bench/run_benchmarks.sh [BUILD_DIR] [extra Google Benchmark flags...]
# The build directory must have been configured with GENFLOW_BUILD_BENCHMARKS=ON (the release
# preset does) and built in Release.
set -euo pipefail
build_dir=${1:-build/release}
shift || true
binaries=("$build_dir/bench/genflow_bench" "$build_dir/bench/genflow_flow_bench" "$build_dir/bench/genflow_hausdorff_bench"
  "$build_dir/bench/genflow_match_bench")
for binary in "${binaries[@]}"; do
  if [[ ! -x "$binary" ]]; then
    echo "run_benchmarks.sh: $binary not found; build with: cmake --preset release && cmake --build --preset release" >&2
    exit 2
  fi
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u +%Y-%m-%d)"
echo
echo "| benchmark | time per iteration | iterations |"
echo "|---|---:|---:|"
for binary in "${binaries[@]}"; do
  "$binary" --benchmark_format=csv "$@" 2>/dev/null |
    awk -F, '$1 !~ /^"?name/ && NF > 4 { gsub(/"/, "", $1); printf "| %s | %.2f %s | %s |\n", $1, $3, $5, $2 }'
done
