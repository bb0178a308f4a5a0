#!/usr/bin/env bash
# One step from a clean clone to a built genflow: installs the Debian packages, configures the
# `release` preset and builds the library, the genflow tool, tests, examples and benchmarks into
# build/release. Under CI (CI=true) warnings are errors and the build is a unity build.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
werror=OFF
unity=OFF
if [[ "${CI:-}" == "true" ]]; then
  werror=ON
  unity=ON  # a third less compile time from a clean clone; editing one file rebuilds its batch
fi
cmake --preset release -DGENFLOW_WERROR=$werror -DCMAKE_UNITY_BUILD=$unity >/dev/null
cmake --build --preset release
