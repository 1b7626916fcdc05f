#!/usr/bin/env bash
# The demo, from a fresh clone: install what is missing, build, project environments into
# spherical harmonics with `prt-bake probe` (the built-in sky, then a real HDR map from
# Debian's blender-data), bake the built-in room scene and show what the asset holds.
# Later stages turn this into the web demo.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset native >/dev/null
cmake --build --preset native --target prt-bake -j "$(nproc)"

bake=build/native/baker/prt-bake
echo
echo "=== order-3 SH of the built-in sky (radiance, RGB)"
"$bake" probe --builtin sky --order 3

exr=$(ls /usr/share/blender/datafiles/studiolights/world/*.exr 2>/dev/null | head -n 1 || true)
if [[ -n "$exr" ]]; then
  echo
  echo "=== order-3 SH of $exr"
  "$bake" probe "$exr" --order 3
fi
echo
echo "=== baking the built-in room scene (Embree, order 5, 1024 samples, interreflection)"
mkdir -p build/demo
"$bake" --default -o build/demo/room.prt
"$bake" info build/demo/room.prt
echo
echo "More: $bake --help, $bake probe --help, docs/baker.md"
