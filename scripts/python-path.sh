#!/usr/bin/env bash
# Has Debian's Python (/usr/bin/python3) import genflow from this clone's build/release/python:
# writes genflow.pth, naming that directory, into its site directory (as root, or through
# sudo). Run by scripts/setup.sh; run again after moving the clone.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  sudo="sudo"
fi
$sudo mkdir -p "$site"
echo "$PWD/build/release/python" | $sudo tee "$site/genflow.pth" >/dev/null
