#!/usr/bin/env bash
# One step from a clean clone to a built genflow: installs the Debian packages, configures the
# `release` preset and builds the library, the genflow tool, the Python package, tests, examples
# and benchmarks into build/release, and has Debian's Python find the package (`import genflow`).
# Under CI (CI=true) warnings are errors, the build is a unity build, and Python is left as it
# is (the tests point it at the package themselves).
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
if [[ "${CI:-}" != "true" ]]; then
  scripts/python-path.sh
fi
