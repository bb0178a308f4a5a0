#!/usr/bin/env bash
# Installs everything genflow needs from Debian 12 packages. Idempotent: does nothing when all
# packages are present; otherwise runs apt-get (as root, or through sudo).
# --anchors: also the speed harness's CGAL anchor (libcgal-dev, header-only, for
# bench/anchors/hausdorff_anchor; genflow itself never links it).
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libsuitesparse-dev libnanoflann-dev libmeshoptimizer-dev libcli11-dev nlohmann-json3-dev
  libspectra-dev
  libtinygltf-dev libjs-three
  pybind11-dev python3-dev python3-numpy python3-scipy python3-distributed
  libgtest-dev libbenchmark-dev libpng-dev chromium
  libopenblas0-pthread
  clang clang-format libfuzzer-14-dev
)
case "${1:-}" in
  "") ;;
  --anchors) packages+=(libcgal-dev) ;;
  *)
    echo "install-deps: unknown option '$1' (the only one is --anchors)" >&2
    exit 2
    ;;
esac
missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
