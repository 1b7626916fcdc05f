// Radiance transfer textures in the wasm core (web/src/rtt_texture.h, prt/rtt.h): files the
// native `prt-bake rtt` writes are read by the wasm reader, and the packed half-float textures'
// lookup (the fragment shader's, emulated) equals prt::rttLookup to binary16 precision.
// Usage: node rtt_core_node_test.mjs PRT_CORE_NODE_JS PRT_BAKE WORK_DIR
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const [coreJs, bake, workDir] = process.argv.slice(2);
if (!workDir) {
  console.error('usage: node rtt_core_node_test.mjs PRT_CORE_NODE_JS PRT_BAKE WORK_DIR');
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
const core = await createRequire(import.meta.url)(path.resolve(coreJs))({ wasmBinary: fs.readFileSync(coreJs.replace(/\.js$/, '.wasm')) });

const failures = [];
let checks = 0;
function check(ok, message) {
  checks++;
  if (!ok) failures.push(message);
  return ok;
}

// Files from the native baker: view-dependent grey, diffuse, and RGB from an albedo map.
const cases = [
  { name: 'weave', args: ['--patch', 'weave', '--size', '32', '--spatial', '16', '--views', '8'], views: 8, channels: 1 },
  { name: 'stucco-diffuse', args: ['--patch', 'stucco', '--size', '32', '--views', '1', '--spatial', '32'], views: 1, channels: 1 },
  { name: 'holes-order3', args: ['--patch', 'holes', '--size', '32', '--spatial', '8', '--views', '4', '--order', '3'], views: 4, channels: 1 },
];
for (const c of cases) {
  const file = path.join(workDir, `${c.name}.rtt`);
  const r = spawnSync(bake, ['rtt', ...c.args, '-o', file, '--quiet'], { encoding: 'utf8' });
  if (!check(r.status === 0, `${c.name}: prt-bake rtt exited ${r.status}: ${r.stderr}`)) continue;
  const result = core.rttTextureCheck(fs.readFileSync(file), 400, 7);
  if (!check(typeof result === 'object', `${c.name}: ${result}`)) continue;
  console.log(`${c.name}: ${result.spatial}^2 x ${result.views}^2, ${result.layers} layers of ${result.size}^2; packed lookup vs reference ${result.worst.toExponential(2)} of the peak ${result.peak.toFixed(4)}`);
  check(result.views === c.views && result.channels === c.channels, `${c.name}: shape ${JSON.stringify(result)}`);
  check(result.peak > 0.01, `${c.name}: coefficients peak at ${result.peak}`);
  check(result.worst < 2e-3, `${c.name}: the packed textures' lookup differs from prt::rttLookup by ${result.worst} of the peak (binary16: < 1e-3)`);
}

// Damaged files are refused by the wasm reader with the reason.
{
  const good = fs.readFileSync(path.join(workDir, 'weave.rtt'));
  const cut = core.rttTextureCheck(good.subarray(0, good.length - 9), 1, 1);
  check(typeof cut === 'string' && /truncated|ends/.test(cut), `a cut RTT: ${cut}`);
  const flipped = Buffer.from(good);
  flipped[1000] ^= 0x10;
  const bad = core.rttTextureCheck(flipped, 1, 1);
  check(typeof bad === 'string' && /checksum/.test(bad), `a damaged RTT: ${bad}`);
}

// Packing limits: WebGL2's guaranteed 2048 texels a side and 256 layers.
{
  const big = core.syntheticRtt(1, 1, 260, 8, 1.0);  // 2080 texels a side
  const r = core.rttTextureCheck(big, 1, 1);
  check(typeof r === 'string' && /2080\^2 texels/.test(r), `a 260^2 x 8^2 RTT: ${r}`);
  const huge = core.syntheticRtt(2, 3, 2, 2, 1e6);  // beyond binary16
  const h = core.rttTextureCheck(huge, 1, 1);
  check(typeof h === 'string' && /binary16/.test(h), `coefficients of 1e6: ${h}`);
  const rgb = core.rttTextureCheck(core.syntheticRtt(8, 3, 4, 4, 0.5), 200, 3);
  check(typeof rgb === 'object' && rgb.layers === 48 && rgb.worst < 2e-3, `order 8 RGB: ${JSON.stringify(rgb)}`);
}

// Bi-scale's rotation step on the CPU (the page's GPU step is checked against it) equals
// prt::ShRotation at every order the client draws, frames up to the asset's tolerance included.
for (const [bands, rowTexels] of [[1, 1], [3, 3], [4, 4], [5, 7], [5, 9]]) {
  const r = core.biScaleRotateCheck(bands, rowTexels, 50, bands);
  if (!check(typeof r === 'object', `bi-scale rotation at ${bands} bands: ${r}`)) continue;
  console.log(`  bi-scale rotation, ${bands} bands in rows of ${rowTexels} texels: worst ${r.worst.toExponential(2)} of ${r.peak.toFixed(3)}`);
  check(r.worst <= 1e-5 * Math.max(r.peak, 1), `bi-scale rotation at ${bands} bands differs from ShRotation by ${r.worst}`);
  check(r.zeroTail === 0, `bi-scale rotation at ${bands} bands leaves ${r.zeroTail} beyond its coefficients`);
  check(r.mainLength > 100, `bi-scale rotation step's GLSL at ${bands} bands is ${r.mainLength} characters`);
}

if (failures.length) {
  console.error(`rtt core: ${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`rtt core: ${checks} checks passed`);
