#!/usr/bin/env bash
# The demo, from a fresh clone: install what is missing, build the native tools and the
# wasm client, bake the built-in room scene if its asset is missing or older than the
# baker, and serve it with prt-serve on 127.0.0.1. Open the printed URL.
# PORT=8080 by default; PRT_DEMO_SAMPLES (default 1024) trades bake time for noise.
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
asset=$root/default-room.prt
mkdir -p "$root"
if [[ ! -f $asset || $bake -nt $asset ]]; then
  echo "=== baking the built-in room scene (Embree: unshadowed, shadowed, interreflected)"
  "$bake" --default -o "$asset" --samples "${PRT_DEMO_SAMPLES:-1024}"
else
  echo "=== $asset is up to date"
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
