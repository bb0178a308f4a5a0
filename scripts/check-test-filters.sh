#!/usr/bin/env bash
# Fails if a name in the asan test preset's exclusion (CMakePresets.json) matches no test of the
# release build: a renamed test would otherwise leave the list and run under ASan unnoticed
# (a 30-second match took 237 s there and brought .ci/run near its 30-minute bound).
# Usage: scripts/check-test-filters.sh [BUILD_DIR]   (default build/release, already built)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build/release}
exclusion=$(grep -o '"exclude": {"name": "[^"]*"' CMakePresets.json | sed 's/.*"name": "//; s/"$//')
if [[ -z "$exclusion" ]]; then
  echo "check-test-filters: no exclusion found in the asan test preset of CMakePresets.json" >&2
  exit 1
fi
mapfile -t tests < <(ctest --test-dir "$build" -N | sed -n 's/^ *Test *#[0-9]*: //p')
if ((${#tests[@]} == 0)); then
  echo "check-test-filters: no tests listed in $build (build it first)" >&2
  exit 1
fi
# One string searched with a here-string: `printf | grep -q` under pipefail fails at random
# when grep stops at its first match and printf dies of SIGPIPE.
listed=$(printf '%s\n' "${tests[@]}")
missing=0
IFS='|' read -r -a names <<<"$exclusion"
for name in "${names[@]}"; do
  if ! grep -q -- "$name" <<<"$listed"; then
    echo "check-test-filters: '$name' in the asan preset's exclusion matches no test" >&2
    missing=1
  fi
done
((missing == 0)) && echo "test filters: ${#names[@]} exclusions each match a test"
exit "$missing"
