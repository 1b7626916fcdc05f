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

  local_lighting() {
    // The default room with spatially-varying lighting: the sphere defaults to the bounds'
    // centre and half their diagonal (room x, z in [-2, 2], y in [0, 3]).
    const { out, r } = bakeDefault('local.prt', ['--lighting', 'local', '--json', '--name', 'default-room-local']);
    const stats = json(r);
    const radius = 0.5 * Math.sqrt(16 + 9 + 16);
    if (stats) {
      check(stats.lighting?.model === 'local-sphere', `bake --json lighting: ${JSON.stringify(stats.lighting)}`);
      check(JSON.stringify(stats.lighting?.center) === '[0,1.5,0]', `default centre: ${JSON.stringify(stats.lighting)}`);
      check(Math.abs(stats.lighting?.radius - radius) < 1e-5, `default radius: ${stats.lighting?.radius}, expected ${radius}`);
      check(stats.lighting?.vertices_outside === 0, `no vertex lies outside the default sphere: ${JSON.stringify(stats.lighting)}`);
    }
    const info = json(expectExit(['info', out, '--json'], 0));
    if (info) {
      check(info.version === '1.1' && info.name === 'default-room-local', `info: ${JSON.stringify(info)}`);
      check(info.lighting?.model === 'local-sphere' && Math.abs(info.lighting.radius - radius) < 1e-5,
            `info lighting: ${JSON.stringify(info.lighting)}`);
    }
    const text = expectExit(['info', out], 0).stdout;
    check(/^lighting: local-sphere, centre \(0, 1\.5, 0\), radius 3\.2015/m.test(text), `info text: ${text}`);

    // Under uniform light the DC basis function is constant, so the local unshadowed transfer
    // lights every vertex exactly as the distant one does (same samples): the area form's
    // white furnace. The paper's weighting brightens vertices away from the centre.
    const { out: distant } = bakeDefault('distant.prt', ['--passes', 'unshadowed']);
    const { out: paper } = bakeDefault('paper.prt', ['--passes', 'unshadowed', '--lighting', 'local-paper']);
    const shade = (file) => json(expectExit(['shade', file, '--light', 'constant', '--pass', 'unshadowed', '--json'], 0));
    const l = shade(out), d = shade(distant), p = shade(paper);
    if (l && d && p) {
      let worst = 0, brighter = 0;
      for (let v = 0; v < d.vertices.length; v++) {
        for (let c = 0; c < 3; c++) {
          worst = Math.max(worst, Math.abs(l.vertices[v].radiance[c] - d.vertices[v].radiance[c]));
          if (p.vertices[v].radiance[c] > 1.05 * d.vertices[v].radiance[c]) brighter++;
        }
      }
      check(worst < 1e-5, `local unshadowed differs from distant under uniform light by ${worst}`);
      check(brighter > 1000, `the paper variant brightened only ${brighter} vertex channels`);
    }

    // An explicit sphere is recorded as given; one too small for the room warns with the count.
    const small = expectExit(['--default', '-o', work('small.prt'), ...quick.filter((a) => a !== '--quiet'),
                              '--passes', 'shadowed', '--lighting', 'local-paper', '--light-center', '0.5,1,-0.25',
                              '--light-radius', '1.5'], 0,
                             /warning: \d+ of \d+ vertices lie outside the lighting sphere/);
    const count = Number(/warning: (\d+) of/.exec(small.stderr)?.[1]);
    check(count > 1000 && count < 20000, `outside count ${count}`);
    const smallInfo = json(expectExit(['info', work('small.prt'), '--json'], 0));
    check(JSON.stringify(smallInfo?.lighting) === '{"model":"local-sphere-paper","center":[0.5,1,-0.25],"radius":1.5}',
          `explicit sphere: ${JSON.stringify(smallInfo?.lighting)}`);
    const distantInfo = json(expectExit(['info', distant, '--json'], 0));
    check(JSON.stringify(distantInfo?.lighting) === '{"model":"distant"}', `distant: ${JSON.stringify(distantInfo?.lighting)}`);
  },

  lighting_usage_errors() {
    const bakeArgs = (...extra) => ['--default', '-o', work('x.prt'), ...quick, ...extra];
    expectExit(bakeArgs('--lighting', 'nearby'), 2, /unknown --lighting 'nearby' \(expected distant, local or local-paper\)/);
    expectExit(bakeArgs('--light-radius', '2'), 2, /--light-radius needs --lighting local or local-paper/);
    expectExit(bakeArgs('--lighting', 'distant', '--light-center', '0,0,0'), 2, /--light-center needs --lighting local/);
    for (const r of ['0', '-1', 'nan', 'inf', '1e99', 'two', '']) {
      expectExit(bakeArgs('--lighting', 'local', `--light-radius=${r}`), 2, r === '' ? /needs a value/ : /--light-radius expects a finite number > 0/);
    }
    for (const c of ['1,2', '1,2,3,4', '1;2;3', '1 2 3']) {
      expectExit(bakeArgs('--lighting', 'local', '--light-center', c), 2, /--light-center expects X,Y,Z \(three numbers/);
    }
    for (const [c, k] of [['nan,0,0', 1], ['0,inf,0', 2], ['0,0,x', 3], ['0,1e39,0', 2], ['1,,3', 2], [',1,2', 1]]) {
      expectExit(bakeArgs('--lighting', 'local', '--light-center', c), 2, new RegExp(`component ${k} '[^']*' is not one`));
    }
    expectExit(bakeArgs('--name', 'tab\there'), 2, /--name must be/);
    const help = expectExit(['--default', '--help'], 0);
    check(/--lighting MODEL/.test(help.stdout) && /--light-center/.test(help.stdout) && /--light-radius/.test(help.stdout),
          'bake --help documents the lighting options');
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
