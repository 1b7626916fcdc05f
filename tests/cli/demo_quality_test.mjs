// The demo's bake against an 8192-sample float32 bake of the same room (issue: the demo must show
// no Monte Carlo or codec patches): the room baked with the demo's own settings
// (scripts/demo_bake_settings.sh, read here, so the test checks what scripts/demo.sh bakes) and
// shaded by `prt-bake shade` under two of blender-data's maps, per vertex:
//   - relative RMS error of the exit radiance over all vertices and channels: <= 1%;
//   - the patch error: per vertex, the luminance error averaged over the vertices within 15 cm,
//     over the averaged reference luminance (vertices whose neighbourhood is darker than 0.05
//     left out: relative error there is noise over nothing); its 99th percentile <= 1%, about
//     the smallest contrast a patch that size shows on a display.
// Usage: node demo_quality_test.mjs PRT_BAKE SETTINGS_SH WORLD_DIR WORK_DIR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

const [prtBake, settingsSh, worldDir, workDir] = process.argv.slice(2);
if (!workDir) {
  console.error('usage: node demo_quality_test.mjs PRT_BAKE SETTINGS_SH WORLD_DIR WORK_DIR');
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });

// The demo's defaults, as bash reads them with the overrides unset.
const env = { ...process.env };
delete env.PRT_DEMO_SAMPLES;
delete env.PRT_DEMO_COMPRESS;
const [samples, compress] = execFileSync('bash', ['-c', `source "${settingsSh}" && echo "$demo_samples $demo_compress"`],
  { encoding: 'utf8', env }).trim().split(' ');

const bake = (out, args) => execFileSync(prtBake, ['--default', '-o', out, '--quiet', ...args], { stdio: ['ignore', 'ignore', 'inherit'] });
const demo = path.join(workDir, 'demo.prt'), reference = path.join(workDir, 'reference.prt');
bake(demo, ['--samples', samples, '--compress', compress]);
bake(reference, ['--samples', '8192']);
const shade = (asset, map) => JSON.parse(execFileSync(prtBake, ['shade', asset, '--light', path.join(worldDir, map), '--json'],
  { encoding: 'utf8', maxBuffer: 1 << 28 })).vertices;

// Per-vertex patch error (see the header), one value per vertex with a lit neighbourhood.
function patchErrors(got, want, radius) {
  const lum = (c) => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  const cellOf = (p) => p.map((x) => Math.floor(x / radius));
  const cells = new Map();
  want.forEach((v, i) => {
    const k = cellOf(v.position).join(',');
    if (!cells.has(k)) cells.set(k, []);
    cells.get(k).push(i);
  });
  const out = [];
  for (const v of want) {
    const c = cellOf(v.position);
    let error = 0, sum = 0, count = 0;
    for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
      for (const j of cells.get([c[0] + dx, c[1] + dy, c[2] + dz].join(',')) || []) {
        const q = want[j].position;
        if ((q[0] - v.position[0]) ** 2 + (q[1] - v.position[1]) ** 2 + (q[2] - v.position[2]) ** 2 > radius * radius) continue;
        error += lum(got[j].radiance) - lum(want[j].radiance);
        sum += lum(want[j].radiance);
        count++;
      }
    }
    if (sum / count > 0.05) out.push(Math.abs(error / sum));
  }
  return out;
}

let failed = 0;
const check = (ok, what) => {
  if (!ok) {
    failed++;
    console.error(`FAIL: ${what}`);
  }
};
for (const map of ['city.exr', 'forest.exr']) {
  const got = shade(demo, map), want = shade(reference, map);
  check(got.length === want.length && got.length === 20434, `${map}: ${got.length} and ${want.length} vertices`);
  let se = 0, sr = 0;
  for (let i = 0; i < want.length; i++) {
    check(got[i].position.every((x, k) => x === want[i].position[k]), `${map}: vertex ${i} moved`);
    for (let c = 0; c < 3; c++) {
      se += (got[i].radiance[c] - want[i].radiance[c]) ** 2;
      sr += want[i].radiance[c] ** 2;
    }
  }
  const rms = Math.sqrt(se / sr);
  const patches = patchErrors(got, want, 0.15).sort((a, b) => a - b);
  const p99 = patches[Math.floor(0.99 * (patches.length - 1))], max = patches[patches.length - 1];
  console.log(`${map}: demo (${samples} samples, ${compress}) vs 8192 samples: RMS ${(100 * rms).toFixed(3)}%, ` +
              `patch error 99th percentile ${(100 * p99).toFixed(3)}%, largest ${(100 * max).toFixed(3)}%`);
  check(rms <= 0.01, `${map}: RMS error ${(100 * rms).toFixed(3)}% > 1%`);
  check(p99 <= 0.01, `${map}: patch error 99th percentile ${(100 * p99).toFixed(3)}% > 1%`);
}
console.log(failed ? `${failed} checks failed` : 'demo quality: ok');
process.exit(failed ? 1 : 0);
