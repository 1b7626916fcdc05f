// The client's wasm core (shared decoder and SH code, compiled by Emscripten) under Node,
// against the native build: the same asset must decode to the same summary and the same
// exit radiance as `prt-bake info` / `prt-bake shade` print natively, corrupt bytes must be
// rejected with the reader's named errors, and SH rotation must match its closed form.
// Usage: node core_node_test.mjs PRT_CORE_NODE_JS NATIVE_PRT_BAKE WORK_DIR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const [coreJs, prtBake, workDir] = process.argv.slice(2);
const failures = [];
let checks = 0;
const check = (ok, message) => {
  checks++;
  if (!ok) failures.push(message);
  return ok;
};
if (!fs.existsSync(prtBake)) {
  console.error(`native prt-bake not found at ${prtBake}: build the native preset first (scripts/test.sh does)`);
  process.exit(1);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });

const createPrtCore = createRequire(import.meta.url)(path.resolve(coreJs));
const core = await createPrtCore();

// A small asset from the native baker.
const asset = path.join(workDir, 'room.prt');
execFileSync(prtBake, ['--default', '-o', asset, '--samples', '64', '--order', '4', '--quiet']);
const bytes = fs.readFileSync(asset);

const info = core.inspectAsset(bytes);
const nativeInfo = JSON.parse(execFileSync(prtBake, ['info', asset, '--json'], { encoding: 'utf8' }));
check(info.ok, `wasm decode failed: ${info.error}`);
check(info.order === nativeInfo.order && info.vertices === nativeInfo.vertices && info.triangles === nativeInfo.triangles,
  `wasm summary ${JSON.stringify(info)} differs from native ${JSON.stringify(nativeInfo)}`);
check(info.passes.map((p) => p.kind).join() === nativeInfo.passes.map((p) => p.kind).join(), 'pass lists differ');

for (const pass of ['unshadowed', 'shadowed', 'interreflected']) {
  const wasm = core.shadeConstant(bytes, pass);
  const native = JSON.parse(execFileSync(prtBake, ['shade', asset, '--light', 'constant', '--pass', pass, '--json'],
    { encoding: 'utf8', maxBuffer: 256 << 20 })).vertices;
  if (!check(wasm && wasm.length === native.length * 3, `${pass}: wasm gave ${wasm && wasm.length} values for ${native.length} vertices`)) continue;
  let worst = 0;
  for (let v = 0; v < native.length; v++) {
    for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(wasm[3 * v + c] - native[v].radiance[c]) / Math.max(1e-3, Math.abs(native[v].radiance[c])));
  }
  check(worst < 1e-5, `${pass}: wasm and native exit radiance differ by ${worst} (relative)`);
}

// Corrupt input: named errors, never a crash.
const truncated = core.inspectAsset(bytes.subarray(0, 1000));
check(!truncated.ok && /truncated/.test(truncated.error), `truncated asset: ${truncated.error}`);
const flipped = Buffer.from(bytes);
flipped[Math.floor(flipped.length / 2)] ^= 1;
const bad = core.inspectAsset(flipped);
check(!bad.ok && /checksum/.test(bad.error), `corrupted asset: ${bad.error}`);
const garbage = core.inspectAsset(Buffer.from('PRTB and some other bytes, far too short'));
check(!garbage.ok, 'garbage accepted');

// SH: band 1 closed form, and a z rotation by 90 degrees turns +x into +y.
const y = core.evalBasis(3, 0.6, 0.0, 0.8);
check(Math.abs(y[3] - 0.488603 * 0.6) < 1e-6 && Math.abs(y[2] - 0.488603 * 0.8) < 1e-6, `basis: ${y.slice(0, 4)}`);
const lobe = [0, 0, 0, 1, 0, 0, 0, 0, 0];  // y_1,1 ~ x
const rotated = core.rotateCoefficients(3, lobe, [0, -1, 0, 1, 0, 0, 0, 0, 1]);
check(Math.abs(rotated[1] - 1) < 1e-6 && Math.abs(rotated[3]) < 1e-6, `rotation: ${rotated}`);
check(typeof core.rotateCoefficients(3, lobe, [2, 0, 0, 0, 1, 0, 0, 0, 1]) === 'string', 'a non-rotation must be rejected');

if (failures.length) {
  console.error(`${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`wasm client core: ${checks} checks passed`);
