#!/usr/bin/env bash
# Transfer-texture benchmark on the default room (docs/transfer-textures.md). One run, side by
# side:
#   - bake cost of the texel passes against the vertex passes of the same bake (the same
#     directions and bounces): seconds per million texels, ns per receiver and sample;
#   - texture bytes and exit-radiance PSNR per codec setting (prt-bake compress-report
#     --texels), and the vertex pass's for comparison;
#   - frame time at 1280x720 in headless Chromium (SwiftShader unless a GPU is there): vertex
#     PRT and texel PRT of one asset, with still and with moving lights, and texel diffuse +
#     TPFL glossy (the frame bake adds --texel-glossy: visibility order 2n - 1).
# Writes docs/bench/transfer-textures.{md,json}. Takes about 25 minutes on the 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
export NODE_PATH=/usr/share/nodejs
cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-serve -j "$(nproc)"
cmake --preset wasm >/dev/null && cmake --build --preset wasm --target prt_client prt_web_shell -j "$(nproc)"

work=build/bench-data/textures
root=$work/root
mkdir -p "$work" "$root" docs/bench
bake=build/native/baker/prt-bake
size=${PRT_BENCH_TEXTURE_SIZE:-512}
bake_args=(--default --texels --texture-size "$size" --order 5 --samples "${PRT_BENCH_SAMPLES:-1024}" --bounces 2 --quiet)
bake_text="prt-bake ${bake_args[*]}"

# 1. One bake, vertex and texel passes, float32 (the codec's reference), timed by prt-bake.
$bake "${bake_args[@]}" -o "$work/room.prt" --json > "$work/bake.json"

# 2. The codec on the interreflected texel pass and on the vertex pass (the first 8 lightings).
settings=${PRT_BENCH_TEXTURE_SETTINGS:-f16,q16,q8,cpca16,cpca8}
$bake compress-report "$work/room.prt" --texels --settings "$settings" --lightings 8 --json > "$work/codec-texels.json"
$bake compress-report "$work/room.prt" --settings "$settings" --lightings 8 --json > "$work/codec-vertex.json"

# 3. Frame times: the same bake, q16, served to the page (no stale result if it fails).
rm -f "$work/frame.json"
$bake "${bake_args[@]}" --texel-glossy -o "$root/room-texels.prt" --compress q16 --name room-texels
cp -f /usr/share/blender/datafiles/studiolights/world/forest.exr "$root/"
port=$(node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})')
build/native/server/prt-serve --root "$root" --web build/wasm/web/dist --port "$port" --quiet &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for _ in $(seq 100); do curl -sf "http://127.0.0.1:$port/api/scenes" >/dev/null && break; sleep 0.1; done
node bench/web_texel_bench.mjs "http://127.0.0.1:$port" room-texels "$work/frame.json" --order 5 || echo "bench-textures: the page benchmark failed" >&2

node bench/texel_report.mjs "$work/bake.json" "$work/codec-texels.json" "$work/codec-vertex.json" "$work/frame.json" \
  docs/bench/transfer-textures.json docs/bench/transfer-textures.md "$bake_text"
