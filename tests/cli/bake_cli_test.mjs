// End-to-end tests of `prt-bake` baking, `info` and `shade` on the real binary.
// Usage: node bake_cli_test.mjs CASE PRT_BAKE WORK_DIR
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

const [caseName, bake, workDir] = process.argv.slice(2);
if (!workDir) {
  console.error('usage: node bake_cli_test.mjs CASE PRT_BAKE WORK_DIR');
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
const work = (name) => path.join(workDir, name);

const failures = [];
let checks = 0;
function check(ok, message) {
  checks++;
  if (!ok) failures.push(message);
  return ok;
}
function run(args) {
  const r = spawnSync(bake, args, { encoding: 'utf8', timeout: 240000, maxBuffer: 256 << 20 });
  if (r.error) throw new Error(`cannot run ${bake}: ${r.error.message}`);
  return { code: r.status, stdout: r.stdout, stderr: r.stderr, args };
}
function expectExit(args, code, pattern) {
  const r = run(args);
  const where = `prt-bake ${args.join(' ')}`;
  check(r.code === code, `${where}: expected exit ${code}, got ${r.code}; stderr ${JSON.stringify(r.stderr.slice(-400))}`);
  if (pattern) check(pattern.test(r.stderr), `${where}: stderr should match ${pattern}, got ${JSON.stringify(r.stderr.slice(-400))}`);
  return r;
}
function json(r) {
  try {
    return JSON.parse(r.stdout);
  } catch (e) {
    check(false, `prt-bake ${r.args.join(' ')}: stdout is not JSON (${e.message})`);
    return null;
  }
}

// A small, quick bake of the default scene shared by several cases.
const quick = ['--samples', '64', '--order', '3', '--quiet'];
function bakeDefault(name, extra = []) {
  const out = work(name);
  const r = expectExit(['--default', '-o', out, ...quick, ...extra], 0);
  return { out, r };
}

const cases = {
  default_scene() {
    const { out, r } = bakeDefault('room.prt', ['--json']);
    const stats = json(r);
    if (stats) {
      check(stats.vertices > 10000 && stats.triangles > 10000, `default scene is too small: ${r.stdout}`);
      check(stats.passes[0].name === 'direct' && stats.passes[0].rays > 0, 'direct pass statistics missing');
      check(stats.bounces >= 1 && stats.bounces <= 8, `bounces ${stats.bounces} outside 1..8`);
      check(stats.peak_memory_mib > 0 && stats.total_seconds > 0, 'peak memory / time missing');
      check(stats.bytes === fs.statSync(out).size, 'reported bytes differ from the file size');
    }
    const info = json(expectExit(['info', out, '--json'], 0));
    if (info) {
      check(info.order === 3 && info.vertices === stats?.vertices, `info disagrees with the bake: ${JSON.stringify(info)}`);
      check(info.passes.map((p) => p.kind).join() === 'unshadowed,shadowed,interreflected', `passes: ${JSON.stringify(info.passes)}`);
    }
    // Exit radiance under a constant white sky: shadowed <= unshadowed everywhere, and
    // interreflection stays below 1 (albedo < 1 and sky radiance 1 bound every bounce).
    const shade = (pass) => json(expectExit(['shade', out, '--light', 'constant', '--pass', pass, '--json'], 0));
    const u = shade('unshadowed'), s = shade('shadowed'), i = shade('interreflected');
    if (u && s && i) {
      check(u.vertices.length === info?.vertices, 'shade prints every vertex');
      let darker = 0;
      for (let v = 0; v < u.vertices.length; v++) {
        for (let c = 0; c < 3; c++) {
          const a = u.vertices[v].radiance[c], b = s.vertices[v].radiance[c], t = i.vertices[v].radiance[c];
          if (!check(Number.isFinite(a) && Number.isFinite(b) && Number.isFinite(t), `vertex ${v} radiance not finite`)) return;
          if (!check(b <= a + 1e-5, `vertex ${v}: shadowed ${b} > unshadowed ${a}`)) return;
          if (!check(t >= b - 1e-5 && t <= 1.0, `vertex ${v}: interreflected ${t} outside [shadowed ${b}, 1]`)) return;
          if (b < 0.9 * a) darker++;
        }
      }
      check(darker > 1000, `only ${darker} vertex channels are visibly shadowed; contact shadows missing?`);
    }
  },

  determinism() {
    const a = bakeDefault('a.prt', ['--threads', '1', '--seed', '7']).out;
    const b = bakeDefault('b.prt', ['--threads', '2', '--seed', '7']).out;
    const c = bakeDefault('c.prt', ['--threads', '2', '--seed', '8']).out;
    check(Buffer.compare(fs.readFileSync(a), fs.readFileSync(b)) === 0, '1 and 2 threads give different assets');
    check(Buffer.compare(fs.readFileSync(a), fs.readFileSync(c)) !== 0, 'seeds 7 and 8 give identical assets');
  },

  bad_assets() {
    const { out } = bakeDefault('good.prt', ['--passes', 'shadowed']);
    const bytes = fs.readFileSync(out);
    fs.writeFileSync(work('truncated.prt'), bytes.subarray(0, Math.floor(bytes.length / 2)));
    expectExit(['info', work('truncated.prt')], 1, /truncated/);
    const flipped = Buffer.from(bytes);
    flipped[Math.floor(bytes.length * 0.7)] ^= 0x40;
    fs.writeFileSync(work('flipped.prt'), flipped);
    expectExit(['info', work('flipped.prt')], 1, /checksum/);
    fs.writeFileSync(work('garbage.prt'), Buffer.from('definitely not an asset, just text'));
    expectExit(['info', work('garbage.prt')], 1, /magic|truncated/);
    expectExit(['info', work('missing.prt')], 1, /no such file/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'interreflected'], 1, /no interreflected pass/);
    expectExit(['shade', out, '--light', 'constant', '--order', '9'], 2, /exceeds the asset's order/);
  },

  bad_scenes() {
    expectExit([work('nothing.gltf'), '-o', work('x.prt')], 1, /nothing\.gltf/);
    fs.writeFileSync(work('broken.gltf'), '{"asset": {"version": "2.0"}, "meshes": [');
    expectExit([work('broken.gltf'), '-o', work('x.prt'), '--quiet'], 1, /broken\.gltf/);
    fs.writeFileSync(work('empty.gltf'), '{"asset": {"version": "2.0"}}');
    expectExit([work('empty.gltf'), '-o', work('x.prt'), '--quiet'], 1, /triangle/);
    check(!fs.existsSync(work('x.prt')), 'a failed bake wrote an asset');
  },

  usage_errors() {
    expectExit(['--default'], 2, /missing -o/);
    expectExit(['--default', '-o', work('x.prt'), '--order', '9'], 2, /--order/);
    expectExit(['--default', '-o', work('x.prt'), '--order', '1'], 2, /--order/);
    expectExit(['--default', '-o', work('x.prt'), '--samples', 'many'], 2, /--samples/);
    expectExit(['--default', '-o', work('x.prt'), '--sampling', 'stratified', '--samples', '1000'], 2, /square/);
    expectExit(['--default', '-o', work('x.prt'), '--passes', 'shadowed,glossy'], 2, /glossy/);
    expectExit(['--default', '-o', work('x.prt'), '--bounces', '3', '--bounce-threshold', '0.1'], 2, /not both/);
    expectExit(['--default', 'scene.glb', '-o', work('x.prt')], 2, /not both/);
    expectExit(['frobnicate'], 2, /unknown command/);
    const help = expectExit(['--default', '--help'], 0);
    check(/--samples/.test(help.stdout) && /--bounces/.test(help.stdout), 'bake --help lists the options');
    check(!fs.existsSync(work('x.prt')), 'a usage error wrote an asset');
  },

  async interrupted() {
    // SIGINT in the middle of a long bake leaves neither the asset nor a temporary file.
    const out = work('interrupted.prt');
    const child = spawn(bake, ['--default', '-o', out, '--samples', '65536', '--quiet']);
    await new Promise((resolve) => setTimeout(resolve, 1500));
    child.kill('SIGINT');
    const code = await new Promise((resolve) => child.on('exit', (c, s) => resolve(s || c)));
    check(code === 'SIGINT' || code !== 0, `bake should die on SIGINT, got ${code}`);
    const left = fs.readdirSync(workDir);
    check(left.length === 0, `files left behind: ${left.join(', ')}`);
  },
};

if (!(caseName in cases)) {
  console.error(`unknown case ${caseName}; known: ${Object.keys(cases).join(', ')}`);
  process.exit(2);
}
await cases[caseName]();
if (failures.length) {
  console.error(`${caseName}: ${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`${caseName}: ${checks} checks passed`);
