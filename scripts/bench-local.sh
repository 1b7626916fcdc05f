#!/usr/bin/env bash
# Spatially-varying lighting benchmark (bench/local_error.cpp, docs/spatially-varying.md): the
# built-in room baked at order 5 for local-sphere and for distant lighting, each compared per
# vertex with a brute-force area integral over a 15-degree cap emitter on the lighting
# sphere, and the two bakes timed against each other in the same run.
# Refreshes docs/bench/local-lighting-error.{md,json}.
#
# Usage: scripts/bench-local.sh [--binary PATH] [extra prt-bench-local-error arguments]
#   --binary PATH  run an already built prt-bench-local-error (a Release build) instead of
#                  configuring and building build/native
# Run it on an otherwise idle machine: the timings record the date and CPU.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

binary=""
if [[ "${1:-}" == "--binary" ]]; then
  [[ $# -ge 2 ]] || { echo "bench-local.sh: --binary needs a path" >&2; exit 2; }
  binary="$2"
  shift 2
fi
if [[ -z "$binary" ]]; then
  scripts/install-deps.sh
  cmake --preset native >/dev/null
  cmake --build --preset native --target prt-bench-local-error -j "$(nproc)"
  binary="build/native/bench/prt-bench-local-error"
fi
[[ -x "$binary" ]] || { echo "bench-local.sh: $binary is not an executable" >&2; exit 2; }

mkdir -p docs/bench
"$binary" --json docs/bench/local-lighting-error.json --md docs/bench/local-lighting-error.md "$@"
