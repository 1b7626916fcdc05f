// Quality at equal bytes: transfer textures against per-vertex transfer on a low-poly scene,
// both against a closed-form reference (docs/transfer-textures.md, "Quality at equal bytes").
//
// Scene: a floor [-2, 2]^2 (albedo 0.8) under a square plate of side 1.2 floating 0.5 m above
// it. Under constant unit radiance the shadowed pass's exit radiance at a floor point is
// albedo x (1 - F), F the plate's form factor from the point (Lambert's polygon formula, exact
// for a polygon wholly above the point's horizon). The texel bakes keep the floor at two
// triangles and vary the atlas side; the vertex bakes refine the floor into a grid. Each is
// evaluated as a client draws it (bilinear in the atlas; linear over each triangle) at a
// 200 x 200 grid of points over [-1.5, 1.5]^2 of the floor, and scored by PSNR against the
// reference (peak = the albedo). Bytes: the whole asset file and the shadowed pass alone.
//
// Usage: node bench/texel_quality_bench.mjs PRT_BAKE WORK_DIR OUT_JSON OUT_MD [--samples N]
//        [--settings none,q16,cpca16@0.005] [--sizes 32,64,...] [--cells 8,16,...]
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { gltfText } from '../tests/web/floor_scene_gltf.mjs';

const [prtBake, workDir, outJson, outMd, ...rest] = process.argv.slice(2);
if (!prtBake || !outMd) {
  console.error('usage: node bench/texel_quality_bench.mjs PRT_BAKE WORK_DIR OUT_JSON OUT_MD [--samples N] [--settings a,b] [--sizes a,b] [--cells a,b]');
  process.exit(2);
}
const option = (name, fallback) => {
  const i = rest.indexOf(name);
  return i >= 0 ? rest[i + 1] : fallback;
};
const samples = Number(option('--samples', '8192'));
const settings = option('--settings', 'none,q16,cpca16@0.005').split(',');
const sizes = option('--sizes', '32,64,128,256').split(',').map(Number);
const cellCounts = option('--cells', '8,16,32,64,128,256').split(',').map(Number);
fs.mkdirSync(workDir, { recursive: true });

const HALF = 2, ALBEDO = 0.8, PLATE = { half: 0.6, height: 0.5 };
// The atlas: the floor over u in [0, 0.75] (the plate's chart beside it, 2 texels away at 32).
const FLOOR_U = 0.75, PLATE_UV = [0.8125, 1, 0, 0.1875];

// The floor as a grid of cells x cells quads (two triangles each, split along the b-c
// diagonal), facing +y, its chart u = FLOOR_U (x + 2) / 4, v = (z + 2) / 4.
function floorPart(cells) {
  const part = { positions: [], normals: [], uv: [], indices: [], color: [ALBEDO, ALBEDO, ALBEDO, 1] };
  for (let j = 0; j <= cells; j++)
    for (let i = 0; i <= cells; i++) {
      part.positions.push(-HALF + (2 * HALF * i) / cells, 0, -HALF + (2 * HALF * j) / cells);
      part.normals.push(0, 1, 0);
      part.uv.push((FLOOR_U * i) / cells, j / cells);
    }
  for (let j = 0; j < cells; j++)
    for (let i = 0; i < cells; i++) {
      const a = j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
      part.indices.push(a, c, b, b, c, d);  // counter-clockwise seen from +y
    }
  return part;
}

// The plate facing down (a thin occluder: any ray hitting it is blocked).
function platePart() {
  const h = PLATE.half, y = PLATE.height, [u0, u1, v0, v1] = PLATE_UV;
  return {
    positions: [-h, y, -h, h, y, -h, h, y, h, -h, y, h], normals: [0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0],
    uv: [u0, v0, u1, v0, u1, v1, u0, v1], indices: [0, 1, 2, 0, 2, 3], color: [ALBEDO, ALBEDO, ALBEDO, 1],
  };
}

