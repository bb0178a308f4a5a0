#!/usr/bin/env bash
# One step from a clean clone to a built genflow: installs the Debian packages, configures the
# `release` preset and builds the library, the genflow tool, tests, examples and benchmarks into
# build/release. Under CI (CI=true) warnings are errors.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
werror=OFF
if [[ "${CI:-}" == "true" ]]; then
  werror=ON
fi
cmake --preset release -DGENFLOW_WERROR=$werror >/dev/null
cmake --build --preset release
