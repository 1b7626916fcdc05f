// Transfer textures (per-texel PRT) in the page, headless Chromium (SwiftShader) against a real
// prt-serve: the default room baked with --texels, streamed in parts. The fragment shader's
// radiance read back in UV space must equal the baker's per-texel radiance (prt-bake shade
// --texels) at the sampled texel centres; the picture in texel mode must be lit, differ from
// vertex mode at the contact shadows and switch back to the same vertex picture; an asset with
// texel passes only must render (and equal the full asset's texel picture). TPFL glossy: the
// visibility pass streams in bands, the GPU's per-fragment glossy term equals prt-bake shade
// --texels --pass glossy at the sampled texels, and an orbit changes the glossy objects' texels
// and pixels while the matte floor's stay; on a normal-mapped glossy quad the GPU's glossy term
// reflects about the asset's texel normals as prt-bake shade does.
// Usage: node browser_texel_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR PRT_CORE_NODE_JS ENV_EXR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { makeChecks, startServer, openPage, capture, luminance, windowLuminance, runCase, maxChannelDifference } from './browser_harness.mjs';
import { stripeQuadGltf } from './floor_scene_gltf.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, coreJs, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
for (const [what, p] of [['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['prt_core_node.js', coreJs], ['environment map', envExr]]) {
  if (!p || !fs.existsSync(p)) {
    console.error(`${what} not found at ${p} (build the native and wasm presets)`);
    process.exit(1);
  }
}

// ---- fixture: the default room with texel passes at 512 texels a side, order 3, one bounce, q16 so the texel passes stream band by band. About
// 10 s on the 2-core machine.
const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });
const asset = path.join(root, 'room-texel.prt');
const bakeStart = Date.now();
// With a TPFL visibility pass (asset format 1.5, order 2n - 1 = 5), the texel passes' glossy term.
execFileSync(prtBake, ['--default', '--texels', '--texture-size', '512', '--samples', '64', '--bounces', '1', '--order', '3',
  '--passes', 'shadowed,interreflected', '--texel-glossy', '--compress', 'q16', '--name', 'room-texel', '-o', asset, '--quiet']);
console.log(`bake: ${((Date.now() - bakeStart) / 1000).toFixed(1)} s, ${(fs.statSync(asset).size / 1e6).toFixed(1)} MB`);
fs.copyFileSync(envExr, path.join(root, 'forest.exr'));

// The page's constant lighting: the white furnace (radiance 1), environment on, no lights.
const FURNACE = '?env=white%20furnace';
const waitAll = (page) => page.waitForFunction(() => window.prtApp.error || (window.prtApp.ready && window.prtApp.bytesReceived === window.prtApp.bytesTotal),
  null, { timeout: 90000 });

// Atlas `atlas` of texel pass `pass` read back in UV space, as {width, height, rgba: Float32Array}
// (sent base64: a million floats as JSON would be slow).
// positions = true: the fragments' world positions instead.
async function readAtlas(page, pass, atlas = 0, positions = false) {
  const r = await page.evaluate(([p, a, w]) => {
    const { width, height, data } = window.prtApp.texelAtlasRadiance(p, a, w);
    const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
    let s = '';
    for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return { width, height, b64: btoa(s) };
  }, [pass, atlas, positions]);
  const buf = Buffer.from(r.b64, 'base64');
  return { width: r.width, height: r.height, rgba: new Float32Array(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.length)) };
}

// Fraction of pixels clearly brighter than the clear colour, and the mean luminance.
function litStats(img) {
  let lit = 0, sum = 0;
  for (let y = 0; y < img.height; y++)
    for (let x = 0; x < img.width; x++) {
      const l = luminance(img, x, y);
      sum += l;
      if (l > 40) lit++;
    }
  return { litFraction: lit / (img.width * img.height), mean: sum / (img.width * img.height) };
}

// prt-bake shade's TPFL glossy term alone at every sampled texel of `assetPath` under the forest
// map from `eye` (it reflects about the asset's texel normals when it has them).
function glossyReference(assetPath, eye) {
  return JSON.parse(execFileSync(prtBake, ['shade', assetPath, '--texels', '--light', envExr, '--pass', 'glossy', '--glossy-only',
    '--view', eye.join(','), '--json'], { encoding: 'utf8', maxBuffer: 1 << 30 }));
}

