// Transfer textures in the client's wasm core under Node (web/src/texel_texture.h, shared/prt/half_float.h):
// a texel pass baked by the native baker, decoded as the streaming client decodes it, must pack
// into the RGBA16F layers at exactly the positions docs/web-client.md "Transfer textures" gives,
// every value the correctly rounded half of the float pass (checked against an independent
// reference rounding here), zero padding, prefixes of bands as order-b passes, and device limits
// refused with messages naming both numbers. Also: the per-fragment shader's tone mapping is
// shade.frag's, and texel-only assets (for the browser test) decode with texel passes only.
// TPFL glossy (the bake carries a visibility pass): texel_prt.frag's glossy arithmetic run on
// the CPU from the packed textures (tpflGlossyCpu) equals prt::tpflGlossyExitRadiance on the
// same texels, and prt-bake shade --texels --pass glossy; its SH, lobe and Schlick functions are
// glossy.vert's text. Texel normals decode into the RGBA16F textures the glossy term reads.
// Usage: node texel_core_node_test.mjs PRT_CORE_NODE_JS NATIVE_PRT_BAKE WORK_DIR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { stripeQuadGltf } from './floor_scene_gltf.mjs';

const [coreJs, prtBake, workDir] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const failures = [];
let checks = 0;
const check = (ok, message) => {
  checks++;
  if (!ok) failures.push(message);
  return ok;
};
for (const [what, p] of [['prt_core_node.js', coreJs], ['native prt-bake', prtBake]]) {
  if (!p || !fs.existsSync(p)) {
    console.error(`${what} not found at ${p}: build the native and wasm presets first`);
    process.exit(1);
  }
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
const core = await createRequire(import.meta.url)(path.resolve(coreJs))();

// The half's value from its bits, written independently of the C++ (sign, exponent, mantissa).
function halfValue(bits) {
  const sign = bits & 0x8000 ? -1 : 1, e = (bits >> 10) & 31, m = bits & 1023;
  if (e === 31) return m ? NaN : sign * Infinity;
  return sign * (e ? (1 + m / 1024) * 2 ** (e - 15) : m * 2 ** -24);
}
// The half nearest float32 value f, ties to even, by arithmetic on the value (not its bits).
function nearestHalf(f) {
  if (Number.isNaN(f)) return NaN;
  const a = Math.abs(f);
  if (a === 0) return f;
  if (a >= 65520) return Math.sign(f) * Infinity;
  let e = Math.floor(Math.log2(a));
  if (2 ** e > a) e--;
  if (2 ** (e + 1) <= a) e++;
  const ulp = 2 ** (Math.max(e, -14) - 10);  // below 2^-14 the spacing stays 2^-24 (subnormals)
  const q = a / ulp;
  let r = Math.floor(q);
  const rest = q - r;
  if (rest > 0.5 || (rest === 0.5 && r % 2 === 1)) r++;
  return Math.sign(f) * r * ulp;
}
const same = (a, b) => (Number.isNaN(a) && Number.isNaN(b)) || a === b;

// ---- floatToHalf / halfToFloat on the cases that break converters ----
{
  const f = Math.fround;
  const cases = [0, 1, -1, 0.1, 65504, f(65519.99), 65520, 1e6, -1e6, 2 ** -14, 2 ** -24, 2 ** -25, 1.5 * 2 ** -25, 2 ** -26,
    f(2 ** -14 - 2 ** -25), 1 + 2 ** -11, 1 + 3 * 2 ** -11, 1 + 2 ** -11 + 2 ** -20, 3 * 2 ** -25, 1 / 3, -2.5e-6, NaN].map(f);
  const halves = core.floatsToHalves(cases);
  const back = core.halvesToFloats(Array.from(halves));
  cases.forEach((x, i) => {
    check(same(halfValue(halves[i]), nearestHalf(x)), `floatToHalf(${x}) = 0x${halves[i].toString(16)} (${halfValue(halves[i])}), nearest half ${nearestHalf(x)}`);
    check(same(back[i], halfValue(halves[i])), `halfToFloat(0x${halves[i].toString(16)}) = ${back[i]}, expected ${halfValue(halves[i])}`);
  });
  check(halves[1] === 0x3c00 && halves[4] === 0x7bff && halves[6] === 0x7c00 && halves[10] === 0x0001 && halves[11] === 0,
    `landmark bits: 1 -> ${halves[1].toString(16)}, 65504 -> ${halves[4].toString(16)}, 65520 -> ${halves[6].toString(16)}, 2^-24 -> ${halves[10]}, 2^-25 -> ${halves[11]}`);
  // Every half bit pattern survives halfToFloat -> floatToHalf.
  const all = Array.from({ length: 65536 }, (_, i) => i).filter((b) => (b & 0x7c00) !== 0x7c00 || (b & 0x3ff) === 0);
  const again = core.floatsToHalves(Array.from(core.halvesToFloats(all)));
  check(all.every((b, i) => again[i] === b), 'some half does not round-trip through float');
}

// ---- packing a baked texel pass ----
// The default room at 512 texels a side; order 3 (9 coefficients: 3 layers per channel, 3 padding lanes); q16 so
// that the passes are encoded and decode band by band like a streamed one.
const asset = path.join(workDir, 'room-texel.prt');
execFileSync(prtBake, ['--default', '--texels', '--texture-size', '512', '--samples', '16', '--bounces', '1', '--order', '3',
  '--passes', 'shadowed,interreflected', '--texel-glossy', '--compress', 'q16', '-o', asset, '--quiet']);
const bytes = fs.readFileSync(asset);
const info = core.inspectAsset(bytes);
check(info.ok && info.passes.filter((p) => p.domain === 'texel').length === 3, `the bake has no texel passes (2 and a visibility pass): ${JSON.stringify(info)}`);

for (const kind of ['shadowed', 'interreflected']) {
  for (const bands of [0, 2]) {
    const what = `${kind} at ${bands || 'all'} bands`;
    const r = core.texelPackCheck(bytes, kind, bands, 16384, 2048);
    if (!check(typeof r === 'object', `${what}: ${r}`)) continue;
    const order = bands || 3, n2 = order * order, channels = kind === 'shadowed' ? 1 : 3, perChannel = Math.ceil(n2 / 4);
    check(r.order === order && r.channels === channels && r.layersPerChannel === perChannel && r.atlases.length === 1,
      `${what}: order ${r.order}, ${r.channels} channels, ${r.layersPerChannel} layers per channel, ${r.atlases.length} atlases`);
    const a = r.atlases[0], texels = a.width * a.height;
    check(a.width === 512 && a.height === 512 && a.layers === channels * perChannel && a.halves.length === texels * a.layers * 4,
      `${what}: atlas ${a.width}x${a.height}, ${a.layers} layers, ${a.halves.length} halves`);
    check(r.floats.length === texels * channels * n2, `${what}: ${r.floats.length} floats for ${texels} texels`);
    let wrongRounding = 0, padding = 0, worstRelative = 0, nonZero = 0, first = '';
    for (let t = 0; t < texels; t++) {
      for (let c = 0; c < channels; c++) {
        for (let i = 0; i < 4 * perChannel; i++) {
          // Texel t = y * width + x of the pass is texel (x, y) of every layer: layer c * perChannel + i / 4, lane i % 4.
          const h = a.halves[((c * perChannel + Math.floor(i / 4)) * texels + t) * 4 + (i % 4)];
          if (i >= n2) {
            if (h !== 0) padding++;
            continue;
          }
          const f = r.floats[(t * channels + c) * n2 + i], v = halfValue(h);
          if (f !== 0) nonZero++;
          if (!same(v, nearestHalf(f))) {
            if (!wrongRounding) first = `texel ${t} channel ${c} coefficient ${i}: ${f} packed as ${v}, nearest half ${nearestHalf(f)}`;
            wrongRounding++;
          }
          if (Math.abs(f) >= 2 ** -14) worstRelative = Math.max(worstRelative, Math.abs(v - f) / Math.abs(f));
        }
      }
    }
    check(wrongRounding === 0, `${what}: ${wrongRounding} values not the nearest half (${first})`);
    check(padding === 0, `${what}: ${padding} padding lanes not zero`);
    check(worstRelative <= 2 ** -11, `${what}: worst relative half error ${worstRelative} > 2^-11`);
    check(nonZero > texels / 4, `${what}: only ${nonZero} non-zero coefficients: the comparison proves little`);
    if (bands === 0) console.log(`${kind}: ${texels} texels x ${channels} x ${n2} coefficients, worst relative half error ${worstRelative.toExponential(2)}`);
  }
}

// ---- device limits: clear errors naming both numbers ----
{
  const small = core.texelPackCheck(bytes, 'interreflected', 0, 256, 2048);
  check(typeof small === 'string' && /512x512/.test(small) && /MAX_TEXTURE_SIZE is 256/.test(small), `a 512 atlas on a 256 device: ${small}`);
  const layers = core.texelPackCheck(bytes, 'interreflected', 0, 16384, 8);
  check(typeof layers === 'string' && /needs 9 texture layers/.test(layers) && /MAX_ARRAY_TEXTURE_LAYERS is 8/.test(layers), `9 layers on an 8-layer device: ${layers}`);
  const absent = core.texelPackCheck(bytes, 'unshadowed', 0, 16384, 2048);
  check(typeof absent === 'string' && /no texel pass 'unshadowed'/.test(absent), `an absent pass: ${absent}`);
  const damaged = Buffer.from(bytes);
  damaged[damaged.length - 100] ^= 0x40;
  const bad = core.texelPackCheck(damaged, 'visibility', 0, 16384, 2048);  // the last section
  check(typeof bad === 'string' && /checksum/.test(bad), `a damaged texel pass: ${bad}`);
}

// ---- texel-only assets (browser_texel_test.mjs makes one to load) ----
{
  const only = core.texelOnlyAsset(bytes, 'room-texel-only');
  const i = typeof only === 'string' ? { ok: false, error: only } : core.inspectAsset(only);
  check(i.ok && i.name === 'room-texel-only' && i.passes.length === 3 && i.passes.every((p) => p.domain === 'texel'), `texel-only asset: ${JSON.stringify(i)}`);
  const vertexOnly = path.join(workDir, 'room-vertex.prt');
  execFileSync(prtBake, ['--default', '--samples', '16', '--order', '2', '-o', vertexOnly, '--quiet']);
  const refused = core.texelOnlyAsset(fs.readFileSync(vertexOnly), '');
  check(typeof refused === 'string' && /no texel pass/.test(refused), `texel-only from a vertex-only asset: ${refused}`);
}

// ---- the per-fragment shader tone-maps exactly as shade.frag ----
{
  const shaderText = (name) => fs.readFileSync(path.join(here, '../../web/shaders', name), 'utf8');
  const fn = (text, name) => (text.match(new RegExp(`vec3 ${name}\\(vec3 [a-z]+\\) \\{[^}]*\\}`)) || [null])[0];
  for (const name of ['acesFit', 'linearToSrgb']) {
    const a = fn(shaderText('shade.frag'), name), b = fn(shaderText('texel_prt.frag'), name);
    check(a !== null && a === b, `${name} differs between shade.frag and texel_prt.frag`);
  }
}

// ---- TPFL glossy: the shader's arithmetic on the packed textures against the CPU reference ----
// Texels, positions and normals from prt-bake shade --texels --pass glossy (every sampled texel;
// the glossy objects are the sphere and the torus, the rest is matte with k_s = 0). Two lightings:
// (a) order-3 coloured lighting with every coefficient set (a fixed pseudo-random draw), so
// every P_ik and every visibility layer and lane counts, against prt::tpflGlossyExitRadiance on
// the float visibility; (b) constant radiance 1 (L_0 = sqrt(4 pi)), against the native baker's
// own numbers. Tolerance 2e-3 of the peak: the RGBA16F visibility is the float one rounded to
// 11 bits (relative 4.9e-4 per coefficient), summed with both signs over 25 coefficients.
{
  const eye = [0.7, 1.6, 3.2];
  const shade = JSON.parse(execFileSync(prtBake, ['shade', asset, '--texels', '--light', 'constant', '--pass', 'glossy', '--view', eye.join(','),
    '--glossy-only', '--json'], { encoding: 'utf8', maxBuffer: 1 << 30 }));
  // Every 7th glossy texel and every 97th matte one: enough to cover both objects, quick.
  const picked = shade.texels.filter((t, k) => (t.radiance.some((r) => r !== 0) ? k % 7 === 0 : k % 97 === 0));
  const glossyCount = picked.filter((t) => t.radiance.some((r) => r !== 0)).length;
  check(glossyCount > 500, `only ${glossyCount} glossy texels picked: the comparison proves little`);
  const flat = picked.flatMap((t) => [0, t.x, t.y, ...t.position, ...t.normal]);
  let seed = 12345;
  const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648) * 2 - 1;
  const coloured = Array.from({ length: 27 }, (_, k) => (k < 3 ? 3 + k * 0.5 : 0.8 * random()));
  const constant = [Math.sqrt(4 * Math.PI), Math.sqrt(4 * Math.PI), Math.sqrt(4 * Math.PI), ...new Array(24).fill(0)];
  for (const [what, lighting, against] of [['coloured lighting', coloured, 'tpflGlossyExitRadiance'], ['constant radiance 1', constant, 'prt-bake shade']]) {
    const r = core.tpflTexelCheck(bytes, flat, eye, lighting, 3);
    if (!check(typeof r === 'object', `TPFL ${what}: ${r}`)) continue;
    check(r.visibilityOrder === 5 && r.transferOrder === 5 && r.layers === 7 && r.rowTexels === 7,
      `TPFL ${what}: visibility order ${r.visibilityOrder}, transfer order ${r.transferOrder}, ${r.layers} layers, ${r.rowTexels} texels a row (want 5, 5, 7, 7)`);
    const want = against === 'prt-bake shade' ? picked.flatMap((t) => t.radiance) : Array.from(r.reference);
    let peak = 0, worst = 0, at = '', matteNonZero = 0;
    for (const x of want) peak = Math.max(peak, Math.abs(x));
    for (let k = 0; k < picked.length; k++) {
      for (let c = 0; c < 3; c++) {
        const e = Math.abs(r.gpu[3 * k + c] - want[3 * k + c]);
        if (e > worst) { worst = e; at = `texel (${picked[k].x}, ${picked[k].y}) channel ${c}: shader ${r.gpu[3 * k + c]}, ${against} ${want[3 * k + c]}`; }
        if (want[3 * k + c] === 0 && r.gpu[3 * k + c] !== 0) matteNonZero++;
      }
    }
    console.log(`TPFL ${what}: ${picked.length} texels (${glossyCount} glossy), shader emulation vs ${against}: worst ${(worst / peak).toExponential(2)} of the peak ${peak.toFixed(4)}`);
    check(peak > 0.01, `TPFL ${what}: the reference is dark (peak ${peak})`);
    check(worst <= 2e-3 * peak, `TPFL ${what}: worst difference ${(worst / peak).toExponential(2)} of the peak > 2e-3 (${at})`);
    check(matteNonZero === 0, `TPFL ${what}: ${matteNonZero} matte channel values not exactly 0`);
  }
}

