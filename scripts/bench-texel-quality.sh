#!/usr/bin/env bash
# Quality at equal bytes of transfer textures against per-vertex transfer on a low-poly scene
# (a two-triangle floor under a floating plate), both against a closed form
# (bench/texel_quality_bench.mjs; docs/transfer-textures.md, "Quality at equal bytes").
# Writes docs/bench/texel-quality.{md,json}. Takes about 5 minutes on the 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake -j "$(nproc)"
work=build/bench-data/texel-quality
rm -rf "$work"
mkdir -p "$work" docs/bench
node bench/texel_quality_bench.mjs build/native/baker/prt-bake "$work" docs/bench/texel-quality.json docs/bench/texel-quality.md "$@"
