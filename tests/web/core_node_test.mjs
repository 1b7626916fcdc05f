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

// CPCA rendering (web/src/cpca_texture.h): the per-cluster table and per-vertex weighted sum
// the shaders compute, emulated on the CPU from the packed textures, against the plain dot
// product with the expanded transfer, at the baked order and cut to fewer bands.
{
  const cpcaAsset = path.join(workDir, 'room-cpca.prt');
  execFileSync(prtBake, ['--default', '-o', cpcaAsset, '--samples', '64', '--order', '4', '--compress', 'cpca8@0.02', '--quiet']);
  const cpcaBytes = fs.readFileSync(cpcaAsset);
  // The packLighting layout (client_limits.h): kMaxClientOrder^2 coefficients per channel.
  const perChannel = core.kMaxClientOrder * core.kMaxClientOrder;
  check(core.kMaxClientOrder === 8 && core.kPackedLightingFloats === 3 * perChannel,
    `client limits: order ${core.kMaxClientOrder}, ${core.kPackedLightingFloats} packed floats`);
  for (const kind of ['shadowed', 'interreflected']) {
    for (const order of [4, 2]) {
      const lighting = new Array(core.kPackedLightingFloats).fill(0);
      for (let c = 0; c < 3; c++)
        for (let i = 0; i < order * order; i++) lighting[perChannel * c + i] = (i === 0 ? 3 : Math.sin(1.7 * i + c)) * (1 + 0.2 * c);
      const r = core.cpcaRadianceCheck(cpcaBytes, kind, lighting, order);
      if (!check(r && typeof r === 'object', `CPCA ${kind} order ${order}: ${r}`)) continue;
      check(r.clusters >= 1 && r.weights > 0, `CPCA ${kind}: ${r.clusters} clusters, ${r.weights} weights`);
      let peak = 0, worst = 0;
      for (let i = 0; i < r.expanded.length; i++) peak = Math.max(peak, Math.abs(r.expanded[i]));
      for (let i = 0; i < r.expanded.length; i++) worst = Math.max(worst, Math.abs(r.packed[i] - r.expanded[i]));
      check(r.packed.length === r.expanded.length && peak > 0.1, `CPCA ${kind} order ${order}: ${r.packed.length} values, peak ${peak}`);
      check(worst <= 2e-5 * peak, `CPCA ${kind} order ${order}: clusters-first radiance differs from the expanded transfer's by ${worst} (peak ${peak})`);
    }
  }
  const notCpca = core.cpcaRadianceCheck(bytes, 'shadowed', new Array(core.kPackedLightingFloats).fill(1), 4);
  check(typeof notCpca === 'string' && /not CPCA/.test(notCpca), `a float32 asset as CPCA: ${notCpca}`);
}

// SH: band 1 closed form, and a z rotation by 90 degrees turns +x into +y.
const y = core.evalBasis(3, 0.6, 0.0, 0.8);
check(Math.abs(y[3] - 0.488603 * 0.6) < 1e-6 && Math.abs(y[2] - 0.488603 * 0.8) < 1e-6, `basis: ${y.slice(0, 4)}`);
const lobe = [0, 0, 0, 1, 0, 0, 0, 0, 0];  // y_1,1 ~ x
const rotated = core.rotateCoefficients(3, lobe, [0, -1, 0, 1, 0, 0, 0, 0, 1]);
check(Math.abs(rotated[1] - 1) < 1e-6 && Math.abs(rotated[3]) < 1e-6, `rotation: ${rotated}`);
check(typeof core.rotateCoefficients(3, lobe, [2, 0, 0, 0, 1, 0, 0, 0, 1]) === 'string', 'a non-rotation must be rejected');

