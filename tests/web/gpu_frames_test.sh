#!/usr/bin/env bash
# prt-gpu-frames (web/native: the client's renderer on native OpenGL ES, docs/web-client.md
# "Frame times on a GPU") on this machine's EGL, which without a GPU is Mesa's llvmpipe.
# Usage: gpu_frames_test.sh CASE PRT_GPU_FRAMES PRT_BAKE WORK_DIR
#   glossy: a glossy room bake renders every setting, and the GPU's per-vertex glossy
#           radiance matches the CPU reference (the tool's own check, which exits 1 otherwise);
#   errors: bad arguments exit 2 and a bad asset exits 1, each naming the problem.
set -euo pipefail
case_name=$1 frames=$2 bake=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# expect STATUS PATTERN CMD...: CMD exits with STATUS and its stderr matches PATTERN.
expect() {
  local want=$1 pattern=$2 status=0
  shift 2
  timeout 300 "$@" >out.txt 2>err.txt || status=$?
  [[ $status == "$want" ]] || fail "'$*' exited $status, not $want: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "'$*' did not say '$pattern': $(cat err.txt)"
}

case $case_name in
  glossy)
    timeout 300 "$bake" --default -o room.prt --order 3 --samples 16 --bounces 1 --glossy --compress cpca8@0.02 --quiet
    timeout 600 "$frames" room.prt --width 96 --height 54 --frames 1 --rounds 1 > result.json
    node - result.json <<'JS'
const r = JSON.parse(require('fs').readFileSync(process.argv[2], 'utf8'));
const want = ['lambert', 'diffuse PRT', 'diffuse PRT, lights moving', 'diffuse + glossy, camera moving',
  'diffuse + glossy, lights moving', 'glossy: cluster table alone', 'glossy: table + fused step (lights moving)',
  'glossy: table + transferred radiance + view step',
  'glossy: view step alone'];
const names = r.rows.map((x) => x.setting);
if (JSON.stringify(names) !== JSON.stringify(want)) throw new Error(`rows ${JSON.stringify(names)}`);
for (const x of r.rows) if (!(x.ms > 0 && Number.isFinite(x.ms))) throw new Error(`${x.setting}: ${x.ms} ms`);
if (r.vertices !== 20434 || r.order !== 3 || r.glossy.bands !== 3 || r.glossy.channels !== 3) throw new Error(JSON.stringify(r));
const c = r.glossy_check;
if (!(c.peak > 0 && c.max_abs_error <= 1e-4 * c.peak) || JSON.stringify(c.steps) !== '["fused","view"]') throw new Error(`glossy check ${JSON.stringify(c)}`);
if (!/OpenGL ES 3/.test(r.version)) throw new Error(`context ${r.version}`);
console.log(`${r.renderer}: glossy error ${c.max_abs_error} of peak ${c.peak}`);
JS
    ;;
  errors)
    expect 2 "no ASSET given" "$frames"
    expect 2 "unknown option --fast" "$frames" x.prt --fast 1
    expect 2 "--frames takes an integer" "$frames" x.prt --frames 0
    expect 2 "--mode takes" "$frames" x.prt --mode glossy
    expect 1 "cannot open 'missing.prt'" "$frames" missing.prt
    head -c 300 /dev/urandom > junk.prt
    expect 1 "not an asset file" "$frames" junk.prt --width 16 --height 16
    [[ ! -s out.txt ]] || fail "a failed run printed results"
    ;;
  *) fail "unknown case '$case_name'" ;;
esac
echo "gpu_frames_$case_name: ok"
