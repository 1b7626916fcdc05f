#!/usr/bin/env bash
# Builds the native Release tree and runs the SH basis evaluation benchmark (prt-bench-sh),
# refreshing docs/bench/sh-eval.json and docs/bench/sh-eval.md.
#
# Usage: scripts/bench-sh.sh [--binary PATH] [extra prt-bench-sh arguments, e.g. --reps 30]
#   --binary PATH  run an already built prt-bench-sh instead of configuring and building
#                  build/native (it must be a Release build for the numbers to mean anything)
# Run it on an otherwise idle machine; the results record the date, CPU and compiler.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

binary=""
if [[ "${1:-}" == "--binary" ]]; then
  [[ $# -ge 2 ]] || { echo "bench-sh.sh: --binary needs a path" >&2; exit 2; }
  binary="$2"
  shift 2
fi

if [[ -z "$binary" ]]; then
  build_dir="$root/build/native"
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release
  ninja -C "$build_dir" prt-bench-sh
  binary="$build_dir/bench/prt-bench-sh"
fi
[[ -x "$binary" ]] || { echo "bench-sh.sh: $binary is not an executable" >&2; exit 2; }

mkdir -p docs/bench
# prt-bench-sh writes each file to a temporary name and renames it, so a failed or
# interrupted run leaves the previous results in place.
"$binary" --json docs/bench/sh-eval.json --md docs/bench/sh-eval.md "$@"
echo "bench-sh.sh: wrote docs/bench/sh-eval.json and docs/bench/sh-eval.md"