// ---- Dynamic lights (web/src/emitters.h, cube_faces.h) ----------------------------------
const light = (shape, extra = {}) => {
  const l = [shape, 1, 2, 3, 0.5, 0.25, 0, 0, 1, 1, 0.5, 0.25, 2, 0, 0, 0];
  for (const [k, v] of Object.entries(extra)) l[Number(k)] = v;
  return l;
};
{
  const ok = core.parseLights([...light(0), ...light(1, { 6: 0, 7: -2, 8: 0 }), ...light(2), ...light(3, { 13: 1 })], 2);
  check(ok.error === '' && ok.count === 4, `valid lights rejected: ${ok.error}`);
  if (ok.count === 4) {
    check(ok.emitters[0].radiance.join() === [2, 1, 0.5].join(), `radiance is colour x intensity: ${ok.emitters[0].radiance}`);
    check(ok.emitters[1].normal.join() === '0,-1,0', `disc normal not normalised: ${ok.emitters[1].normal}`);
  }
  // Bad input: the error names the light index and the field; nothing is accepted.
  const bad = [
    [[...light(0), ...light(0, { 4: 0 })], /light 1: sizeX must be > 0/],
    [light(2, { 5: -1 }), /light 0: sizeY must be > 0/],
    [light(0, { 2: NaN }), /light 0: py is not finite/],
    [light(0, { 12: Infinity }), /light 0: intensity is not finite/],
    [light(7), /light 0: shape must be/],
    [light(0.5), /light 0: shape must be/],
    [light(1, { 6: 0, 7: 0, 8: 0 }), /light 0: normal .* must be non-zero/],
    [light(0, { 10: -1 }), /light 0: g must be >= 0/],
    [light(3, { 13: 2 }), /light 0: meshId 2.* is not a mesh/],
    [light(0).slice(0, 15), /16 floats per light/],
  ];
  for (const [flat, pattern] of bad) {
    const r = core.parseLights(flat, 2);
    check(pattern.test(r.error) && r.count === 0, `bad lights ${JSON.stringify(flat)}: '${r.error}' does not match ${pattern}`);
  }
  // The disc/rect frame: orthonormal, right-handed around n, v = up projected on the plane.
  let worstFrame = 0, upOk = true;
  for (let k = 0; k < 200; k++) {
    const n = k < 4 ? [[0, 1, 0], [0, -1, 0], [0, 0.9999, 0.0141], [1, 0, 0]][k] : [Math.sin(k * 1.7), Math.cos(k * 2.3), Math.sin(k * 0.7 + 1)];
    const e = core.parseLights(light(2, { 6: n[0], 7: n[1], 8: n[2] }), 0).emitters[0];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const uxv = cross(e.u, e.v);
    worstFrame = Math.max(worstFrame, Math.abs(dot(e.u, e.u) - 1), Math.abs(dot(e.v, e.v) - 1), Math.abs(dot(e.u, e.v)),
      Math.abs(dot(e.u, e.normal)), ...uxv.map((x, i) => Math.abs(x - e.normal[i])));
    if (Math.abs(e.normal[1]) < 0.99 && e.v[1] < 0) upOk = false;
  }
  check(worstFrame < 1e-5, `emitter frame is not orthonormal around n (error ${worstFrame})`);
  check(upOk, 'rect v axis should be +y projected onto the plane');
}
{
  // Face projection: the GL cube-map table (sc, tc, ma), written out independently here.
  const table = [(d) => [-d[2], -d[1], d[0]], (d) => [d[2], -d[1], -d[0]], (d) => [d[0], d[2], d[1]],
    (d) => [d[0], -d[2], -d[1]], (d) => [d[0], -d[1], d[2]], (d) => [-d[0], -d[1], -d[2]]];
  const faceOf = (d) => {
    const a = d.map(Math.abs);
    if (a[0] >= a[1] && a[0] >= a[2]) return d[0] > 0 ? 0 : 1;
    if (a[1] >= a[2]) return d[1] > 0 ? 2 : 3;
    return d[2] > 0 ? 4 : 5;
  };
  const c = [0.3, -1, 2];
  let worst = 0, depthOrdered = true;
  for (let k = 0; k < 300; k++) {
    const d = [Math.sin(k * 12.9898) * 2, Math.cos(k * 78.233), Math.sin(k * 3.7 + 0.4) * 1.5];
    const f = faceOf(d);
    const [sc, tc, ma] = table[f](d);
    const near = core.cubeFaceProject(f, c, d.map((v, i) => c[i] + v));
    const far = core.cubeFaceProject(f, c, d.map((v, i) => c[i] + 3 * v));
    worst = Math.max(worst, Math.abs(near[0] - sc / ma), Math.abs(near[1] - tc / ma), Math.abs(far[0] - sc / ma));
    if (!(near[2] > -1 && near[2] < far[2] && far[2] < 1)) depthOrdered = false;
  }
  check(worst < 1e-5, `cube face projection differs from the GL table by ${worst}`);
  check(depthOrdered, 'cube face depth must grow with distance inside (-1, 1)');
  // Face culling is conservative: a sphere with any point on a face's side touches it.
  let missed = 0, culled = 0;
  for (let k = 0; k < 400; k++) {
    const centre = [Math.sin(k * 1.3) * 3, Math.cos(k * 2.1) * 3, Math.sin(k * 0.37) * 3];
    const radius = 0.05 + 1.5 * Math.abs(Math.sin(k * 5.1));
    for (let f = 0; f < 6; f++) {
      const touches = core.sphereTouchesCubeFace(f, [0, 0, 0], centre, radius);
      if (!touches) culled++;
      for (let s = 0; s < 300 && !touches; s++) {
        const u = [Math.sin(s * 1.1 + k), Math.cos(s * 2.7 + k), Math.sin(s * 0.9 + 2 * k)];
        const r = radius * Math.cbrt(Math.abs(Math.sin(s * 7.7))) / Math.hypot(...u);
        const p = centre.map((v, i) => v + r * u[i]);
        if (faceOf(p) === f) { missed++; break; }
      }
    }
  }
  check(missed === 0, `${missed} spheres were culled from a face they reach`);
  // The texel rectangle the GPU projection reads holds every texel a sphere covers, and
  // is not much larger for a small sphere.
  let outside = 0, loose = 0;
  const faceSize = 64;
  for (let k = 0; k < 150; k++) {
    const centre = [Math.sin(k * 1.9) * 3, Math.cos(k * 0.7) * 3, Math.sin(k * 2.3 + 1) * 3];
    const radius = k % 3 === 0 ? 0.05 : 0.2 + Math.abs(Math.sin(k * 4.1));
    const rects = [0, 1, 2, 3, 4, 5].map((f) => core.sphereFaceRect(f, [0, 0, 0], centre, radius, faceSize));
    for (let s = 0; s < 400; s++) {
      const u = [Math.sin(s * 1.7 + k), Math.cos(s * 3.1 + k), Math.sin(s * 0.3 + 3 * k)];
      const r = radius * Math.cbrt(Math.abs(Math.sin(s * 5.3))) / Math.hypot(...u);
      const p = centre.map((v, i) => v + r * u[i]);
      const f = faceOf(p);
      const [sc, tc, ma] = table[f](p);
      const i = Math.min(faceSize - 1, Math.floor((sc / ma + 1) / 2 * faceSize));
      const j = Math.min(faceSize - 1, Math.floor((tc / ma + 1) / 2 * faceSize));
      const [x0, y0, x1, y1] = rects[f];
      if (i < x0 || i > x1 || j < y0 || j > y1) outside++;
    }
    if (radius === 0.05) {  // about 1 degree seen from 3 units: a few texels plus the margin
      const area = rects.reduce((a, [x0, y0, x1, y1]) => a + Math.max(0, x1 - x0 + 1) * Math.max(0, y1 - y0 + 1), 0);
      if (area > 8 * 8) loose++;
    }
  }
  check(outside === 0, `${outside} sphere points fell outside the face rectangles`);
  check(loose === 0, `${loose} small spheres got loose face rectangles`);
  check(culled > 400, `face culling culls too little to be useful (${culled} of 2400)`);
  // RGBE8 atlas: value = byte / 255 * 2^(alpha - 128); face f at ((f % 3) size, (f / 3) size).
  const size = 2;
  const bytes = new Uint8Array(3 * size * 2 * size * 4);
  const at = (x, y) => 4 * (y * 3 * size + x);
  bytes.set([255, 51, 0, 130], at(size + 1, size + 0));  // face 4 (+Z), texel (1, 0)
  bytes.set([128, 0, 255, 120], at(0, 1));               // face 0 (+X), texel (0, 1)
  const faces = core.decodeRgbeAtlas(size, bytes);
  const texel = (f, i, j) => faces[f].slice(3 * (j * size + i), 3 * (j * size + i) + 3);
  const near = (a, b) => a.every((v, i) => Math.abs(v - b[i]) <= 1e-6 * Math.max(1, Math.abs(b[i])));
  check(near(texel(4, 1, 0), [4, 0.8, 0]), `RGBE decode of face 4: ${texel(4, 1, 0)}`);
  check(near(texel(0, 0, 1), [128 / 255 / 256, 0, 1 / 256]), `RGBE decode of face 0: ${texel(0, 0, 1)}`);
  check(faces.every((f, k) => f.reduce((a, v) => a + v, 0) > 0 === (k === 0 || k === 4)), 'RGBE atlas decoded into the wrong faces');
  check(typeof core.decodeRgbeAtlas(size, bytes.subarray(1)) === 'string', 'a short RGBE atlas must be rejected');
}
{
  // The analytic circular light: band 0 is radiance x cap solid angle x y_00.
  const zeta = 0.3, radiance = 2.5;
  const sh = core.circularLightSH(5, zeta, radiance, 0, 0, 1);
  const l0 = radiance * 2 * Math.PI * (1 - Math.cos(zeta)) * 0.5 / Math.sqrt(Math.PI);
  check(Math.abs(sh[0] - l0) < 1e-5 * l0, `circular light L0 ${sh[0]}, expected ${l0}`);
  check(Math.abs(sh[1]) < 1e-6 && Math.abs(sh[3]) < 1e-6 && sh[2] > 0, `a cap about +z has only m = 0 terms: ${sh.slice(0, 4)}`);
  const whole = core.circularLightSH(3, Math.PI, 1, 0, 1, 0);
  check(Math.abs(whole[0] - 2 * Math.sqrt(Math.PI)) < 1e-5 && whole.slice(1).every((v) => Math.abs(v) < 1e-5), `a full-sphere cap is constant: ${whole}`);
}

