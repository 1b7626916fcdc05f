#!/usr/bin/env bash
# The demo, from a fresh clone: install what is missing, build, and project an environment
# into spherical harmonics with `prt-bake probe` (the built-in sky, then a real HDR map
# from Debian's blender-data). Later stages turn this into the web demo.
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
echo "More: $bake probe --help"
