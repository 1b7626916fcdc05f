// End-to-end tests of `prt-bake` baking, `info` and `shade` on the real binary.
// Usage: node bake_cli_test.mjs CASE PRT_BAKE WORK_DIR [TEXEL_ASSET_TOOL]
// (the last only for texel_info: tests/cli/make_texel_asset.cpp's binary)
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { bowlGltf } from './bowl_gltf.mjs';
import { planeGltf } from './plane_gltf.mjs';
import { stripeQuadGltf, stripeSlope } from '../web/floor_scene_gltf.mjs';
import { box, quad, texturedSceneGltf } from './texture_sets_gltf.mjs';

const [caseName, bake, workDir, texelTool] = process.argv.slice(2);
if (!workDir) {
  console.error('usage: node bake_cli_test.mjs CASE PRT_BAKE WORK_DIR');
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
const work = (name) => path.join(workDir, name);

// prt-bake's exit statuses (native/exit_status.h, docs/baker.md "Exit status").
const EXIT_NOT_FOUND = 3, EXIT_INVALID_INPUT = 4, EXIT_RESOURCE = 6, EXIT_UNAVAILABLE = 7;

const failures = [];
let checks = 0;
function check(ok, message) {
  checks++;
  if (!ok) failures.push(message);
  return ok;
}
function run(args, env = process.env) {
  const r = spawnSync(bake, args, { encoding: 'utf8', timeout: 240000, maxBuffer: 256 << 20, env });
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
  // prt-bake rtt: a built-in patch baked to a file whose header and size match the options,
  // the same bytes twice (any thread count), a grey flat patch's coefficient 0 = rho/pi * pi y00.
  rtt() {
    const out = work('weave.rtt');
    const r = expectExit(['rtt', '--patch', 'weave', '--size', '32', '--spatial', '8', '--views', '4', '-o', out, '--json', '--quiet'], 0);
    const j = json(r);
    if (!j) return;
    check(j.order === 5 && j.channels === 1 && j.spatial === 8 && j.views === 4 && j.light_directions === 128 && j.bounces === 1,
      `summary ${r.stdout}`);
    const bytes = fs.readFileSync(out);
    check(bytes.length === 40 + 4 * 8 * 8 * 4 * 4 * 25 + 4 && j.bytes === bytes.length, `${bytes.length} bytes, summary says ${j.bytes}`);
    check(bytes.subarray(0, 8).toString('latin1') === 'PRTRTT1\n', 'magic');
    const again = work('weave-1thread.rtt');
    expectExit(['rtt', '--patch', 'weave', '--size', '32', '--spatial', '8', '--views', '4', '--threads', '1', '-o', again, '--quiet'], 0);
    check(Buffer.compare(bytes, fs.readFileSync(again)) === 0, 'the RTT differs between 2 threads and 1');
    const flat = work('flat.rtt');
    expectExit(['rtt', '--patch', 'flat', '--size', '8', '--albedo', '0.5', '--views', '1', '--spatial', '2', '-o', flat, '--quiet'], 0);
    const f = fs.readFileSync(flat);
    check(f.length === 40 + 4 * 2 * 2 * 25 + 4, `--views 1 --spatial 2: ${f.length} bytes`);
    const b0 = f.readFloatLE(40);
    check(Math.abs(b0 - 0.5 * 0.28209479) < 1e-5, `flat patch B_0 ${b0}, expected rho/pi * pi y00 = ${0.5 * 0.28209479}`);
    const text = expectExit(['rtt', '--patch', 'holes', '--size', '16', '--spatial', '4', '--views', '2', '-o', work('holes.rtt')], 0);
    check(/direct/.test(text.stderr) && /views/.test(text.stderr), `progress on stderr: ${JSON.stringify(text.stderr)}`);
    check(/RTT of holes, 4x4 positions x 2x2 views, order 5, 1 channel/.test(text.stdout), `summary line: ${text.stdout}`);
    // prt-bake info reads RTT files too: verified, shape and range; a damaged one is named.
    const info = json(expectExit(['info', out, '--json'], 0));
    check(info && info.kind === 'rtt' && info.spatial === 8 && info.views === 4 && info.order === 5 && info.view_dependent === true &&
      info.max > info.min && info.bytes === bytes.length, `info --json of an RTT: ${JSON.stringify(info)}`);
    const infoText = expectExit(['info', flat], 0);
    check(/radiance transfer texture/.test(infoText.stdout) && /view-independent/.test(infoText.stdout), `info of an RTT: ${infoText.stdout}`);
    const damaged = Buffer.from(bytes);
    damaged[100] ^= 1;
    fs.writeFileSync(work('damaged.rtt'), damaged);
    expectExit(['info', work('damaged.rtt')], EXIT_INVALID_INPUT, /damaged\.rtt.*checksum/);
  },
  // Bad command lines and inputs are named; nothing is written.
  rtt_usage_errors() {
    const out = work('x.rtt');
    expectExit(['rtt', '-o', out], 2, /exactly one of --patch/);
    expectExit(['rtt', '--patch', 'weave', '--height', 'h.png', '-o', out], 2, /exactly one of --patch/);
    expectExit(['rtt', '--patch', 'weave'], 2, /missing -o/);
    expectExit(['rtt', '--patch', 'plaid', '-o', out], EXIT_INVALID_INPUT, /unknown patch 'plaid'/);
    expectExit(['rtt', '--patch', 'weave', '--views', '0', '-o', out], 2, /--views/);
    expectExit(['rtt', '--patch', 'weave', '--order', '9', '-o', out], 2, /--order/);
    expectExit(['rtt', '--patch', 'weave', '--albedo', '1.5', '-o', out], 2, /--albedo/);
    expectExit(['rtt', '--patch', 'weave', '--albedo-map', 'a.png', '-o', out], 2, /--albedo-map goes with --height/);
    expectExit(['rtt', '--height', work('missing.png'), '-o', out], EXIT_NOT_FOUND, /missing\.png/);
    fs.writeFileSync(work('junk.png'), 'not an image');
    expectExit(['rtt', '--height', work('junk.png'), '-o', out], EXIT_INVALID_INPUT);
    expectExit(['rtt', '--patch', 'weave', '--size', '16', '-o', workDir], EXIT_INVALID_INPUT);
    check(!fs.existsSync(out), 'a failed rtt bake left an output file');
    const help = run(['rtt', '--help']);
    check(help.code === 0 && /--light-polar/.test(help.stdout) && /Exit status/.test(help.stdout), 'rtt --help');
  },
  texel_info() {
    // `info` on an asset with transfer textures (no bake writes them yet: the generator does,
    // and says what it wrote): each pass's domain, the texel count and the atlases.
    check(Boolean(texelTool), 'texel_info needs the generator as its fourth argument');
    const out = work('texel.prt');
    const made = spawnSync(texelTool, [out], { encoding: 'utf8' });
    if (!check(made.status === 0, `generator failed: ${made.stderr}`)) return;
    const wrote = JSON.parse(made.stdout);
    const info = json(expectExit(['info', out, '--json'], 0));
    if (info) {
      check(info.version === '1.7', `version ${info.version}`);
      const seen = info.passes.map((p) => ({ kind: p.kind, domain: p.domain, encoded: p.encoded }));
      check(JSON.stringify(seen) === JSON.stringify(wrote.passes), `passes ${JSON.stringify(seen)}, wrote ${JSON.stringify(wrote.passes)}`);
      check(info.texels === wrote.texels, `texels ${info.texels}, wrote ${wrote.texels}`);
      check(JSON.stringify(info.atlases) === JSON.stringify(wrote.atlases), `atlases ${JSON.stringify(info.atlases)}, wrote ${JSON.stringify(wrote.atlases)}`);
    }
    const text = expectExit(['info', out], 0).stdout;
    const texelLines = text.split('\n').filter((l) => /^pass: texel /.test(l));
    check(texelLines.length === wrote.passes.filter((p) => p.domain === 'texel').length, `texel pass lines: ${text}`);
    check(/^pass: texel shadowed, scalar \(x albedo\), float32, /m.test(text), `texel shadowed line: ${text}`);
    check(/^pass: shadowed, scalar \(x albedo\), float32, /m.test(text), `vertex shadowed line: ${text}`);
    const a = wrote.atlases;
    const atlasLine = `atlases: ${a.length}, ${wrote.texels} texels: ` +
                      a.map((t) => `${t.width}x${t.height} (triangles ${t.firstTriangle}-${t.firstTriangle + t.triangleCount - 1})`).join(', ');
    check(text.includes(atlasLine + '\n'), `atlases line: expected '${atlasLine}' in ${text}`);
    // The generator's strip is connected within each atlas: one chart each.
    check(JSON.stringify(info?.atlas_usage?.map((u) => u.charts)) === '[1,1]', `charts per atlas: ${JSON.stringify(info?.atlas_usage)}`);
    check(/^atlas 1: 3x2, triangles 5-7 \(3\), 1 chart, /m.test(text), `atlas 1 line: ${text}`);
    // Damage in a texel pass (the last section) is reported as damage.
    const bytes = fs.readFileSync(out);
    const damaged = work('texel-damaged.prt');
    bytes[bytes.length - 1] ^= 1;
    fs.writeFileSync(damaged, bytes);
    expectExit(['info', damaged], EXIT_INVALID_INPUT, /checksum/);
  },
  glossy() {
    // A small glossy bake of the default room: matrix passes in `info`, and `shade` seen from
    // two eyes: the matte room (f0 = 0) has no glossy term at all, the polished sphere has one
    // that follows the eye, and diffuse + glossy is the sum of the two terms.
    const { out } = bakeDefault('glossy.prt', ['--glossy']);
    const info = json(run(['info', out, '--json']));
    if (info) {
      const matrices = info.passes.filter((p) => p.form === 'matrix');
      check(matrices.length === 2, `expected two matrix passes, got ${JSON.stringify(info.passes)}`);
      const shadowed = matrices.find((p) => p.kind === 'shadowed'), inter = matrices.find((p) => p.kind === 'interreflected');
      check(shadowed && shadowed.channels === 1, `shadowed matrix pass: ${JSON.stringify(shadowed)}`);
      check(inter && inter.channels === 3 && inter.bounces === 1, `interreflected matrix pass: ${JSON.stringify(inter)}`);
    }
    const text = run(['info', out]).stdout;
    check(/shadowed glossy matrix, scalar .*symmetric packing \(45 entries/.test(text), `info text: ${text}`);
    const shade = (extra) => {
      const r = expectExit(['shade', out, '--light', 'constant', '--json', ...extra], 0);
      const j = json(r);
      return j ? j.vertices.map((v) => v.radiance) : [];
    };
    const eyeA = ['--view', '-0.9,0.9,3'], eyeB = ['--view', '2,2.5,-0.5'];
    const glossyA = shade(['--pass', 'glossy', ...eyeA, '--glossy-only']);
    const glossyB = shade(['--pass', 'glossy', ...eyeB, '--glossy-only']);
    const both = shade(['--pass', 'glossy', ...eyeA]);
    const diffuse = shade(['--pass', 'interreflected']);
    check(glossyA.length > 1000 && glossyA.length === diffuse.length, `vertex counts ${glossyA.length} ${diffuse.length}`);
    let matte = 0, lit = 0, moved = 0, sumError = 0;
    for (let v = 0; v < glossyA.length; v++) {
      const a = glossyA[v], b = glossyB[v];
      if (a.every((x) => x === 0) && b.every((x) => x === 0)) matte++;
      if (a[0] > 0.01) lit++;
      if (Math.abs(a[0] - b[0]) > 1e-3) moved++;
      for (let c = 0; c < 3; c++) sumError = Math.max(sumError, Math.abs(both[v][c] - (diffuse[v][c] + a[c])));
    }
    check(matte > glossyA.length / 2, `matte vertices with no glossy term: ${matte} of ${glossyA.length}`);
    check(lit > 1000, `vertices with a visible glossy term from eye A: ${lit}`);
    check(moved > 1000, `vertices whose glossy term changes with the eye: ${moved}`);
    check(sumError < 1e-4, `diffuse + glossy differs from the sum of the terms by ${sumError}`);
    // Compressed matrices shade close to the float ones (the codec's own bounds are tested in
    // tests/shared; this checks the CLI decodes and uses them).
    const packed = bakeDefault('glossy-cpca.prt', ['--glossy', '--compress', 'cpca16@0.01']).out;
    const r = expectExit(['shade', packed, '--light', 'constant', '--json', '--pass', 'glossy', ...eyeA, '--glossy-only'], 0);
    const j = json(r);
    if (j) {
      let num = 0, den = 0;
      j.vertices.forEach((v, i) => v.radiance.forEach((x, c) => { num += (x - glossyA[i][c]) ** 2; den += glossyA[i][c] ** 2; }));
      check(Math.sqrt(num / den) < 0.05, `cpca16@0.01 glossy radiance relative RMS error ${Math.sqrt(num / den)}`);
    }
    // --compress-matrices: the matrix passes take their own setting, the vector passes keep
    // --compress's. q8 stores a byte per value and f16 two, so the vector passes' bytes are
    // the same in both bakes and the matrix passes' about double.
    const passBytes = (file) => (json(run(['info', file, '--json']))?.passes ?? []).map((p) => ({ form: p.form, kind: p.kind, bytes: p.bytes }));
    const q8 = passBytes(bakeDefault('glossy-q8.prt', ['--glossy', '--compress', 'q8']).out);
    const mixed = bakeDefault('glossy-q8-f16.prt', ['--glossy', '--compress', 'q8', '--compress-matrices', 'f16']);
    const split = passBytes(mixed.out);
    check(q8.length === 5 && split.length === 5, `passes: ${JSON.stringify(q8)} ${JSON.stringify(split)}`);
    for (let i = 0; i < Math.min(q8.length, split.length); i++) {
      const ratio = split[i].bytes / q8[i].bytes;
      if (q8[i].form === 'matrix') check(ratio > 1.8 && ratio < 2.1, `${q8[i].kind} matrix pass: f16 / q8 bytes ${ratio}`);
      else check(ratio === 1, `${q8[i].kind} vector pass changed with --compress-matrices: ${q8[i].bytes} -> ${split[i].bytes}`);
    }
  },

  glossy_usage_errors() {
    const { out } = bakeDefault('plain.prt');
    const base = ['--default', '-o', work('x.prt'), ...quick];
    expectExit([...base, '--glossy-bounces', '1'], 2, /--glossy-bounces needs --glossy/);
    expectExit([...base, '--specular-exponent', '8'], 2, /--specular-exponent needs --glossy/);
    expectExit([...base, '--glossy', '--specular-exponent', '-1'], 2, /--specular-exponent/);
    expectExit([...base, '--glossy', '--glossy-bounces', '2', '--passes', 'shadowed'], 2, /keep interreflected in --passes/);
    expectExit([...base, '--glossy', '--glossy-bounces', '5', '--bounces', '2'], 2, /exceeds --bounces 2/);
    expectExit([...base, '--glossy', '--compress-matrices', 'f16'], 2, /--compress-matrices needs --compress/);
    expectExit([...base, '--compress', 'q8', '--compress-matrices', 'f16'], 2, /--compress-matrices needs --glossy/);
    expectExit([...base, '--glossy', '--compress', 'q8', '--compress-matrices', 'cpca16n40'], 2, /basis limit n<N> takes N from 0 to 32/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'glossy'], 2, /needs --view X,Y,Z/);
    expectExit(['shade', out, '--light', 'constant', '--view', '1,2,3'], 2, /--view needs a glossy --pass/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'glossy', '--view', '1,2'], 2, /--view expects X,Y,Z/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'glossy-unshadowed', '--view', '1,2,3'], 2, /unknown --pass/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'glossy', '--view', '1,2,3'], EXIT_INVALID_INPUT,
               /no glossy matrix pass/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'glossy-shadowed', '--view', '1,2,3'], EXIT_INVALID_INPUT,
               /no shadowed glossy matrix pass \(bake with --glossy\)/);
    expectExit(['compress-report', out, '--pass', 'glossy'], EXIT_INVALID_INPUT, /no glossy matrix pass/);
    expectExit(['compress-report', out, '--views', '4'], 2, /--views needs a glossy --pass/);
  },

  texels() {
    // Transfer textures of the default room over its TEXCOORD_1 atlas: the bake reports the
    // atlas, `shade --texels` prints every sampled texel, and the texels behave physically
    // under a constant white sky: the floor under the cube (it rests on the floor) gets no
    // light at all, the open floor is lit, interreflection only adds light.
    const { out, r } = bakeDefault('texels.prt', ['--texels', '--texture-size', '512', '--json']);
    const stats = json(r);
    if (stats) {
      check(stats.texels && stats.texels.texcoord === 1 && stats.texels.size === 512, `texel stats: ${JSON.stringify(stats.texels)}`);
      // The room brings its own TEXCOORD_1: no atlas is generated (Blender never runs).
      check(stats.texels?.atlas === 'TEXCOORD_1' && !('unwrap' in stats.texels), `texel atlas: ${JSON.stringify(stats.texels)}`);
      check(stats.texels?.sampled > 100000 && stats.texels.sampled < 512 * 512, `sampled texels: ${stats.texels?.sampled}`);
      check(stats.texels?.charts === 16, `charts: ${stats.texels?.charts}`);
    }
    // `info` counts the charts again from the asset's own geometry and atlas UVs (split at the
    // seams): the same 16, in its JSON and in its atlas line.
    const described = json(expectExit(['info', out, '--json'], 0));
    check(described?.atlas_usage?.length === 1 && described.atlas_usage[0].charts === 16,
          `info charts: ${JSON.stringify(described?.atlas_usage)}`);
    check(/^atlas 0: 512x512, triangles \d+-\d+ \(\d+\), 16 charts, \d+ texels sampled/m.test(expectExit(['info', out], 0).stdout),
          'info atlas line with 16 charts');
    const shade = (pass) => json(expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', pass, '--json'], 0));
    const s = shade('shadowed'), i = shade('interreflected'), u = shade('unshadowed');
    if (!s || !i || !u) return;
    check(s.domain === 'texel' && s.texels.length === stats?.texels?.sampled, `shade --texels printed ${s.texels.length} texels`);
    // The cube: 1 m, centred at (0.9, 0, 0.6), turned 25 degrees about +y (default_scene.cpp).
    const yaw = (25 * Math.PI) / 180;
    const local = (p) => {
      const dx = p[0] - 0.9, dz = p[2] - 0.6;
      return [Math.cos(yaw) * dx - Math.sin(yaw) * dz, Math.sin(yaw) * dx + Math.cos(yaw) * dz];
    };
    let under = 0, underMax = 0, open = 0, openSum = 0, more = 0;
    for (let t = 0; t < s.texels.length; t++) {
      const a = s.texels[t], b = i.texels[t], c = u.texels[t];
      if (!check(a.x === b.x && a.y === b.y && a.x === c.x, `texel ${t} differs between passes`)) return;
      for (let k = 0; k < 3; k++) {
        if (!check(Number.isFinite(a.radiance[k]) && a.radiance[k] >= 0 && a.radiance[k] <= c.radiance[k] + 1e-5,
                   `texel ${t}: shadowed ${a.radiance[k]} outside [0, unshadowed ${c.radiance[k]}]`)) return;
        if (!check(b.radiance[k] >= a.radiance[k] - 1e-4 && b.radiance[k] <= 1, `texel ${t}: interreflected ${b.radiance[k]} outside [shadowed, 1]`)) return;
      }
      if (b.radiance[0] > a.radiance[0] + 1e-3) more++;
      const floor = Math.abs(a.position[1]) < 1e-4 && a.normal[1] > 0.999;
      if (!floor) continue;
      const [lx, lz] = local(a.position);
      if (Math.max(Math.abs(lx), Math.abs(lz)) < 0.45) {  // under the cube, 5 cm in from its edges
        under++;
        underMax = Math.max(underMax, ...a.radiance, ...b.radiance);
      }
      if (Math.hypot(a.position[0] + 1.2, a.position[2] - 1.6) < 0.2) {  // open floor, front left
        open++;
        openSum += a.radiance[0];
      }
    }
    check(under > 100, `only ${under} floor texels under the cube`);
    check(underMax === 0, `light leaks under the cube: radiance up to ${underMax}`);
    check(open > 10 && openSum / open > 0.3, `open floor: ${open} texels, mean shadowed ${openSum / open}`);
    check(more > 10000, `interreflection adds light at only ${more} texels`);
    const info = json(expectExit(['info', out, '--json'], 0));
    if (info) {
      const texelPasses = (info.passes ?? []).filter((p) => p.domain === 'texel').map((p) => p.kind);
      check(texelPasses.join() === 'unshadowed,shadowed,interreflected', `info texel passes: ${JSON.stringify(info.passes)}`);
    }
  },

  texel_usage_errors() {
    const { out } = bakeDefault('plain.prt');
    const base = ['--default', '-o', work('x.prt'), ...quick];
    expectExit([...base, '--texture-size', '256'], 2, /--texture-size needs --texels/);
    expectExit([...base, '--texels', '--texture-size', '256', '--texels-per-unit', '10'], 2, /not both/);
    expectExit([...base, '--texels', '--texture-size', '0'], 2, /--texture-size/);
    expectExit([...base, '--texels', '--texture-size', '20000'], 2, /--texture-size/);
    expectExit([...base, '--texels', '--texels-per-unit', '-3'], 2, /--texels-per-unit/);
    // 1e6 texels per metre over a 4 m room needs a side far past 16384: refused, not clamped.
    expectExit([...base, '--texels', '--texels-per-unit', '1000000'], EXIT_INVALID_INPUT, /outside 1 … 16384/);
    // The bowl has no UVs at all: without the generator the error names both sets.
    fs.writeFileSync(work('bowl.gltf'), bowlGltf());
    expectExit([work('bowl.gltf'), '-o', work('x.prt'), ...quick, '--texels', '--unwrap', 'never'], EXIT_INVALID_INPUT,
               /no UV set is a valid lightmap atlas.*TEXCOORD_1: absent.*TEXCOORD_0: absent/);
    expectExit([...base, '--blender', 'blender'], 2, /--blender needs --texels/);
    expectExit([...base, '--texels', '--unwrap', 'sometimes'], 2, /unknown --unwrap 'sometimes'/);
    expectExit([...base, '--texels', '--unwrap', 'never', '--blender', 'blender'], 2, /--blender needs --unwrap auto/);
    expectExit([...base, '--texels', '--unwrap-timeout', '0'], 2, /--unwrap-timeout expects seconds > 0/);
    check(!fs.existsSync(work('x.prt')), 'a failed texel bake wrote an asset');
    expectExit(['shade', out, '--texels', '--light', 'constant'], EXIT_INVALID_INPUT, /bake with --texels/);
    expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', 'glossy', '--view', '1,2,3'], EXIT_INVALID_INPUT,
               /no texel visibility pass \(bake with --texels --texel-glossy\)/);
    // TPFL glossy texels (--texel-glossy), each misuse named.
    expectExit([...base, '--texel-glossy'], 2, /--texel-glossy needs --texels/);
    expectExit([...base, '--texels', '--visibility-order', '5'], 2, /--visibility-order needs --texel-glossy/);
    for (const m of ['1', '17', 'x']) expectExit([...base, '--texels', '--texel-glossy', '--visibility-order', m], 2, /--visibility-order/);
    expectExit([...base, '--texels', '--texel-glossy', '--lighting', 'local'], 2, /--texel-glossy needs distant lighting/);
    expectExit([...base, '--specular-exponent', '8'], 2, /--specular-exponent needs --glossy or --texel-glossy/);
    expectExit([...base, '--texel-glossy', '--texels', '--glossy-bounces', '1'], 2, /--glossy-bounces needs --glossy/);
    check(!fs.existsSync(work('x.prt')), 'a refused texel-glossy bake wrote an asset');
    expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', 'glossy-interreflected', '--view', '1,2,3'], 2,
               /texel glossy is the shadowed TPFL visibility pass/);
    expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', 'glossy'], 2, /needs --view X,Y,Z/);
    expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', 'glossy', '--view', '1,nan,3'], 2, /--view expects X,Y,Z of finite numbers/);
    expectExit(['shade', out, '--texels', '--light', 'constant', '--view', '1,2,3'], 2, /--view needs a glossy --pass/);
  },

  texel_normal_glossy() {
    // Normal maps in the TPFL glossy term (asset format 1.6, texel normals): a lone plane with a
    // striped normal map (the normal tilted up to 31 degrees along x: stripeQuadGltf), exponent 1,
    // under uniform white light. The bake stores each texel's mapped normal n'; `shade` must
    // print it (within 1 degree of the map's, quantised to 8 bits) and reflect about it: the
    // closed form of texel_glossy with n' in Schlick's n'.v and in R' = reflect(-v, n'), the
    // lobe still clipped by the plane's own horizon (the bump does not move it):
    // k_s(n'.v) (1 + R'.y)/2. The same closed form about the plane's normal misses it at most
    // texels, so shading about the interpolated normal would fail. The plane without the map
    // gets no texel normals section.
    const material = { color: [0.8, 0.4, 0.2, 1], metallic: 0.5, roughness: 0.5 };
    const bakeArgs = ['--samples', '1024', '--order', '3', '--bounces', '0', '--quiet', '--texels', '--texture-size', '64',
                      '--texel-glossy', '--specular-exponent', '1', '--texture-sets', 'scene', '--unwrap', 'never'];
    fs.writeFileSync(work('stripes.gltf'), stripeQuadGltf(64, true, material));
    fs.writeFileSync(work('stripes-flat.gltf'), stripeQuadGltf(64, false, material));
    const mapped = work('stripes.prt'), flat = work('stripes-flat.prt');
    expectExit([work('stripes.gltf'), '-o', mapped, ...bakeArgs], 0);
    expectExit([work('stripes-flat.gltf'), '-o', flat, ...bakeArgs], 0);
    const info = json(expectExit(['info', mapped, '--json'], 0));
    check(info?.version === '1.7' && info?.texel_normals?.encoding === 'octahedral snorm16' && info.texel_normals.bytes === 4 * 64 * 64,
          `info texel_normals: ${JSON.stringify(info?.texel_normals)}`);
    check(/^texel normals: normal-mapped shading normals for the glossy term, octahedral 2 x 16 bits \(snorm\), 16384 bytes$/m.test(
      expectExit(['info', mapped], 0).stdout), 'info text lacks the texel normals line');
    check(json(expectExit(['info', flat, '--json'], 0))?.texel_normals === null, 'the plane without a normal map has texel normals');
    const f0 = [0.8, 0.4, 0.2].map((b) => 0.5 * 0.04 + 0.5 * b);
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const closedForm = (n, v, c) => {
      const nv = dot(n, v), r = [0, 1, 2].map((i) => 2 * nv * n[i] - v[i]);
      return (f0[c] + (1 - f0[c]) * (1 - Math.max(0, nv)) ** 5) * (1 + r[1] / Math.hypot(...r)) / 2;
    };
    for (const eye of [[0.3, 1.5, 0.8], [-1.2, 2.0, 0.5]]) {
      const s = json(expectExit(['shade', mapped, '--texels', '--light', 'constant', '--json', '--pass', 'glossy', '--view', eye.join(','),
                                 '--glossy-only'], 0));
      if (!s) return;
      check(s.texels.length === 64 * 64, `stripes texels: ${s.texels.length}`);
      let worstNormal = 0, worst = 0, interpolatedMisses = 0, compared = 0;
      for (const t of s.texels) {
        if (!t.shading_normal) { check(false, `texel (${t.x}, ${t.y}) has no shading_normal`); return; }
        const slope = stripeSlope((t.x + 0.5) / 64), want = [slope, 1, 0].map((c) => c / Math.hypot(slope, 1));
        worstNormal = Math.max(worstNormal, Math.acos(Math.min(1, dot(want, t.shading_normal))) * 180 / Math.PI);
        const d = eye.map((e, i) => e - t.position[i]), v = d.map((c) => c / Math.hypot(...d));
        if (dot(t.shading_normal, v) < 0.05) continue;  // grazing the bump: Schlick's clamp, not this test's subject
        compared++;
        let missed = false;
        for (let c = 0; c < 3; c++) {
          const want = closedForm(t.shading_normal, v, c);
          worst = Math.max(worst, Math.abs(t.radiance[c] - want) / want);
          const plain = closedForm(t.normal, v, c);
          missed ||= Math.abs(t.radiance[c] - plain) / plain > 0.02;
        }
        if (missed) interpolatedMisses++;
      }
      console.log(`eye ${eye}: ${compared} texels, stored normals within ${worstNormal.toFixed(3)} degrees of the map's, glossy within ` +
                  `${worst.toExponential(2)} of the closed form about them; about the plane's normal ${interpolatedMisses} texels miss by > 2 %`);
      check(worstNormal < 1, `eye ${eye}: a stored shading normal is ${worstNormal} degrees from the map's`);
      check(compared > 0.9 * 64 * 64, `eye ${eye}: only ${compared} texels face the eye through their bump`);
      check(worst < 0.02, `eye ${eye}: TPFL glossy about the stored normal differs from the closed form by ${worst} (relative) at worst`);
      check(interpolatedMisses > 0.5 * compared, `eye ${eye}: the interpolated normal's closed form misses only ${interpolatedMisses} of ${compared} texels`);
    }
  },

  texel_glossy() {
    // TPFL glossy transfer textures (--texels --texel-glossy): the visibility pass in the bake's
    // report and in `info`, and `shade --texels --pass glossy --view` against physics.
    // 1. A lone glossy plane (tests/cli/plane_gltf.mjs): nothing occludes it, so under uniform
    //    white light its glossy term has the closed form of docs/glossy.md for a Phong lobe of
    //    exponent 1: k_s (1 + n.v)/2 (the lobe above the horizon, R at angle acos(n.v) from
    //    n), k_s Schlick's with f0 = mix(0.04, base, metallic), f90 = 1. With order 3 lighting
    //    and visibility order 5 the TPFL product is exact, and the exponent-1 lobe meets the
    //    hemisphere only in bands 0 and 1, so what is left is the Monte Carlo error of the
    //    1024-sample visibility: measured 0.4% (eye above) and 0.9% (grazing eye) at worst,
    //    10% with 64 samples; tolerance 2%.
    fs.writeFileSync(work('plane.gltf'), planeGltf());
    const plane = work('plane.prt');
    const r = expectExit([work('plane.gltf'), '-o', plane, '--samples', '1024', '--order', '3', '--bounces', '0', '--quiet', '--json',
                          '--texels', '--texture-size', '64', '--texel-glossy', '--specular-exponent', '1'], 0);
    const stats = json(r);
    check(stats?.texels?.visibility_order === 5, `bake report: ${JSON.stringify(stats?.texels)}`);
    const f0 = [0.8, 0.4, 0.2].map((b) => 0.5 * 0.04 + 0.5 * b);
    const shadeTexels = (file, extra) =>
      json(expectExit(['shade', file, '--texels', '--light', 'constant', '--json', ...extra], 0));
    for (const eye of [[0.3, 1.5, 0.8], [-3, 0.4, 1]]) {
      const s = shadeTexels(plane, ['--pass', 'glossy', '--view', eye.join(','), '--glossy-only']);
      if (!s) return;
      check(s.glossy === 'visibility' && s.visibility_order === 5 && s.product?.transfer_order === 5, `shade header: ${JSON.stringify({ ...s, texels: undefined })}`);
      check(s.texels.length > 2000, `plane texels: ${s.texels.length}`);
      let worst = 0;
      for (const t of s.texels) {
        const d = eye.map((e, i) => e - t.position[i]);
        const nv = d[1] / Math.hypot(...d);
        for (let c = 0; c < 3; c++) {
          const want = (f0[c] + (1 - f0[c]) * (1 - nv) ** 5) * (1 + nv) / 2;
          worst = Math.max(worst, Math.abs(t.radiance[c] - want) / want);
        }
      }
      check(worst < 0.02, `eye ${eye}: TPFL glossy differs from k_s (1 + n.v)/2 by ${worst} (relative) at worst`);
    }
    // Compressed like the other texel passes: encoded in info, shading within the codec's error.
    const packed = work('plane-q16.prt');
    expectExit([work('plane.gltf'), '-o', packed, '--samples', '1024', '--order', '3', '--bounces', '0', '--quiet', '--texels',
                '--texture-size', '64', '--texel-glossy', '--specular-exponent', '1', '--compress', 'q16'], 0);
    const vis = json(expectExit(['info', packed, '--json'], 0))?.passes?.find((p) => p.form === 'visibility');
    check(vis?.encoded === true && vis.order === 5, `compressed visibility pass: ${JSON.stringify(vis)}`);
    const a = shadeTexels(plane, ['--pass', 'glossy', '--view', '0.3,1.5,0.8', '--glossy-only']);
    const b = shadeTexels(packed, ['--pass', 'glossy', '--view', '0.3,1.5,0.8', '--glossy-only']);
    if (a && b && check(a.texels.length === b.texels.length, 'compressed texel count')) {
      const diff = Math.max(...a.texels.map((t, i) => Math.max(...t.radiance.map((x, c) => Math.abs(x - b.texels[i].radiance[c])))));
      check(diff < 1e-3, `q16 visibility shades ${diff} away from float32`);
    }

    // 2. The default room at 512 texels a side: the pass in `info`, the matte
    //    room's glossy term exactly 0, the polished sphere's and the metal torus's following
    //    the eye, every value finite, and diffuse + glossy the sum of the two terms.
    const { out, r: room } = bakeDefault('room-glossy.prt', ['--bounces', '0', '--texels', '--texture-size', '512', '--texel-glossy', '--json']);
    check(json(room)?.texels?.visibility_order === 5, 'room bake reports visibility order 5');
    const info = json(expectExit(['info', out, '--json'], 0));
    const v = info?.passes?.filter((p) => p.form === 'visibility') ?? [];
    check(v.length === 1 && v[0].kind === 'shadowed' && v[0].domain === 'texel' && v[0].order === 5 && v[0].channels === 1,
          `info visibility pass: ${JSON.stringify(info?.passes)}`);
    check(info?.version === '1.7', `version ${info?.version}`);
    const text = expectExit(['info', out], 0).stdout;
    check(/^pass: texel shadowed visibility \(TPFL glossy\), order 5 \(25 coefficients per texel, exact\), float32, \d+ bytes$/m.test(text),
          `info text: ${text}`);
    const eyeA = ['--view', '-0.9,0.9,3'], eyeB = ['--view', '2,2.5,-0.5'];
    const glossyA = shadeTexels(out, ['--pass', 'glossy', ...eyeA, '--glossy-only']);
    const glossyB = shadeTexels(out, ['--pass', 'glossy', ...eyeB, '--glossy-only']);
    const both = shadeTexels(out, ['--pass', 'glossy-shadowed', ...eyeA]);
    const diffuse = shadeTexels(out, ['--pass', 'shadowed']);
    if (!glossyA || !glossyB || !both || !diffuse) return;
    const n = glossyA.texels.length;
    check(n > 100000 && glossyB.texels.length === n && both.texels.length === n && diffuse.texels.length === n, `texel counts ${n}`);
    let floorZero = 0, floorLit = 0, moved = 0, finite = true, sumError = 0;
    for (let t = 0; t < n; t++) {
      const a = glossyA.texels[t], b = glossyB.texels[t];
      finite &&= [...a.radiance, ...b.radiance, ...both.texels[t].radiance].every(Number.isFinite);
      if (Math.abs(a.position[1]) < 1e-4 && a.normal[1] > 0.999) {  // the matte floor
        if (a.radiance.every((x) => x === 0) && b.radiance.every((x) => x === 0)) floorZero++;
        else floorLit++;
      }
      if (Math.abs(a.radiance[0] - b.radiance[0]) > 1e-3) moved++;
      for (let c = 0; c < 3; c++) {
        sumError = Math.max(sumError, Math.abs(both.texels[t].radiance[c] - (diffuse.texels[t].radiance[c] + a.radiance[c])));
      }
    }
    check(finite, 'a texel radiance is not finite');
    check(floorZero > 10000 && floorLit === 0, `matte floor texels: ${floorZero} with no glossy term, ${floorLit} with one`);
    check(moved > 1000, `texels whose glossy term follows the eye: ${moved}`);
    check(sumError < 1e-4, `diffuse + glossy differs from the sum of the terms by ${sumError}`);
  },

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
      check(info.passes.every((p) => p.domain === 'vertex'), `a vertex bake's passes: ${JSON.stringify(info.passes)}`);
      check(info.texels === 0 && Array.isArray(info.atlases) && info.atlases.length === 0,
            `no transfer textures: texels ${info.texels}, atlases ${JSON.stringify(info.atlases)}`);
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
    expectExit(['info', work('truncated.prt')], EXIT_INVALID_INPUT, /truncated/);
    const flipped = Buffer.from(bytes);
    flipped[Math.floor(bytes.length * 0.7)] ^= 0x40;
    fs.writeFileSync(work('flipped.prt'), flipped);
    expectExit(['info', work('flipped.prt')], EXIT_INVALID_INPUT, /checksum/);
    fs.writeFileSync(work('garbage.prt'), Buffer.from('definitely not an asset, just text'));
    expectExit(['info', work('garbage.prt')], EXIT_INVALID_INPUT, /magic|truncated/);
    expectExit(['info', work('missing.prt')], EXIT_NOT_FOUND, /no such file/);
    // A FIFO given as an input is refused at once, not waited on (no writer ever comes).
    const fifo = work('fifo.prt');
    fs.rmSync(fifo, { force: true });
    check(spawnSync('mkfifo', [fifo]).status === 0, 'mkfifo failed');
    expectExit(['info', fifo], EXIT_INVALID_INPUT, /fifo\.prt': not a regular file/);
    expectExit([fifo.replace(/\.prt$/, '.gltf'), '-o', work('x.prt')], EXIT_NOT_FOUND, /no such file/);
    fs.renameSync(fifo, work('fifo.gltf'));
    expectExit([work('fifo.gltf'), '-o', work('x.prt'), '--quiet'], EXIT_INVALID_INPUT, /fifo\.gltf': not a regular file/);
    expectExit(['shade', out, '--light', 'constant', '--pass', 'interreflected'], EXIT_INVALID_INPUT, /no interreflected pass/);
    expectExit(['shade', out, '--light', 'constant', '--order', '9'], 2, /exceeds the asset's order/);
  },

  bad_scenes() {
    expectExit([work('nothing.gltf'), '-o', work('x.prt')], EXIT_NOT_FOUND, /nothing\.gltf/);
    fs.writeFileSync(work('broken.gltf'), '{"asset": {"version": "2.0"}, "meshes": [');
    expectExit([work('broken.gltf'), '-o', work('x.prt'), '--quiet'], EXIT_INVALID_INPUT, /broken\.gltf/);
    fs.writeFileSync(work('empty.gltf'), '{"asset": {"version": "2.0"}}');
    expectExit([work('empty.gltf'), '-o', work('x.prt'), '--quiet'], EXIT_INVALID_INPUT, /triangle/);
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
      check(info.version === '1.7' && info.name === 'default-room-local', `info: ${JSON.stringify(info)}`);
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
  white_furnace() {
    // A bowl of albedo 1 under constant radiance 1 (bowl_gltf.mjs): every point sees half
    // bowl, half sky, so after N bounces B = 1 - 2^-(N+1) everywhere, tending to 1. An albedo
    // ceiling below 1 shows here at once (0.95 gives 0.905 in the limit).
    const scene = work('bowl.gltf');
    fs.writeFileSync(scene, bowlGltf({ albedo: 1 }));
    const bakeBowl = (name, bounces) => {
      const out = work(name);
      expectExit([scene, '-o', out, '--order', '2', '--samples', '4096', '--passes', 'interreflected',
                  '--bounces', String(bounces), '--quiet'], 0);
      return json(expectExit(['shade', out, '--light', 'constant', '--pass', 'interreflected', '--json'], 0));
    };
    for (const bounces of [2, 16]) {
      const expected = 1 - 2 ** -(bounces + 1);
      const r = bakeBowl(`bowl-${bounces}.prt`, bounces);
      if (!r) continue;
      const values = r.vertices.map((v) => v.radiance[0]);
      const mean = values.reduce((a, b) => a + b, 0) / values.length;
      const bottom = r.vertices.reduce((a, v) => (v.position[1] < a.position[1] ? v : a));
      check(Math.abs(mean - expected) < 0.01, `${bounces} bounces: mean exit radiance ${mean}, expected ${expected}`);
      check(Math.abs(bottom.radiance[0] - expected) < 0.02,
            `${bounces} bounces: bottom exit radiance ${bottom.radiance[0]}, expected ${expected}`);
      const worst = Math.max(...values.map((x) => Math.abs(x - expected)));
      check(worst < 0.05, `${bounces} bounces: a vertex is ${worst} from ${expected}`);
      check(r.vertices.every((v) => v.radiance[0] === v.radiance[1] && v.radiance[1] === v.radiance[2]), 'grey in, grey out');
    }
    // Not a special case for 1: albedo 1/2 converges to (1/4) / (1 - 1/4) = 1/3.
    fs.writeFileSync(scene, bowlGltf({ albedo: 0.5 }));
    const half = bakeBowl('bowl-half.prt', 16);
    if (half) {
      const mean = half.vertices.reduce((a, v) => a + v.radiance[0], 0) / half.vertices.length;
      check(Math.abs(mean - 1 / 3) < 0.01, `albedo 0.5: mean exit radiance ${mean}, expected 1/3`);
    }
  },

  compress_svg() {
    // compress-report --svg: a well-formed SVG (parsed by a real XML parser, Python's
    // ElementTree) with one mark per setting, each where the report's numbers put it on the
    // plot's own tick marks (log x: bytes per vertex; linear y: dB), and the 40 dB line.
    const { out: asset } = bakeDefault('room.prta', ['--bounces', '1']);
    const svgPath = work('rd.svg');
    const settings = ['f32', 'f16', 'q8', 'cpca8@0.05'];
    const report = json(expectExit(['compress-report', asset, '--json', '--lightings', '4', '--settings', settings.join(','),
                                    '--svg', svgPath], 0));
    if (!report || !check(fs.existsSync(svgPath), '--svg wrote no file')) return;
    check(!fs.readdirSync(workDir).some((f) => f.includes('.prt-partial-')), `temporaries left: ${fs.readdirSync(workDir)}`);
    const parse = spawnSync('/usr/bin/python3', ['-c', `
import json, sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
def walk(e):
    return {'tag': e.tag.split('}')[-1], 'ns': e.tag.split('}')[0][1:] if '}' in e.tag else '',
            'attrs': dict(e.attrib), 'text': ''.join(e.itertext()), 'children': [walk(c) for c in e]}
print(json.dumps(walk(root)))
`, svgPath], { encoding: 'utf8' });
    if (!check(parse.status === 0, `the SVG does not parse as XML: ${parse.stderr}`)) return;
    const root = JSON.parse(parse.stdout);
    check(root.tag === 'svg' && root.ns === 'http://www.w3.org/2000/svg', `root element ${root.ns} ${root.tag}`);
    const all = [];
    const flatten = (e) => { all.push(e); e.children.forEach(flatten); };
    flatten(root);
    const cls = (e) => (e.attrs.class || '').split(' ');
    check(!all.some((e) => e.tag === 'script' || e.tag === 'image' || e.tag === 'foreignObject' ||
                          Object.keys(e.attrs).some((k) => /href$/.test(k))), 'the SVG is not self-contained');
    const ticks = (axis) => all.filter((e) => e.tag === 'g' && cls(e).includes('tick') && cls(e).includes(axis)).map((g) => {
      const line = g.children.find((c) => c.tag === 'line');
      return { value: Number(g.children.find((c) => c.tag === 'text').text), at: Number(axis === 'x' ? line.attrs.x1 : line.attrs.y1) };
    });
    // Each axis's map from value to position, from its outermost ticks; every tick must agree.
    const axisMap = (list, f) => {
      const a = list[0], b = list[list.length - 1];
      const map = (v) => a.at + (f(v) - f(a.value)) / (f(b.value) - f(a.value)) * (b.at - a.at);
      for (const t of list) check(Math.abs(map(t.value) - t.at) < 0.05, `tick ${t.value} at ${t.at}, the axis puts it at ${map(t.value)}`);
      return map;
    };
    const xt = ticks('x'), yt = ticks('y');
    if (!check(xt.length >= 3 && yt.length >= 3, `too few ticks: x ${xt.length}, y ${yt.length}`)) return;
    const x = axisMap(xt, Math.log10), y = axisMap(yt, (v) => v);
    const marks = all.filter((e) => e.tag === 'circle' && cls(e).includes('mark'));
    check(marks.length === settings.length, `${marks.length} marks for ${settings.length} settings`);
    const topTick = Math.min(...yt.map((t) => t.at));
    for (const row of report.rows) {
      const m = marks.filter((e) => e.attrs['data-setting'] === row.setting);
      if (!check(m.length === 1, `${m.length} marks for ${row.setting}`)) continue;
      const cx = Number(m[0].attrs.cx), cy = Number(m[0].attrs.cy);
      check(Math.abs(cx - x(row.bytes_per_vertex)) < 0.5, `${row.setting}: mark at x ${cx}, ${row.bytes_per_vertex} B/vertex is at ${x(row.bytes_per_vertex)}`);
      if (row.psnr_db === null) {  // exact (f32): in the band above the top tick
        check(cy < topTick - 5, `${row.setting} is exact but its mark (y ${cy}) is not above the top tick (${topTick})`);
      } else {
        check(Math.abs(cy - y(row.psnr_db)) < 0.5, `${row.setting}: mark at y ${cy}, ${row.psnr_db} dB is at ${y(row.psnr_db)}`);
      }
      check(all.some((e) => e.tag === 'text' && cls(e).includes('mark-label') && e.text === row.setting), `no label for ${row.setting}`);
    }
    const threshold = all.find((e) => e.tag === 'line' && cls(e).includes('threshold'));
    check(threshold && Math.abs(Number(threshold.attrs.y1) - y(40)) < 0.5, `the 40 dB line is at ${threshold?.attrs.y1}, 40 dB is at ${y(40)}`);
    const texts = all.filter((e) => e.tag === 'text').map((e) => e.text).join('\n');
    check(/bytes per vertex/.test(texts) && /PSNR \(dB\)/.test(texts) && /40 dB/.test(texts), `axis titles or the 40 dB label missing: ${texts}`);
    // A bad --svg fails before any encoding, naming the path; the asset is never replaced.
    fs.mkdirSync(work('dir'));
    const r = expectExit(['compress-report', asset, '--settings', 'q8', '--svg', work('dir')], EXIT_INVALID_INPUT, /exists and is a directory/);
    check(!/encoding/.test(r.stderr), `encoding started before the --svg check: ${r.stderr}`);
    expectExit(['compress-report', asset, '--settings', 'q8', '--svg', asset], EXIT_INVALID_INPUT, /refusing to overwrite it/);
    expectExit(['compress-report', asset, '--svg'], 2, /--svg/);
  },
  output_safety() {
    // -o never destroys what is not a regular file, nor any input; the check runs before the
    // bake. Each refusal names the path.
    const scene = work('scene.gltf');
    fs.writeFileSync(scene, bowlGltf({ rings: 4, slices: 8 }));
    const sceneBytes = fs.readFileSync(scene);
    const quickBowl = ['--order', '2', '--samples', '16', '--quiet'];
    const refused = (out, pattern) => {
      const r = expectExit([scene, '-o', out, ...quickBowl], EXIT_INVALID_INPUT, pattern);
      check(r.stderr.includes(`'${out}'`), `the refusal names ${out}: ${r.stderr}`);
    };
    const fifo = work('fifo');
    check(spawnSync('mkfifo', [fifo]).status === 0, 'mkfifo failed');
    refused(fifo, /exists and is a FIFO; refusing to replace it/);
    check(fs.lstatSync(fifo).isFIFO(), 'the FIFO was replaced');
    fs.mkdirSync(work('dir'));
    refused(work('dir'), /exists and is a directory; refusing/);
    // A link to a device must not replace the link nor write to the device.
    fs.symlinkSync('/dev/null', work('null-link'));
    refused(work('null-link'), /exists and is a character device; refusing/);
    check(fs.lstatSync(work('null-link')).isSymbolicLink() && fs.statSync('/dev/null').isCharacterDevice(),
          'the link to /dev/null or /dev/null itself was replaced');
    // A device node itself (root can make one; CI runs as root).
    if (spawnSync('mknod', [work('devnode'), 'c', '1', '3']).status === 0) {
      refused(work('devnode'), /exists and is a character device; refusing/);
      check(fs.lstatSync(work('devnode')).isCharacterDevice(), 'the device node was replaced');
    } else {
      console.log('output_safety: not root, so no device node of our own; the link to /dev/null covers devices');
    }
    // The input itself, by the same name, a hard link or a symbolic link.
    refused(scene, /is the input '.*scene\.gltf'; refusing to overwrite it/);
    fs.linkSync(scene, work('hard.gltf'));
    refused(work('hard.gltf'), /is the input/);
    fs.symlinkSync(scene, work('alias.gltf'));
    refused(work('alias.gltf'), /is the input/);
    fs.symlinkSync(work('missing.prt'), work('dangling'));
    refused(work('dangling'), /symbolic link to a missing/);
    check(Buffer.compare(fs.readFileSync(scene), sceneBytes) === 0, 'the input scene changed');

    // What is allowed: replacing a regular file, and writing through a link to one (the link stays).
    fs.writeFileSync(work('old.prt'), 'old');
    expectExit([scene, '-o', work('old.prt'), ...quickBowl], 0);
    expectExit(['info', work('old.prt')], 0);
    fs.writeFileSync(work('target.prt'), 'old');
    fs.symlinkSync(work('target.prt'), work('link.prt'));
    expectExit([scene, '-o', work('link.prt'), ...quickBowl], 0);
    check(fs.lstatSync(work('link.prt')).isSymbolicLink(), 'the link to the output was replaced by a file');
    expectExit(['info', work('target.prt')], 0);
    const left = fs.readdirSync(workDir).filter((f) => f.includes('.prt-partial-'));
    check(left.length === 0, `temporaries left: ${left.join(', ')}`);
  },

  durable_write() {
    // The file is flushed before the rename and its directory after it (strace shows the calls).
    const scene = work('scene.gltf');
    fs.writeFileSync(scene, bowlGltf({ rings: 4, slices: 8 }));
    const out = work('out.prt'), trace = work('trace.txt');
    const r = spawnSync('strace', ['-f', '-o', trace, '-e', 'trace=openat,fsync,fdatasync,rename,renameat,renameat2',
                                   bake, scene, '-o', out, '--order', '2', '--samples', '16', '--quiet'],
                         // LeakSanitizer cannot run under ptrace; the other tests check leaks.
                         { encoding: 'utf8', env: { ...process.env, ASAN_OPTIONS: `${process.env.ASAN_OPTIONS ?? ''}:detect_leaks=0` } });
    if (!check(r.status === 0, `strace prt-bake failed (is strace installed?): ${r.error?.message ?? r.stderr.slice(-400)}`)) return;
    const lines = fs.readFileSync(trace, 'utf8').split('\n');
    const renameAt = lines.findIndex((l) => /rename/.test(l) && l.includes('.prt-partial-') && l.includes(`"${out}"`) && / = 0$/.test(l));
    if (!check(renameAt >= 0, `no successful rename of a temporary onto ${out} in the trace`)) return;
    const fsyncsBefore = lines.slice(0, renameAt).filter((l) => /fsync\(\d+\)\s+= 0/.test(l));
    check(fsyncsBefore.length >= 1, 'the temporary is not flushed before the rename');
    const after = lines.slice(renameAt + 1);
    const dirOpen = after.map((l) => l.match(new RegExp(`openat\\(AT_FDCWD, "${workDir.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}", [^)]*O_DIRECTORY[^)]*\\)\\s+= (\\d+)`))).find(Boolean);
    if (!check(dirOpen, `the output's directory is not opened after the rename:\n${after.slice(0, 10).join('\n')}`)) return;
    check(after.some((l) => new RegExp(`fsync\\(${dirOpen[1]}\\)\\s+= 0`).test(l)), 'the directory is not flushed after the rename');
  },

  async signal_window() {
    // Killed with its temporary complete but not yet renamed (the test hook holds it there),
    // the baker removes the temporary, the old output stays as it was, and the process still
    // dies of the signal.
    const scene = work('scene.gltf');
    fs.writeFileSync(scene, bowlGltf({ rings: 4, slices: 8 }));
    for (const signal of ['SIGINT', 'SIGTERM', 'SIGHUP']) {
      const out = work(`out-${signal}.prt`);
      fs.writeFileSync(out, 'old');
      const child = spawn(bake, [scene, '-o', out, '--order', '2', '--samples', '16', '--quiet'],
                          { env: { ...process.env, PRT_TEST_STALL_BEFORE_RENAME_MS: '60000' } });
      let stderr = '';
      const stalled = new Promise((resolve) => child.stderr.on('data', (d) => {
        stderr += d;
        if (stderr.includes('stalling before renaming')) resolve(true);
      }));
      const exited = new Promise((resolve) => child.on('exit', (c, s) => resolve(s || c)));
      let timer;
      const timeout = new Promise((r) => { timer = setTimeout(() => r('timeout'), 60000); });
      const first = await Promise.race([stalled, exited, timeout]);
      clearTimeout(timer);  // or the pending timer keeps node alive for its full minute
      if (!check(first === true, `${signal}: the bake never reached the rename (${first}): ${stderr}`)) {
        child.kill('SIGKILL');
        continue;
      }
      const partial = fs.readdirSync(workDir).filter((f) => f.startsWith(`out-${signal}.prt.prt-partial-`));
      check(partial.length === 1, `${signal}: expected one temporary while stalled, found ${partial.join(', ')}`);
      child.kill(signal);
      const how = await exited;
      check(how === signal, `${signal}: the baker should die of the signal, got ${how}`);
      const left = fs.readdirSync(workDir).filter((f) => f.includes('.prt-partial-'));
      check(left.length === 0, `${signal}: temporaries left: ${left.join(', ')}`);
      check(fs.readFileSync(out, 'utf8') === 'old', `${signal}: the old output was changed`);
    }
  },

  texture_sets() {
    // One floor patch instanced twice (the same TEXCOORD_1), one instance in the open, one
    // under a low roof: as one atlas the instances overlap (rejected), as texture sets each
    // object gets its own atlas and the roofed instance is in shadow.
    const patch = quad([-0.5, 0, -0.5], [0, 0, 1], [1, 0, 0], [0.1, 0.1, 0.9, 0.9]);   // faces +y
    const roof = quad([-1.5, 0.25, -1.5], [3, 0, 0], [0, 0, 3], [0.1, 0.1, 0.9, 0.9]);  // faces -y
    const scene = work('instanced.gltf');
    fs.writeFileSync(scene, texturedSceneGltf([patch, roof], [
      { mesh: 0, translation: [-3, 0, 0], name: 'open' },
      { mesh: 0, translation: [3, 0, 0], name: 'roofed' },
      { mesh: 1, translation: [3, 0, 0], name: 'roof' },
    ]));
    const common = ['--samples', '64', '--order', '3', '--texels', '--texels-per-unit', '32', '--unwrap', 'never'];
    expectExit([scene, '-o', work('scene.prt'), ...common, '--texture-sets', 'scene'], EXIT_INVALID_INPUT,
               /no UV set is a valid lightmap atlas.*TEXCOORD_1: \d+ overlapping triangle pairs/);
    check(!fs.existsSync(work('scene.prt')), 'a failed bake wrote an asset');
    const out = work('sets.prt');
    const r = expectExit([scene, '-o', out, ...common, '--json'], 0,
                         /texture sets: 3 atlases: one atlas per object: no UV set is valid for the whole scene, but 3 of 3 objects/);
    check(/transfer textures: 3 atlases \(/.test(r.stderr) && /atlas 1: node 1 \('roofed'\), mesh 0: TEXCOORD_1, 32x32, 2 triangles/.test(r.stderr),
          `atlas lines: ${r.stderr}`);
    const stats = json(r);
    const atlases = stats?.texels?.atlases ?? [];
    check(atlases.length === 3 && atlases.every((a) => a.uv === 'TEXCOORD_1'), `atlases: ${JSON.stringify(atlases)}`);
    check(atlases.map((a) => a.size).join() === '32,32,96', `atlas sizes: ${JSON.stringify(atlases)}`);
    const info = json(expectExit(['info', out, '--json'], 0));
    check(info?.atlases?.length === 3 && info.atlases.map((a) => a.triangleCount).join() === '2,2,2', `info atlases: ${JSON.stringify(info?.atlases)}`);
    const used = (info?.atlas_usage ?? []).map((u) => u.sampled);
    check(used.length === 3 && used.every((n, i) => n === atlases[i]?.sampled && n > 0), `atlas usage ${JSON.stringify(info?.atlas_usage)} vs ${JSON.stringify(atlases)}`);
    const text = expectExit(['info', out], 0).stdout;
    check(/^atlas 0: 32x32, triangles 0-1 \(2\), 1 chart, \d+ texels sampled/m.test(text) && /^atlas 2: 96x96, triangles 4-5 \(2\)/m.test(text), `info text: ${text}`);
    const s = json(expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', 'shadowed', '--json'], 0));
    if (!s) return;
    check(s.texels.length === stats?.texels?.sampled, `shade printed ${s.texels.length} of ${stats?.texels?.sampled} texels`);
    for (const a of [0, 1, 2]) check(s.texels.filter((x) => x.atlas === a).length === atlases[a]?.sampled, `shade texels of atlas ${a}`);
    const mean = (atlas) => {
      const xs = s.texels.filter((x) => x.atlas === atlas).map((x) => x.radiance[0]);
      return xs.reduce((p, q) => p + q, 0) / xs.length;
    };
    const open = mean(0), roofed = mean(1);
    check(s.texels.filter((x) => x.atlas === 0).every((x) => x.position[0] < -2) &&
          s.texels.filter((x) => x.atlas === 1).every((x) => x.position[0] > 2 && Math.abs(x.position[1]) < 1e-5),
          'atlas 0 should hold the open instance, atlas 1 the roofed one');
    check(open > 0.6 && roofed < 0.2 * open, `shadowed radiance: open ${open}, roofed ${roofed}`);
    console.log(`texture_sets: open instance ${open.toFixed(4)}, roofed ${roofed.toFixed(4)}; sizes ${atlases.map((a) => a.size).join(', ')}`);
  },

  texture_sets_density() {
    // A 4 m floor and a 10 cm box in one valid TEXCOORD_1: the box gets 5x the floor's texels
    // per metre there, so auto splits them, and each atlas then gets the asked-for density.
    const floor = quad([-2, 0, -2], [0, 0, 4], [4, 0, 0], [0.02, 0.02, 0.62, 0.62]);
    const cube = box([-0.05, 0, -0.05], [0.05, 0.1, 0.05], [0.66, 0.02, 0.98, 0.34]);
    const scene = work('floor-box.gltf');
    fs.writeFileSync(scene, texturedSceneGltf([floor, cube], [{ mesh: 0, name: 'floor' }, { mesh: 1, name: 'box' }]));
    const common = ['--samples', '16', '--order', '2', '--passes', 'shadowed', '--texels', '--unwrap', 'never', '--json'];
    const tolerance = 0.05;  // a side is rounded up to whole texels: a 38-texel atlas is 2.6% over
    const byDensity = json(expectExit([scene, '-o', work('tpu.prt'), ...common, '--texels-per-unit', '64'], 0,
                                      /texture sets: 2 atlases: one atlas per object \(2 objects\): in TEXCOORD_1 node 1 \('box'\), mesh 1 has [0-9.]+x the texels per metre of node 0/));
    const a = byDensity?.texels?.atlases ?? [];
    check(a.length === 2 && a.every((x) => Math.abs(x.texels_per_metre / 64 - 1) < tolerance), `densities at 64 texels/m: ${JSON.stringify(a)}`);
    const byBudget = json(expectExit([scene, '-o', work('budget.prt'), ...common, '--texture-size', '256'], 0));
    const b = byBudget?.texels?.atlases ?? [];
    const total = b.reduce((p, x) => p + x.size * x.size, 0);
    check(b.length === 2 && Math.abs(b[1].texels_per_metre / b[0].texels_per_metre - 1) < tolerance, `budget densities: ${JSON.stringify(b)}`);
    check(Math.abs(total / (256 * 256) - 1) < tolerance, `budget: ${total} texels for 256 x 256`);
    const one = json(expectExit([scene, '-o', work('one.prt'), ...common, '--texels-per-unit', '64', '--texture-sets', 'scene'], 0));
    check(one?.texels?.atlases?.length === 1, `--texture-sets scene: ${JSON.stringify(one?.texels?.atlases)}`);
    console.log(`texture_sets_density: per object ${a.map((x) => `${x.size}^2 at ${x.texels_per_metre.toFixed(2)}/m`).join(', ')}; ` +
                `budget ${b.map((x) => `${x.size}^2 at ${x.texels_per_metre.toFixed(2)}/m`).join(', ')}`);
  },

  texture_sets_default() {
    // The default room has a valid scene-wide TEXCOORD_1 of one density: auto keeps one atlas,
    // and the asset is byte for byte the one --texture-sets scene (the old path) writes.
    const auto = bakeDefault('auto.prt', ['--texels', '--texture-size', '512']).out;
    const r = expectExit(['--default', '-o', work('scene.prt'), '--samples', '64', '--order', '3', '--texels', '--texture-size', '512',
                          '--texture-sets', 'scene'], 0, /texture sets: 1 atlas: one atlas: TEXCOORD_1 is valid for the whole scene/);
    check(/transfer textures: TEXCOORD_1, 512x512 atlas/.test(r.stderr), `summary: ${r.stderr}`);
    check(Buffer.compare(fs.readFileSync(auto), fs.readFileSync(work('scene.prt'))) === 0, 'auto and --texture-sets scene differ');
    const info = json(expectExit(['info', auto, '--json'], 0));
    check(info?.atlases?.length === 1 && info.atlases[0].width === 512, `atlases: ${JSON.stringify(info?.atlases)}`);
  },

  texture_sets_limit() {
    // 1025 instances of one small quad: one atlas each would pass the format's 1024.
    const tile = quad([0, 0, 0], [0, 0, 0.1], [0.1, 0, 0], [0.1, 0.1, 0.9, 0.9]);
    const nodes = [];
    for (let i = 0; i < 1025; i++) nodes.push({ mesh: 0, translation: [0.2 * (i % 40), 0, 0.2 * Math.floor(i / 40)] });
    const scene = work('tiles.gltf');
    fs.writeFileSync(scene, texturedSceneGltf([tile], nodes));
    expectExit([scene, '-o', work('tiles.prt'), '--samples', '16', '--texels', '--texture-sets', 'object', '--unwrap', 'never'],
               EXIT_INVALID_INPUT, /the scene has 1025 objects, but an asset holds at most 1024 atlases; the first past the limit is node 1024, mesh 0/);
    check(!fs.existsSync(work('tiles.prt')), 'a failed bake wrote an asset');
    expectExit([scene, '-o', work('x.prt'), '--texture-sets', 'object'], 2, /--texture-sets needs --texels/);
    expectExit([scene, '-o', work('x.prt'), '--texels', '--texture-sets', 'atlas'], 2, /unknown --texture-sets 'atlas' \(expected auto, scene or object\)/);
  },

  texel_unwrap() {
    // A scene without UVs gets a generated atlas (the real Blender, once): the bake says so in
    // its text and JSON, the asset's atlas is valid, and shading its texels works. The default
    // room keeps its own TEXCOORD_1 (texels case).
    const scene = work('bowl.gltf');
    fs.writeFileSync(scene, bowlGltf({ rings: 8, slices: 16 }));
    const out = work('bowl.prt');
    const r = expectExit([scene, '-o', out, '--samples', '64', '--order', '3', '--texels', '--texture-size', '128', '--json'], 0,
                         /transfer textures: generated atlas \(Blender Smart UV Project, \d+ attempts?, margin [0-9.e-]+, [0-9.]+ s\), 128x128 atlas/);
    check(/atlas attempt 1: Smart UV Project, margin [0-9.e-]+, 128x128: [0-9.]+ s, /.test(r.stderr), `attempt lines: ${r.stderr}`);
    check(/not used: TEXCOORD_1: absent/.test(r.stderr) && /not used: TEXCOORD_0: absent/.test(r.stderr), `rejected sets: ${r.stderr}`);
    const stats = json(r);
    if (stats) {
      const t = stats.texels;
      check(t?.atlas === 'generated' && t.texcoord === -1 && t.size === 128, `texel stats: ${JSON.stringify(t)}`);
      check(t?.unwrap?.attempts >= 1 && t.unwrap.margin > 0 && t.unwrap.seconds > 0, `unwrap stats: ${JSON.stringify(t?.unwrap)}`);
      check(t?.sampled > 1000 && t.charts >= 1, `texel stats: ${JSON.stringify(t)}`);
      // The seams split vertices: more than the bowl's 8 x 16 + 1.
      check(stats.vertices > 129, `vertices ${stats.vertices}`);
    }
    const info = json(expectExit(['info', out, '--json'], 0));
    check(JSON.stringify(info?.atlases?.map((a) => [a.width, a.height])) === '[[128,128]]', `atlases: ${JSON.stringify(info?.atlases)}`);
    const s = json(expectExit(['shade', out, '--texels', '--light', 'constant', '--pass', 'shadowed', '--json'], 0));
    check(s?.texels?.length === stats?.texels?.sampled && s.texels.every((x) => x.radiance.every((v) => v >= 0 && v <= 1)),
          `shade --texels: ${s?.texels?.length} texels`);
  },

  async texel_unwrap_errors() {
    // Without a working Blender the bake fails with the reason and writes nothing; no Blender
    // starts here: the failing ones are a missing path, /bin/false and a script that hangs.
    const scene = work('bowl.gltf');
    fs.writeFileSync(scene, bowlGltf({ rings: 4, slices: 8 }));
    const out = work('x.prt');
    const base = [scene, '-o', out, ...quick, '--texels', '--texture-size', '64'];
    expectExit([...base, '--blender', '/nonexistent/blender'], EXIT_NOT_FOUND,
               /Blender not found \(cannot run '\/nonexistent\/blender': No such file or directory\).*apt-get install --no-install-recommends blender/);
    expectExit([...base, '--blender', '/bin/false'], EXIT_UNAVAILABLE, /Blender \(\/bin\/false\) failed .*exited with status 1/);
    const tmp = work('tmp');
    fs.mkdirSync(tmp);
    const hang = work('hanging-blender');
    fs.writeFileSync(hang, `#!/bin/sh\necho $$ > ${work('hang.pid')}\nexec sleep 60\n`, { mode: 0o755 });
    const r = run([...base, '--blender', hang, '--unwrap-timeout', '0.5'], { ...process.env, TMPDIR: tmp });
    check(r.code === EXIT_RESOURCE && /ran past the time limit of 0\.5 s/.test(r.stderr), `timeout: ${r.code} ${r.stderr}`);
    check(fs.readdirSync(tmp).length === 0, `scratch left after the timeout: ${fs.readdirSync(tmp).join(', ')}`);
    check(!fs.existsSync(out), 'a failed unwrap wrote an asset');
    // SIGTERM while Blender runs: the hanging "Blender" is killed, the scratch directory removed,
    // and the baker dies of the signal.
    fs.rmSync(work('hang.pid'), { force: true });
    const child = spawn(bake, [...base, '--blender', hang], { env: { ...process.env, TMPDIR: tmp } });
    const exited = new Promise((resolve) => child.on('exit', (c, sig) => resolve(sig || c)));
    let pid = 0;
    for (let i = 0; i < 200 && !pid; i++) {
      await new Promise((r2) => setTimeout(r2, 50));
      if (fs.existsSync(work('hang.pid'))) pid = Number(fs.readFileSync(work('hang.pid'), 'utf8')) || 0;
    }
    if (!check(pid > 0, 'the hanging Blender never started')) {
      child.kill('SIGKILL');
      return;
    }
    check(fs.readdirSync(tmp).some((f) => f.startsWith('prt-unwrap-')), `no scratch directory while Blender runs: ${fs.readdirSync(tmp)}`);
    child.kill('SIGTERM');
    const how = await exited;
    check(how === 'SIGTERM', `the baker should die of SIGTERM, got ${how}`);
    check(fs.readdirSync(tmp).length === 0, `scratch left after SIGTERM: ${fs.readdirSync(tmp).join(', ')}`);
    // Dead or a zombie (an init that does not reap, as in some containers, leaves one).
    const running = () => {
      try {
        return !/^\d+ \(.*\) Z/.test(fs.readFileSync(`/proc/${pid}/stat`, 'utf8'));
      } catch {
        return false;
      }
    };
    let alive = true;
    for (let i = 0; i < 40 && (alive = running()); i++) await new Promise((r2) => setTimeout(r2, 50));
    check(!alive, `the Blender child ${pid} outlived the baker`);
    check(!fs.existsSync(out), 'an interrupted unwrap wrote an asset');
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