// Glossy rendering from a real glossy bake (web/src/glossy_texture.h): the glossy shaders'
// arithmetic emulated from the packed CPCA matrix textures, and glossyExitRadiance on the
// codec's cpcaMatrixReconstruct, against glossyExitRadiance on the pass's full decode; and the
// wasm reference under constant light against native `prt-bake shade --glossy-only`.
{
  const glossyAsset = path.join(workDir, 'room-glossy.prt');
  execFileSync(prtBake, ['--default', '--glossy', '-o', glossyAsset, '--samples', '32', '--order', '3', '--compress', 'cpca8', '--quiet']);
  const glossyBytes = fs.readFileSync(glossyAsset);
  const eye = [0.5, 1.2, 3];
  for (const kind of ['shadowed', 'interreflected']) {
    const lighting = [];
    for (let i = 0; i < 9; i++) lighting.push(i === 0 ? 3 : Math.sin(1.3 * i), i === 0 ? 2.5 : Math.cos(0.7 * i), i === 0 ? 2 : 0.3);
    const r = core.glossyAssetCheck(glossyBytes, kind, lighting, eye, true);
    if (!check(r && typeof r === 'object' && r.emulated, `glossy ${kind}: ${r}`)) continue;
    let peak = 0, emulated = 0, reconstructed = 0;
    for (let i = 0; i < r.reference.length; i++) peak = Math.max(peak, Math.abs(r.reference[i]));
    for (let i = 0; i < r.reference.length; i++) {
      emulated = Math.max(emulated, Math.abs(r.emulated[i] - r.reference[i]));
      reconstructed = Math.max(reconstructed, Math.abs(r.reconstructed[i] - r.reference[i]));
    }
    check(peak > 1e-3, `glossy ${kind}: the reference glossy radiance peaks at ${peak}`);
    check(emulated <= 1e-4 * peak, `glossy ${kind}: emulated shaders differ from the reference by ${emulated / peak} of the peak (allowed 1e-4)`);
    check(reconstructed === 0, `glossy ${kind}: cpcaMatrixReconstruct's radiance differs from the full decode's by ${reconstructed}`);
    check(r.expansionsAgree, `glossy ${kind}: the client's expansion differs from cpcaMatrixReconstruct`);
    // Constant radiance 1: L_00 = 2 sqrt(pi), as prt-bake shade --light constant.
    const l0 = 2 * Math.sqrt(Math.PI);
    const constant = core.glossyAssetCheck(glossyBytes, kind, [l0, l0, l0], eye, true);
    const native = JSON.parse(execFileSync(prtBake, ['shade', glossyAsset, '--light', 'constant', '--pass', `glossy-${kind}`, '--view', eye.join(','),
      '--glossy-only', '--order', '1', '--json'], { encoding: 'utf8', maxBuffer: 256 << 20 })).vertices;
    if (!check(typeof constant === 'object' && constant.reference.length === 3 * native.length, `glossy ${kind} constant: ${constant}`)) continue;
    let worst = 0;
    for (let v = 0; v < native.length; v++)
      for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(constant.reference[3 * v + c] - native[v].radiance[c]) / Math.max(1e-3, Math.abs(native[v].radiance[c])));
    check(worst < 1e-5, `glossy ${kind}: wasm and native glossy radiance under constant light differ by ${worst} (relative)`);
  }
}

