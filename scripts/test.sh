#!/usr/bin/env bash
# The whole test suite, from a fresh clone: install what is missing, build the native,
# sanitizer and wasm configurations, run every test. .ci/run calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
export NODE_PATH=/usr/share/nodejs  # Debian's emscripten finds acorn there

jobs=$(nproc)
for preset in native asan wasm; do
  echo "=== $preset: configure and build"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  echo "=== $preset: test"
  ctest --preset "$preset" -j "$jobs"
done
echo "=== all tests passed (native, asan, wasm)"