// Closed form: albedo x (1 - F) at floor point (x, 0, z), F = (1/2pi) |sum_i theta_i
// (unit(r_i x r_i+1) . n)|, r_i the unit directions to the plate's corners, n = +y.
function reference(x, z) {
  const h = PLATE.half, corners = [[-h, -h], [h, -h], [h, h], [-h, h]];
  const r = corners.map(([cx, cz]) => {
    const d = [cx - x, PLATE.height, cz - z], l = Math.hypot(...d);
    return d.map((c) => c / l);
  });
  let sum = 0;
  for (let i = 0; i < 4; i++) {
    const a = r[i], b = r[(i + 1) % 4];
    const c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const theta = Math.acos(Math.min(1, Math.max(-1, a[0] * b[0] + a[1] * b[1] + a[2] * b[2])));
    sum += theta * (c[1] / Math.hypot(...c));
  }
  return ALBEDO * (1 - Math.abs(sum) / (2 * Math.PI));
}

const GRID = 200, REGION = 1.5;
const points = [];
for (let j = 0; j < GRID; j++)
  for (let i = 0; i < GRID; i++) {
    const x = -REGION + (2 * REGION * (i + 0.5)) / GRID, z = -REGION + (2 * REGION * (j + 0.5)) / GRID;
    points.push([x, z, reference(x, z)]);
  }

function score(evaluate) {
  let se = 0, worst = 0;
  for (const [x, z, want] of points) {
    const e = evaluate(x, z) - want;
    if (!Number.isFinite(e)) throw new Error(`no value at floor point (${x}, ${z})`);
    se += e * e;
    worst = Math.max(worst, Math.abs(e));
  }
  const rmse = Math.sqrt(se / points.length);
  return { psnr: 20 * Math.log10(ALBEDO / rmse), rmse, maxError: worst };
}

function bakeAsset(name, cells, extra) {
  const gltf = path.join(workDir, `${name}.gltf`), asset = path.join(workDir, `${name}.prt`);
  fs.writeFileSync(gltf, gltfText([floorPart(cells), platePart()]));
  const t0 = Date.now();
  execFileSync(prtBake, [gltf, '-o', asset, '--order', '3', '--samples', String(samples), '--bounces', '0', '--passes', 'shadowed', '--quiet', ...extra]);
  const seconds = (Date.now() - t0) / 1000;
  const info = JSON.parse(execFileSync(prtBake, ['info', asset, '--json'], { encoding: 'utf8' }));
  return { asset, info, seconds };
}

const shade = (asset, texels) => JSON.parse(execFileSync(prtBake, ['shade', asset, '--light', 'constant', '--pass', 'shadowed', '--json',
  ...(texels ? ['--texels'] : [])], { encoding: 'utf8', maxBuffer: 1 << 30 }));
const compressArgs = (setting) => (setting === 'none' ? [] : ['--compress', setting]);
const passBytes = (info, domain) => info.passes.find((p) => p.kind === 'shadowed' && p.domain === domain).bytes;

const rows = [];
for (const setting of settings) {
  for (const size of sizes) {
    const { asset, info, seconds } = bakeAsset(`texel-${size}-${setting}`, 1, // The chart layout above must be the one atlas (it is valid from 32 a side).
      ['--texels', '--texture-size', String(size), '--unwrap', 'never', '--texture-sets', 'scene', ...compressArgs(setting)]);
    const out = shade(asset, true);
    const grid = new Float64Array(size * size).fill(NaN);
    for (const t of out.texels) if (t.atlas === 0) grid[t.y * size + t.x] = t.radiance[0];
    const at = (x, y) => grid[y * size + x];
    const s = score((x, z) => {
      const px = FLOOR_U * ((x + HALF) / (2 * HALF)) * size - 0.5, py = ((z + HALF) / (2 * HALF)) * size - 0.5;
      const x0 = Math.floor(px), y0 = Math.floor(py), fx = px - x0, fy = py - y0;
      return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) + fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
    });
    rows.push({ domain: 'texel', setting, resolution: `${size}² atlas`, receivers: info.texels, assetBytes: info.bytes,
      passBytes: passBytes(info, 'texel'), bakeSeconds: seconds, ...s });
    console.log(JSON.stringify(rows.at(-1)));
  }
  for (const cells of cellCounts) {
    const { asset, info, seconds } = bakeAsset(`vertex-${cells}-${setting}`, cells, compressArgs(setting));
    const out = shade(asset, false);
    const key = (x, z) => `${x.toFixed(5)},${z.toFixed(5)}`;
    const byPosition = new Map();
    for (const v of out.vertices) if (v.position[1] === 0) byPosition.set(key(v.position[0], v.position[2]), v.radiance[0]);
    const value = (i, j) => byPosition.get(key(-HALF + (2 * HALF * i) / cells, -HALF + (2 * HALF * j) / cells));
    const s = score((x, z) => {
      const gx = ((x + HALF) / (2 * HALF)) * cells, gz = ((z + HALF) / (2 * HALF)) * cells;
      const i = Math.min(cells - 1, Math.floor(gx)), j = Math.min(cells - 1, Math.floor(gz)), sx = gx - i, tz = gz - j;
      const a = value(i, j), b = value(i + 1, j), c = value(i, j + 1), d = value(i + 1, j + 1);
      return sx + tz <= 1 ? a + sx * (b - a) + tz * (c - a) : d + (1 - sx) * (c - d) + (1 - tz) * (b - d);
    });
    rows.push({ domain: 'vertex', setting, resolution: `${cells}² cells`, receivers: info.vertices, assetBytes: info.bytes,
      passBytes: passBytes(info, 'vertex'), bakeSeconds: seconds, ...s });
    console.log(JSON.stringify(rows.at(-1)));
  }
}