// The page's shadowed glossy term read back in UV space (atlas 0) against `reference`
// (glossyReference) at every texel a triangle covers. Tolerance per channel value: 3e-3 of the
// peak + 3e-3 of the value + 2 g dp, with dp the distance between the fragment's shading point
// (read back) and the baker's sample, and g the largest slope |dL| / |dp| to the four
// neighbouring texels of `slopeFrom` (default the reference itself). Matte texels (k_s = 0)
// must be exactly 0. `against` (optional, texels as the reference's) replaces the GPU values,
// so the same measure can be applied to another CPU answer.
async function compareGlossy(page, reference, { slopeFrom = reference, against = null } = {}) {
  const gpu = await readAtlas(page, 'shadowed');
  const at = await readAtlas(page, 'shadowed', 0, true);
  let peak = 0;
  for (const t of reference.texels) peak = Math.max(peak, ...t.radiance);
  let compared = 0, glossy = 0, sloped = 0, worstDp = 0, worstRelative = 0, worstAbsolute = 0, bad = 0, firstBad = '';
  const slopeTexels = new Map(slopeFrom.texels.map((t) => [t.y * gpu.width + t.x, t]));
  const alternative = against && new Map(against.texels.map((t) => [t.y * gpu.width + t.x, t]));
  for (const t of reference.texels) {
    const i = 4 * (t.y * gpu.width + t.x);
    if (gpu.rgba[i + 3] !== 1) continue;
    const dp = Math.hypot(at.rgba[i] - t.position[0], at.rgba[i + 1] - t.position[1], at.rgba[i + 2] - t.position[2]);
    worstDp = Math.max(worstDp, dp);
    compared++;
    if (t.radiance.some((r) => r !== 0)) glossy++;
    const own = slopeTexels.get(t.y * gpu.width + t.x);
    for (let c = 0; c < 3; c++) {
      const want = t.radiance[c], got = alternative ? alternative.get(t.y * gpu.width + t.x).radiance[c] : gpu.rgba[i + c];
      const error = Math.abs(got - want);
      worstAbsolute = Math.max(worstAbsolute, error / peak);
      if (Math.abs(want) > 0.01 * peak) worstRelative = Math.max(worstRelative, error / Math.abs(want));
      const base = 3e-3 * Math.abs(want) + 3e-3 * peak;
      let slope = 0;
      for (const [dx, dy] of [[1, 0], [-1, 0], [0, 1], [0, -1]]) {
        const n = slopeTexels.get((t.y + dy) * gpu.width + t.x + dx);
        const d = n && own && Math.hypot(n.position[0] - own.position[0], n.position[1] - own.position[1], n.position[2] - own.position[2]);
        if (d > 0) slope = Math.max(slope, Math.abs(n.radiance[c] - own.radiance[c]) / d);
      }
      if (error > base) sloped++;
      // k_s = 0 (the matte room and boxes): exactly 0, whatever the visibility holds.
      if (!(want === 0 ? got === 0 : error <= base + 2 * slope * dp)) {
        if (!bad) firstBad = `texel (${t.x}, ${t.y}) channel ${c}: GPU ${got}, baker ${want}, shading point ${dp.toExponential(2)} from the sample, slope ${slope.toFixed(3)}`;
        bad++;
      }
    }
  }
  return { compared, glossy, sloped, worstDp, worstRelative, worstAbsolute, bad, firstBad, peak };
}
const cases = {
  // (a) The GPU's per-fragment radiance at texel centres against the CPU reference, for the
  // interreflected (RGB) and the shadowed (scalar x albedo) pass under constant radiance 1.
  // Tolerance: the RGBA16F coefficients are the float ones rounded to 11 significant bits
  // (relative error <= 2^-11 = 4.9e-4; constant light reads coefficient 0 alone, so the
  // radiance inherits that bound), plus float32 arithmetic and texel-centre interpolation:
  // 1e-3 of the texel's own radiance, and 1e-4 of the atlas's peak for texels near black.
  async texel_atlas_matches_baker(browser) {
    const server = await startServer(prtServe, root, webDist);
    try {
      const entry = (await (await fetch(`${server.base}/api/scenes`)).json()).scenes.find((e) => e.name === 'room-texel');
      const texelBands = (entry?.parts ?? []).filter((p) => p.domain === 'texel' && p.kind === 'transfer-band');
      const texelBandParts = texelBands.filter((p) => p.form !== 'visibility').length;
      const visibilityBandParts = texelBands.filter((p) => p.form === 'visibility').length;
      check(texelBandParts === 6, `the catalogue lists ${texelBandParts} texel band parts, not 2 passes x 3 bands: the texel passes would not stream band by band`);
      check(visibilityBandParts === 5, `the catalogue lists ${visibilityBandParts} visibility band parts, not 2 x 3 - 1`);
      const visibilityBytes = (entry?.parts ?? []).filter((p) => p.form === 'visibility').reduce((s, p) => s + p.size, 0);
      const { page, consoleErrors } = await openPage(browser, `${server.base}/${FURNACE}&source=texel`, { waitReady: false });
      await waitAll(page);
      const state = await page.evaluate(() => ({ error: window.prtApp.error, source: window.prtApp.source, texelBands: window.prtApp.texelBands,
        atlases: window.prtApp.atlases, environment: window.prtApp.environment, lights: window.prtApp.lights.length }));
      check(state.error === null, `page error: ${state.error}`);
      check(state.source === 'texel', `source is ${state.source}, not texel`);
      check(JSON.stringify(state.texelBands) === '[0,3,3]', `texel bands ${JSON.stringify(state.texelBands)} (want [0, 3, 3]: no unshadowed pass, order 3)`);
      check(state.environment === 'white furnace' && state.lights === 0, `lighting: ${state.environment}, ${state.lights} lights`);
      // The visibility pass streams with the rest (its 5 bands), for the glossy term.
      const total = await page.evaluate(() => window.prtApp.bytesTotal);
      check(visibilityBytes > 0 && total === entry.bytes, `the page fetches ${total} of ${entry.bytes} bytes (the visibility pass: ${visibilityBytes})`);
      check(await page.evaluate(() => window.prtApp.texelGlossyBands) === 5, 'the visibility pass is not on the GPU at its 5 bands');
      // The diffuse passes alone here (the baker's diffuse shade); the glossy term: texel_glossy_matches_baker.
      await page.evaluate(() => window.prtApp.set({ glossy: { shadowed: 'diffuse', interreflected: 'diffuse' } }));
      // Constant light reads coefficient 0 alone; the forest map (unrotated, the page's and the
      // baker's projection of the same file) weighs all 9, so every layer and lane is checked.
      for (const [pass, light] of [['interreflected', 'constant'], ['shadowed', 'constant'], ['interreflected', 'forest']]) {
        const t0 = Date.now();
        if (light === 'forest') await page.evaluate(() => window.prtApp.set({ environment: 'forest', envRotation: [0, 0], intensity: 1 }));
        const reference = JSON.parse(execFileSync(prtBake, ['shade', asset, '--texels', '--light', light === 'forest' ? envExr : 'constant',
          '--pass', pass, '--json'], { encoding: 'utf8', maxBuffer: 1 << 30 }));
        const gpu = await readAtlas(page, pass);
        const what = `${pass} under ${light} light`;
        const [atlas] = reference.atlases;
        if (!check(gpu.width === atlas.width && gpu.height === atlas.height, `${what}: read back ${gpu.width}x${gpu.height}, atlas ${atlas.width}x${atlas.height}`)) continue;
        let peak = 0;
        for (const t of reference.texels) peak = Math.max(peak, ...t.radiance);
        let compared = 0, worstRelative = 0, worstAbsolute = 0, bad = 0, firstBad = '';
        for (const t of reference.texels) {
          const i = 4 * (t.y * gpu.width + t.x);  // read-back row y is texel row y: no flip
          if (gpu.rgba[i + 3] !== 1) continue;  // the texel's centre lies outside every triangle (a chart's edge texel)
          compared++;
          for (let c = 0; c < 3; c++) {
            const want = t.radiance[c], got = gpu.rgba[i + c], error = Math.abs(got - want);
            worstAbsolute = Math.max(worstAbsolute, error / peak);
            if (Math.abs(want) > 0.01 * peak) worstRelative = Math.max(worstRelative, error / Math.abs(want));
            if (!(error <= 1e-3 * Math.abs(want) + 1e-4 * peak)) {
              if (!bad) firstBad = `texel (${t.x}, ${t.y}) channel ${c}: GPU ${got}, baker ${want}`;
              bad++;
            }
          }
        }
        console.log(`${what}: ${compared} of ${reference.texels.length} sampled texels compared, worst relative error ${worstRelative.toExponential(2)}, ` +
          `worst absolute ${worstAbsolute.toExponential(2)} of the peak ${peak.toFixed(3)} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
        check(compared > 0.5 * reference.texels.length, `${what}: only ${compared} of ${reference.texels.length} sampled texels were drawn in UV space`);
        check(bad === 0, `${what}: ${bad} channel values beyond 1e-3 relative + 1e-4 of the peak (${firstBad})`);
        check(peak > 0.1, `${what}: the reference is dark (peak ${peak})`);
      }
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // (b) The full-screen picture per texel: lit, different from the vertex picture where the
  // shading changes fastest (the contact shadows along the cube's base and under the sphere,
  // which the vertex grid, 6.25 cm apart, blurs and the 512 atlas, about 2 cm a texel, resolves)
  // and much less on open floor; switching back draws the vertex picture of before; lights
  // still light the texel picture (they only change the lighting vector).
  async texel_switch_and_shadows(browser) {
    const server = await startServer(prtServe, root, webDist);
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/${FURNACE}`, { waitReady: false });
      await waitAll(page);
      check(await page.evaluate(() => window.prtApp.source) === 'vertex', 'the page does not start per vertex');
      const vertex = await capture(page, { source: 'vertex', background: false });
      // Diffuse against diffuse: the vertex bake has no glossy pass.
      const texel = await capture(page, { source: 'texel', glossy: { shadowed: 'diffuse', interreflected: 'diffuse' } });
      check(await page.evaluate(() => window.prtApp.source) === 'texel', 'set({source: texel}) did not switch');
      const back = await capture(page, { source: 'vertex' });
      const lit = litStats(texel), litVertex = litStats(vertex);
      console.log(`lit fraction: texel ${lit.litFraction.toFixed(3)} (mean ${lit.mean.toFixed(1)}), vertex ${litVertex.litFraction.toFixed(3)} (mean ${litVertex.mean.toFixed(1)})`);
      check(lit.litFraction > 0.3 && Math.abs(lit.mean - litVertex.mean) < 0.1 * litVertex.mean,
        `texel picture: ${(100 * lit.litFraction).toFixed(1)} % lit, mean ${lit.mean.toFixed(1)} against the vertex picture's ${litVertex.mean.toFixed(1)}`);
      check(maxChannelDifference(vertex, back) === 0, `back in vertex mode the picture differs from before by up to ${maxChannelDifference(vertex, back)}/255`);
      // World points: just outside the cube's base (centre (0.9, 0, 0.6), side 1, turned 25 deg
      // about +y: x' = x cos + z sin, z' = -x sin + z cos), at the sphere's contact point (-0.9,
      // 0, 0.5) on its camera side, and on open floor far from every object.
      const yaw = 25 * Math.PI / 180, cube = (lx, lz) => [0.9 + lx * Math.cos(yaw) + lz * Math.sin(yaw), 0.002, 0.6 - lx * Math.sin(yaw) + lz * Math.cos(yaw)];
      const contact = [];
      for (const t of [-0.35, -0.2, 0, 0.2, 0.35]) contact.push(cube(0.52, t), cube(-0.52, t), cube(t, 0.52));
      for (const a of [0, 0.5, 1, 1.5, 2, 2.5, 3]) contact.push([-0.9 + 0.06 * Math.cos(a - 1.5), 0.002, 0.5 + 0.06 * Math.sin(a - 1.5) + 0.04]);
      const open = [[0, 0.002, 1.6], [-1.6, 0.002, 1.6], [0.2, 0.002, 1.2], [-0.3, 0.002, 0.9], [1.6, 0.002, 1.7], [0.0, 0.002, 1.9]];
      const pixels = await page.evaluate((pts) => pts.map((p) => window.prtApp.project(p)), [...contact, ...open]);
      const difference = (ps) => ps.reduce((sum, p) => sum + Math.abs(windowLuminance(texel, p, 2) - windowLuminance(vertex, p, 2)), 0) / ps.length;
      const atContact = difference(pixels.slice(0, contact.length)), onOpenFloor = difference(pixels.slice(contact.length));
      console.log(`|texel - vertex| luminance: ${atContact.toFixed(2)} at the contact shadows, ${onOpenFloor.toFixed(2)} on open floor`);
      check(atContact > 1.5 && atContact > 4 * onOpenFloor,
        `texel and vertex pictures differ by ${atContact.toFixed(2)} at the contact shadows and ${onOpenFloor.toFixed(2)} on open floor`);
      // A light above the cube: the texel picture brightens, in texel mode still.
      await page.evaluate(() => window.prtApp.set({ source: 'texel' }));
      const before = await capture(page, {});
      const withLight = await capture(page, { lights: [{ shape: 'sphere', position: [0.9, 2.2, 0.6], radius: 0.15, intensity: 60 }] });
      check(litStats(withLight).mean > litStats(before).mean + 2, `a light did not brighten the texel picture (${litStats(before).mean.toFixed(1)} -> ${litStats(withLight).mean.toFixed(1)})`);
      let refused = '';
      try {
        await page.evaluate(() => window.prtApp.set({ source: 'pixel' }));
      } catch (e) {
        refused = e.message;
      }
      check(/source must be one of vertex, texel/.test(refused), `set({source: 'pixel'}) was not refused: ${refused}`);
      await page.screenshot({ path: path.join(workDir, 'texel.png') });
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // (d) The TPFL glossy term per fragment against the CPU reference: the shadowed pass's glossy
  // term alone (panel switch 'glossy') read back in UV space under the forest map (all 9
  // lighting coefficients, so every entry of P(L) counts) from the page's own eye, against
  // prt-bake shade --texels --pass glossy --glossy-only --view EYE at the sampled texels.
  // The fragment shades its interpolated position and normal, which the rasteriser's sub-pixel
  // snapping (1/16 pixel in SwiftShader) moves by up to ~1/32 texel (0.6 mm here) from the
  // baker's sample; on the torus's thin tube (radius 0.14) that turns the normal by ~4 mrad, and
  // the glossy term, a difference of large terms where it is dim, moves by up to 7e-3 of the
  // peak. So the tolerance is 3e-3 of the peak plus 3e-3 of the value (the RGBA16F visibility:
  // 3e-4 of the peak in the Node test; float32 sums) plus 2 g dp, with dp the distance between
  // the fragment's shading point (read back) and the sample, and g the reference's own largest
  // slope |dL| / |dp| to its four neighbouring texels. Matte texels (k_s = 0) must be exactly 0.
  async texel_glossy_matches_baker(browser) {
    const server = await startServer(prtServe, root, webDist);
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/${FURNACE}&source=texel`, { waitReady: false });
      await waitAll(page);
      await page.evaluate(() => window.prtApp.set({ environment: 'forest', envRotation: [0, 0], intensity: 1, mode: 'shadowed', glossy: { shadowed: 'glossy' } }));
      await capture(page, {});
      const state = await page.evaluate(() => ({ error: window.prtApp.error, glossyError: window.prtApp.texelGlossyError, eye: window.prtApp.eye,
        bands: window.prtApp.texelGlossyBands, lights: window.prtApp.lights.length, stats: document.getElementById('stats').textContent }));
      check(state.error === null && state.glossyError === '', `page error: ${state.error} / ${state.glossyError}`);
      check(state.bands === 5 && state.lights === 0, `visibility bands ${state.bands} (want 5), ${state.lights} lights (want none: the baker's forest alone)`);
      check(/TPFL glossy, visibility order 5/.test(state.stats), `stats line: ${state.stats}`);
      const t0 = Date.now();
      const reference = glossyReference(asset, state.eye);
      const { compared, glossy, sloped, worstDp, worstRelative, worstAbsolute, bad, firstBad, peak } = await compareGlossy(page, reference);
      console.log(`TPFL glossy: ${compared} of ${reference.texels.length} texels compared (${glossy} glossy; ${sloped} channel values needed the slope term, shading point up to ${(1e3 * worstDp).toFixed(2)} mm from the sample), worst relative ${worstRelative.toExponential(2)}, ` +
        `worst absolute ${worstAbsolute.toExponential(2)} of the peak ${peak.toFixed(3)} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
      check(glossy > 1000, `only ${glossy} glossy texels compared`);
      check(sloped < 0.01 * 3 * glossy, `${sloped} of ${3 * glossy} glossy channel values beyond 3e-3 relative + 3e-3 of the peak: more than the texels where the shading point matters`);
      check(worstDp < 2e-3, `a fragment shaded ${worstDp} m from its texel's sample (more than a tenth of a texel)`);
      check(bad === 0, `TPFL glossy: ${bad} channel values beyond the tolerance (${firstBad})`);
      check(peak > 0.05, `the glossy reference is dark (peak ${peak})`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // (f) Normal maps in the glossy term: a gold metal quad (roughness 0.3) with a striped normal
  // map (the normal tilted up to 31 degrees along x, stripeQuadGltf), baked with --texel-glossy:
  // the asset carries texel normals (format 1.6), and the page's glossy term, read back in UV
  // space under the forest map, must equal prt-bake shade's, which reflects about them, within
  // texel_glossy_matches_baker's tolerance. The quad baked without the map has the same
  // visibility (the bump does not move the horizon) and no texel normals: its reference is what
  // a client reflecting about the interpolated normal computes, and the same measure must
  // refuse it at most glossy texels, so this case would fail such a client.
  async texel_glossy_normal_map(browser) {
    const gold = { color: [1.0, 0.78, 0.34, 1], metallic: 1, roughness: 0.3 };
    const bakeQuad = (name, withMap) => {
      const scene = path.join(workDir, `${name}.gltf`);
      fs.writeFileSync(scene, stripeQuadGltf(64, withMap, gold));
      const out = path.join(root, `${name}.prt`);
      execFileSync(prtBake, [scene, '-o', out, '--texels', '--texture-size', '64', '--samples', '256', '--order', '3',
        '--passes', 'shadowed', '--texel-glossy', '--texture-sets', 'scene', '--unwrap', 'never', '--name', name, '--quiet']);
      return { out, info: JSON.parse(execFileSync(prtBake, ['info', out, '--json'], { encoding: 'utf8' })) };
    };
    const mapped = bakeQuad('stripes-gold', true), flat = bakeQuad('stripes-gold-flat', false);
    check(mapped.info.version === '1.7' && mapped.info.texel_normals?.bytes === 4 * 64 * 64,
      `the normal-mapped bake has no texel normals section: ${JSON.stringify(mapped.info.texel_normals)}`);
    check(flat.info.texel_normals === null, `the bake without a normal map has texel normals: ${JSON.stringify(flat.info.texel_normals)}`);
    const server = await startServer(prtServe, root, webDist);
    try {
      const entry = (await (await fetch(`${server.base}/api/scenes`)).json()).scenes.find((e) => e.name === 'stripes-gold');
      const normalsPart = (entry?.parts ?? []).filter((p) => p.domain === 'texel' && p.pass === undefined && p.size >= 4 * 64 * 64);
      check(normalsPart.length >= 1, 'the catalogue lists no texel part large enough for the texel normals');
      const { page, consoleErrors } = await openPage(browser, `${server.base}/${FURNACE}&scene=stripes-gold&source=texel`, { waitReady: false });
      await waitAll(page);
      await page.evaluate(() => window.prtApp.set({ environment: 'forest', envRotation: [0, 0], intensity: 1, mode: 'shadowed', glossy: { shadowed: 'glossy' } }));
      // Up from the framing's grazing view: there the order-3 lobe of the sharp gold reflects the
      // forest's dark ground and rings below 0; from above it reflects the sky.
      await page.evaluate(() => window.prtApp.orbit(0, 0.6));
      await capture(page, {});
      const state = await page.evaluate(() => ({ error: window.prtApp.error, glossyError: window.prtApp.texelGlossyError, eye: window.prtApp.eye,
        bands: window.prtApp.texelGlossyBands }));
      check(state.error === null && state.glossyError === '', `page error: ${state.error} / ${state.glossyError}`);
      check(state.bands === 5, `visibility bands ${state.bands} (want 5)`);
      const reference = glossyReference(mapped.out, state.eye);
      const interpolated = glossyReference(flat.out, state.eye);
      check(reference.texels.every((t) => t.shading_normal), 'prt-bake shade prints no shading_normal for the normal-mapped asset');
      // The position dependence alone (no stripes) sets the slope term: the stripes' own texel
      // to texel change would otherwise excuse any normal.
      const gpu = await compareGlossy(page, reference, { slopeFrom: interpolated });
      const cpu = await compareGlossy(page, reference, { slopeFrom: interpolated, against: interpolated });
      console.log(`TPFL glossy with texel normals from (${state.eye.map((x) => x.toFixed(2)).join(', ')}): ${gpu.compared} texels (${gpu.glossy} glossy), GPU worst relative ${gpu.worstRelative.toExponential(2)}, ` +
        `worst absolute ${gpu.worstAbsolute.toExponential(2)} of the peak ${gpu.peak.toFixed(3)}, ${gpu.bad} beyond the tolerance; ` +
        `the interpolated normal: worst absolute ${cpu.worstAbsolute.toExponential(2)}, ${cpu.bad} of ${3 * cpu.glossy} channel values beyond it`);
      check(gpu.glossy > 3000, `only ${gpu.glossy} glossy texels compared`);
      check(gpu.bad === 0, `TPFL glossy with texel normals: ${gpu.bad} channel values beyond the tolerance (${gpu.firstBad})`);
      check(cpu.bad > 0.5 * 3 * cpu.glossy, `the interpolated normal's answer misses the mapped one at only ${cpu.bad} of ${3 * cpu.glossy} channel values: the test could not tell the two apart`);
      check(gpu.peak > 0.05, `the glossy reference is dark (peak ${gpu.peak})`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // (e) The glossy term follows the eye: after an orbit of 0.5 rad the sphere's and the
  // torus's texels (diffuse + glossy, read back in UV space) change and the matte floor's are
  // bit-identical; on screen, points of the torus change and points of the floor keep their
  // luminance (within 1/255: antialiasing at the new pixel positions); the 'diffuse' switch
  // removes the change.
  async texel_glossy_orbit(browser) {
    const server = await startServer(prtServe, root, webDist);
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/${FURNACE}&source=texel`, { waitReady: false });
      await waitAll(page);
      await page.evaluate(() => window.prtApp.set({ environment: 'forest', envRotation: [0, 0], intensity: 1, background: false }));
      // Points on the torus (centre (0.7, 0.14, -0.9), ring 0.4, tube 0.14; a purple metal, so its
      // glossy term is bright, where the white sphere's dielectric f0 = 0.04 keeps it faint).
      const sphere = [[0.7, 0.14, -0.36], [0.7, 0.28, -0.5], [0.7 + 0.283, 0.28, -0.9 + 0.283], [0.7 - 0.283, 0.28, -0.9 + 0.283]];
      const floor = [[0, 0.002, 1.6], [0.2, 0.002, 1.2], [-0.3, 0.002, 1.9]];
      const shoot = async () => {
        const img = await capture(page, {});
        const pixels = await page.evaluate((pts) => pts.map((p) => window.prtApp.project(p)), [...sphere, ...floor]);
        return { img, lum: pixels.map((p) => windowLuminance(img, p, 1)), atlas: await readAtlas(page, 'interreflected') };
      };
      const before = await shoot();
      await page.evaluate(() => { window.prtApp.orbit(0.5, 0); });
      const after = await shoot();
      // Texels: which ones are glossy comes from the baker (non-zero glossy term from either eye).
      const reference = JSON.parse(execFileSync(prtBake, ['shade', asset, '--texels', '--light', envExr, '--pass', 'glossy', '--glossy-only',
        '--view', '0,1.5,4', '--json'], { encoding: 'utf8', maxBuffer: 1 << 30 }));
      let glossyChanged = 0, glossyCount = 0, matteChanged = 0, matteCount = 0;
      for (const t of reference.texels) {
        const i = 4 * (t.y * before.atlas.width + t.x);
        if (before.atlas.rgba[i + 3] !== 1) continue;
        let d = 0;
        for (let c = 0; c < 3; c++) d = Math.max(d, Math.abs(after.atlas.rgba[i + c] - before.atlas.rgba[i + c]));
        const matte = t.radiance.every((r) => r === 0) && t.position[1] < 0.01;  // the floor
        if (matte) { matteCount++; if (d !== 0) matteChanged++; } else if (t.radiance.some((r) => r > 0)) { glossyCount++; if (d > 1e-3) glossyChanged++; }
      }
      const sphereChange = sphere.map((_, k) => Math.abs(after.lum[k] - before.lum[k]));
      const floorChange = floor.map((_, k) => Math.abs(after.lum[sphere.length + k] - before.lum[sphere.length + k]));
      console.log(`orbit 0.5 rad: ${glossyChanged} of ${glossyCount} glossy texels changed, ${matteChanged} of ${matteCount} floor texels; ` +
        `torus pixels by ${sphereChange.map((x) => x.toFixed(1)).join(', ')}, floor pixels by ${floorChange.map((x) => x.toFixed(2)).join(', ')} (of 255)`);
      check(glossyCount > 1000 && glossyChanged > 0.5 * glossyCount, `only ${glossyChanged} of ${glossyCount} glossy texels changed with the eye`);
      check(matteCount > 1000 && matteChanged === 0, `${matteChanged} of ${matteCount} floor texels changed with the eye`);
      check(Math.max(...sphereChange) > 3, `the torus's pixels changed by at most ${Math.max(...sphereChange).toFixed(2)}/255`);
      check(Math.max(...floorChange) <= 1, `the floor's pixels changed by up to ${Math.max(...floorChange).toFixed(2)}/255`);
      // Diffuse only: the same texels stay (the diffuse texel term does not depend on the eye).
      await page.evaluate(() => window.prtApp.set({ glossy: { interreflected: 'diffuse' } }));
      const d1 = await readAtlas(page, 'interreflected');
      await page.evaluate(() => { window.prtApp.orbit(-0.5, 0); });
      await capture(page, {});
      const d0 = await readAtlas(page, 'interreflected');
      let diffuseChanged = 0;
      for (let i = 0; i < d0.rgba.length; i++) if (d0.rgba[i] !== d1.rgba[i]) diffuseChanged++;
      check(diffuseChanged === 0, `with the switch on 'diffuse' ${diffuseChanged} atlas values changed with the eye`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // (c) An asset whose only transfer is per texel renders (whole-file loads: the server cuts no
  // parts, so loadAsset's path is the one taken), per texel, and draws exactly what the full
  // asset draws per texel; asking it for vertex passes is refused.
  async texel_only_asset(browser) {
    // The wasm bytes handed over directly: Node's global fetch (which the harness needs) cannot
    // load a file path.
    const core = await createRequire(import.meta.url)(path.resolve(coreJs))({ wasmBinary: fs.readFileSync(coreJs.replace(/\.js$/, ".wasm")) });
    const only = core.texelOnlyAsset(fs.readFileSync(asset), 'room-texel-only');
    if (typeof only === 'string') throw new Error(`texelOnlyAsset: ${only}`);
    fs.writeFileSync(path.join(root, 'room-texel-only.prt'), only);
    const server = await startServer(prtServe, root, webDist, ['--max-parts-mib', '0']);
    try {
      const open = async (scene, source) => {
        const opened = await openPage(browser, `${server.base}/${FURNACE}&scene=${scene}${source ? `&source=${source}` : ''}`);
        return { ...opened, img: await capture(opened.page, { background: false }) };
      };
      const onlyPage = await open('room-texel-only');
      const state = await onlyPage.page.evaluate(() => ({ error: window.prtApp.error, source: window.prtApp.source,
        texelBands: window.prtApp.texelBands, stats: document.getElementById('stats').textContent }));
      check(state.error === null, `the texel-only asset was refused: ${state.error}`);
      check(state.source === 'texel' && JSON.stringify(state.texelBands) === '[0,3,3]', `texel-only asset: source ${state.source}, texel bands ${JSON.stringify(state.texelBands)}`);
      check(/per texel \(512×512 atlas\)/.test(state.stats), `stats line: ${state.stats}`);
      const lit = litStats(onlyPage.img);
      check(lit.litFraction > 0.3, `the texel-only picture is ${(100 * lit.litFraction).toFixed(1)} % lit`);
      let refused = '';
      try {
        await onlyPage.page.evaluate(() => window.prtApp.set({ source: 'vertex' }));
      } catch (e) {
        refused = e.message;
      }
      check(/no vertex passes/.test(refused), `set({source: 'vertex'}) on a texel-only asset: ${refused || 'accepted'}`);
      // One page at a time: SwiftShader runs every page's GL in one process, and a page drawing
      // texel frames (about 0.3 s each) starves another's loading (80 s instead of 4 s seen).
      await onlyPage.page.close();
      const full = await open('room-texel', 'texel');
      check(await full.page.evaluate(() => window.prtApp.source) === 'texel', 'the full asset with ?source=texel is not drawn per texel');
      const d = maxChannelDifference(onlyPage.img, full.img);
      check(d === 0, `the texel-only asset's picture differs from the full asset's texel picture by up to ${d}/255`);
      check(onlyPage.consoleErrors.length === 0 && full.consoleErrors.length === 0, `console errors: ${[...onlyPage.consoleErrors, ...full.consoleErrors].join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },
};

await runCase(caseName, cases, checks);