// The analytic light path (web/src/analytic_lights.h) under Node: a sphere is the circular
// light of half-angle asin(a/d); a rect seen from behind gives zero; radiance scales it.
{
  const order = 5, a = 0.3, d = 1.5, dir = [0.48, 0.6, -0.64];
  const n = Math.hypot(...dir), u = dir.map((x) => x / n);
  const c = [0.1, 0.2, 0.3];
  const sphere = [0, c[0] + d * u[0], c[1] + d * u[1], c[2] + d * u[2], a, a, 0, 0, 1, 1, 0.5, 0.25, 2, 0, 0, 0];
  const sh = core.analyticLightSH(sphere, c, order);
  const cap = core.circularLightSH(order, Math.asin(a / d), 1, ...u);
  if (check(Array.isArray(sh) && sh.length === 3 * order * order && Array.isArray(cap), `analyticLightSH sphere: ${sh}, circularLightSH: ${cap}`)) {
    let worst = 0;
    for (let i = 0; i < order * order; i++)
      for (let ch = 0; ch < 3; ch++) worst = Math.max(worst, Math.abs(sh[3 * i + ch] - [2, 1, 0.5][ch] * cap[i]));
    check(worst < 1e-6 * Math.abs(2 * cap[0]), `analytic sphere differs from the circular light by ${worst}`);
  }
  const rectFacingAway = [2, 0, 0, 2, 0.5, 0.4, 0, 0, 1, 1, 1, 1, 3, 0, 0, 0];  // at z = 2 emitting toward +z, seen from 0
  const back = core.analyticLightSH(rectFacingAway, [0, 0, 0], order);
  check(Array.isArray(back) && back.every((x) => x === 0), `a rect seen from behind should give zero, got ${back && back.slice(0, 3)}`);
  const rectFacing = [2, 0, 0, 2, 0.5, 0.4, 0, 0, -1, 1, 1, 1, 3, 0, 0, 0];
  const front = core.analyticLightSH(rectFacing, [0, 0, 0], order);
  // On axis: L_0 = 3 x solid angle / (2 sqrt(pi)), solid angle 4 asin(ab / sqrt((a^2+d^2)(b^2+d^2))).
  const omega = 4 * Math.asin((0.25 * 0.2) / Math.sqrt((0.25 ** 2 + 4) * (0.2 ** 2 + 4)));
  check(Array.isArray(front) && Math.abs(front[0] - (3 * omega) / (2 * Math.sqrt(Math.PI))) < 1e-6, `rect on axis L_0 ${front && front[0]}`);
  const bad = core.analyticLightSH([0, 0, 0, 0, -1, 1, 0, 0, 1, 1, 1, 1, 1, 0, 0, 0], c, order);
  check(typeof bad === 'string' && bad.includes('sizeX'), `a bad light should be refused with a message naming the field: ${bad}`);
}

if (failures.length) {
  console.error(`${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`wasm client core: ${checks} checks passed`);