// ---- the TPFL term takes Schlick's term with glossy.vert's own function ----
// (glossy.vert writes the SH and lobe recurrences out per band count, texel_prt.frag keeps
// their loop form; both are checked numerically against the same CPU code: above, and in
// glossy_core_node_test and the browser tests.)
{
  const shaderText = (name) => fs.readFileSync(path.join(here, '../../web/shaders', name), 'utf8');
  // A function's text from its signature to the closing brace at the start of a line.
  const fn = (text, signature) => {
    const i = text.indexOf(signature);
    return i < 0 ? null : text.slice(i, text.indexOf('\n}\n', i) + 3);
  };
  for (const signature of ['vec3 schlick(vec3 f0, float f90, float cosNormalView, bool on)']) {
    const a = fn(shaderText('glossy.vert'), signature), b = fn(shaderText('texel_prt.frag'), signature);
    check(a !== null && a === b, `${signature} differs between glossy.vert and texel_prt.frag`);
  }
}

// ---- texel normals (asset format 1.6) as the client uploads them ----
// A normal-mapped quad (stripes tilting the normal up to 31 degrees along x) baked with
// --texels: every covered texel's RGBA16F texel holds the unit normal the octahedral code
// decodes to (decoded here from docs/asset-format.md's formula, independently of the C++),
// each component the correctly rounded half of it within one float rounding, w = 1; empty
// texels hold 0 in all four lanes; a code count that disagrees with the atlases and an atlas
// over MAX_TEXTURE_SIZE are refused by name.
{
  const scene = path.join(workDir, 'stripes.gltf'), asset = path.join(workDir, 'stripes.prt');
  fs.writeFileSync(scene, stripeQuadGltf(32, true));
  execFileSync(prtBake, [scene, '-o', asset, '--texels', '--texture-size', '32', '--samples', '16', '--order', '2', '--passes', 'shadowed',
    '--texture-sets', 'scene', '--unwrap', 'never', '--quiet']);
  const bytes = fs.readFileSync(asset);
  const r = core.texelNormalsPackCheck(bytes, 16384, 0);
  if (check(typeof r === 'object', `texelNormalsPackCheck: ${r}`)) {
    const decode = (x, y) => {
      const u = Math.max(x / 32767, -1), v = Math.max(y / 32767, -1);
      let n = [u, v, 1 - Math.abs(u) - Math.abs(v)];
      if (n[2] < 0) n = [(1 - Math.abs(v)) * (u >= 0 ? 1 : -1), (1 - Math.abs(u)) * (v >= 0 ? 1 : -1), n[2]];
      const l = Math.hypot(...n);
      return n.map((c) => c / l);
    };
    const a = r.atlases[0];
    check(r.atlases.length === 1 && a.width === 32 && a.height === 32 && a.halves.length === 4 * 32 * 32, `texel normals texture ${a.width}x${a.height}`);
    let covered = 0, worst = 0, emptyBad = 0, wBad = 0, tilted = 0;
    for (let t = 0; t < 32 * 32; t++) {
      const lanes = [0, 1, 2, 3].map((k) => halfValue(a.halves[4 * t + k]));
      if (r.coverage[t] === 0) {
        if (lanes.some((x) => x !== 0)) emptyBad++;
        continue;
      }
      covered++;
      if (lanes[3] !== 1) wBad++;
      const n = decode(r.codes[2 * t], r.codes[2 * t + 1]);
      // float32 decoding then rounding to half: within half an ulp of the half plus a float's rounding.
      for (let k = 0; k < 3; k++) worst = Math.max(worst, Math.abs(lanes[k] - nearestHalf(n[k])) / Math.max(Math.abs(n[k]), 2 ** -14));
      if (Math.abs(n[0]) > 0.1) tilted++;
    }
    console.log(`texel normals: ${covered} covered texels (${tilted} tilted > 5.7 degrees), worst half lane ${worst.toExponential(2)} relative from the rounded decode`);
    check(covered === 32 * 32, `only ${covered} texels covered`);
    check(tilted > 0.5 * covered, `only ${tilted} texels carry the stripes' tilt`);
    check(worst <= 2 ** -10, `a normal lane differs from the correctly rounded half of its decode by ${worst} (relative)`);
    check(emptyBad === 0 && wBad === 0, `${emptyBad} empty texels not all 0, ${wBad} covered texels with w != 1`);
    const short = core.texelNormalsPackCheck(bytes, 16384, 2);
    check(typeof short === 'string' && /2046 codes and 1024 coverage values for 1024 texels/.test(short), `a short code list: ${short}`);
    const small = core.texelNormalsPackCheck(bytes, 16, 0);
    check(typeof small === 'string' && /atlas 0 is 32x32 texels; this device's MAX_TEXTURE_SIZE is 16/.test(small), `a small device: ${small}`);
  }
}

if (failures.length) {
  console.error(`${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`texel core: ${checks} checks passed`);
