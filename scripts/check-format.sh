#!/usr/bin/env bash
# Fails if any C++ file is not clang-formatted (.clang-format) or has whitespace errors.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h')
clang-format --dry-run --Werror "${files[@]}"
if git rev-parse --verify -q HEAD >/dev/null; then
  git diff --check HEAD
fi
echo "format: ${#files[@]} files clean"
