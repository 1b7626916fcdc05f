// Runs the native and the wasm build of prt_sh_digest and checks every value agrees:
// integers exactly, floats within 2e-6 absolute + 2e-6 relative (float rounding may
// differ between the toolchains' libm and contraction choices, nothing more).
// Usage: node compare_digests.mjs NATIVE_BINARY WASM_JS
import { execFileSync } from 'node:child_process';
import { closeSync, existsSync, mkdtempSync, openSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const [nativeBin, wasmJs] = process.argv.slice(2);
if (!nativeBin || !wasmJs) {
  console.error('usage: compare_digests.mjs NATIVE_BINARY WASM_JS');
  process.exit(2);
}
if (!existsSync(nativeBin)) {
  console.error(`native digest binary not found: ${nativeBin}\nbuild the native preset first (scripts/test.sh does both)`);
  process.exit(1);
}

// Output goes to a file, not a pipe: Node exits before flushing a piped stdout of this
// Emscripten version, which would silently truncate the wasm digest.
function run(command, args) {
  const dir = mkdtempSync(join(tmpdir(), 'prt-digest-'));
  const path = join(dir, 'out.txt');
  const fd = openSync(path, 'w');
  try {
    execFileSync(command, args, { stdio: ['ignore', fd, 'inherit'] });
  } finally {
    closeSync(fd);
  }
  const text = readFileSync(path, 'utf8');
  rmSync(dir, { recursive: true, force: true });
  return new Map(text.trim().split('\n').map((line) => line.split(' ')));
}
const native = run(nativeBin, []);
const wasm = run(process.execPath, ['--no-experimental-fetch', wasmJs]);

let failures = 0;
const report = (line) => {
  if (failures < 20) console.error(line);
};
if (native.size !== wasm.size) {
  console.error(`digest sizes differ: native ${native.size}, wasm ${wasm.size}`);
  failures++;
}
let worst = 0;
for (const [key, nv] of native) {
  const wv = wasm.get(key);
  if (wv === undefined) {
    report(`missing in wasm: ${key}`);
    failures++;
    continue;
  }
  const a = Number(nv), b = Number(wv);
  const exact = key.startsWith('pcg');
  const diff = Math.abs(a - b);
  worst = Math.max(worst, diff);
  if (exact ? a !== b : !(diff <= 2e-6 + 2e-6 * Math.abs(a))) {
    report(`${key}: native ${nv} wasm ${wv}`);
    failures++;
  }
}
console.log(`compared ${native.size} values, ${failures} mismatches, worst absolute difference ${worst.toExponential(2)}`);
process.exit(failures ? 1 : 0);
