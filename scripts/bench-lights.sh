#!/usr/bin/env bash
# Light-update benchmark: cube-map render + SH projection per light change in headless
# Chromium (32²/64²/128² per face, orders 3 and 5, GPU and CPU paths) against three.js's
# CubeCamera + LightProbeGenerator in the same page, and the analytic path for 1..256 random
# lights at orders 3, 5 and 8 against the cube at 64². Writes docs/bench/light-update.{md,json}.
# NATIVE_DIR / WASM_DIR pick other build trees (default build/native, build/wasm).
set -euo pipefail
cd "$(dirname "$0")/.."

native=${NATIVE_DIR:-build/native}
wasm=${WASM_DIR:-build/wasm}
export NODE_PATH=/usr/share/nodejs
if [[ -z ${NATIVE_DIR:-} ]]; then
  scripts/install-deps.sh
  cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-serve -j "$(nproc)"
  cmake --preset wasm >/dev/null && cmake --build --preset wasm -j "$(nproc)"
fi
[[ -f web/node_modules/three/examples/jsm/lights/LightProbeGenerator.js ]] || (cd web && npm ci --ignore-scripts --no-audit --no-fund)

root=build/bench-data/lights-root
mkdir -p "$root" docs/bench
# The built-in room at orders 3, 5 and 8; few samples: the benchmark times the lights, not the transfer.
lighting=()
if "$native/baker/prt-bake" --default --help 2>&1 | grep -q -- '--lighting'; then lighting=(--lighting local); fi
for order in 3 5 8; do
  "$native/baker/prt-bake" --default -o "$root/lights$order.prt" --name "lights$order" --order "$order" --samples 64 --passes interreflected \
    --bounces 1 --quiet "${lighting[@]}"
done

node bench/web_lights_bench.mjs "$native/server/prt-serve" "$wasm/web/dist" "$root" docs/bench/light-update.json docs/bench/light-update.md