const cpu = os.cpus()[0]?.model ?? 'unknown CPU';
const meta = { date: new Date().toISOString(), machine: `${cpu}, ${os.cpus().length} threads, load average ${os.loadavg().map((l) => l.toFixed(1)).join(' ')}`,
  samples, order: 3, scene: 'floor [-2,2]^2 under a 1.2 m plate 0.5 m up', evaluation: `${GRID}x${GRID} floor points over [-${REGION},${REGION}]^2` };
fs.writeFileSync(outJson, `${JSON.stringify({ ...meta, rows }, null, 1)}\n`);

// At equal bytes: for each texel row, the vertex row of the same setting whose asset is
// nearest in size (log ratio), side by side.
const kib = (b) => (b / 1024).toFixed(1);
const lines = [
  '# Transfer textures: quality at equal bytes on a low-poly scene',
  '',
  `Generated by \`scripts/bench-texel-quality.sh\` (bench/texel_quality_bench.mjs). One run.`,
  '',
  `- Date: ${meta.date}`,
  `- Machine: ${meta.machine}`,
  `- Scene: the floor [-2, 2]² (albedo 0.8) under a square plate of side 1.2 m, 0.5 m above it; the texel bakes keep the floor at 2 triangles, the vertex bakes refine it into a grid (the plate: 2 triangles in both).`,
  `- Bake: \`prt-bake SCENE --order 3 --samples ${samples} --bounces 0 --passes shadowed\` (+ \`--texels --texture-size N\` for the texel rows).`,
  '- Reference: closed form, albedo × (1 − F) under constant unit radiance, F the plate\'s form factor (Lambert\'s polygon formula).',
  `- Error: at ${meta.evaluation}, each representation interpolated as the client draws it (bilinear in the atlas; linear over a triangle); PSNR with the albedo as peak.`,
  '',
  '| domain | codec | resolution | receivers | asset KiB | pass KiB | PSNR dB | max error | bake s |',
  '|---|---|---|---:|---:|---:|---:|---:|---:|',
  ...rows.map((r) => `| ${r.domain} | ${r.setting} | ${r.resolution} | ${r.receivers} | ${kib(r.assetBytes)} | ${kib(r.passBytes)} | ${r.psnr.toFixed(1)} | ${r.maxError.toFixed(4)} | ${r.bakeSeconds.toFixed(1)} |`),
  '',
  '## Side by side at about equal asset bytes',
  '',
  '| codec | texel | asset KiB | PSNR dB | nearest vertex | asset KiB | PSNR dB | texel − vertex, dB |',
  '|---|---|---:|---:|---|---:|---:|---:|',
];
for (const t of rows.filter((r) => r.domain === 'texel')) {
  const candidates = rows.filter((r) => r.domain === 'vertex' && r.setting === t.setting);
  if (!candidates.length) continue;
  const v = candidates.reduce((best, r) => (Math.abs(Math.log(r.assetBytes / t.assetBytes)) < Math.abs(Math.log(best.assetBytes / t.assetBytes)) ? r : best));
  lines.push(`| ${t.setting} | ${t.resolution} | ${kib(t.assetBytes)} | ${t.psnr.toFixed(1)} | ${v.resolution} | ${kib(v.assetBytes)} | ${v.psnr.toFixed(1)} | ${(t.psnr - v.psnr).toFixed(1)} |`);
}
fs.writeFileSync(outMd, `${lines.join('\n')}\n`);
console.log(`wrote ${outJson} and ${outMd}`);
