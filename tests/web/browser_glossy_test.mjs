// Glossy rendering in the page (docs/web-client.md, "Glossy rendering"), in headless Chromium
// (SwiftShader WebGL2) against a real prt-serve: the GPU's per-vertex glossy radiance (transform
// feedback read back) equals the CPU reference (prt::glossyExitRadiance on the expanded
// matrices, same lighting and eye), orbiting the camera moves the highlight on the glossy
// object while the diffuse floor (f0 = 0) stays as it was, and the diffuse / glossy / both
// switch draws what it says. The glossy passes are synthetic CPCA matrix passes
// (web/src/glossy_synthetic.h, through prtApp.useSyntheticGlossy) on a baked diffuse scene, so
// these cases need neither the matrix codec nor the glossy baker. glossy_asset_gpu_matches_reference
// streams a real glossy bake (prt-bake --default --glossy --compress cpca8) shell by shell and
// compares the GPU with the wasm core's reference computed here from the same bytes.
// Usage: node browser_glossy_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR PRT_CORE_NODE_JS
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { makeChecks, openCatalogueScene, capture, windowLuminance, runCase } from './browser_harness.mjs';
import { floorSceneGltf } from './floor_scene_gltf.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr, coreJs] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
for (const [what, p] of [['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr], ['wasm core', coreJs]]) {
  if (!p || !fs.existsSync(p)) {
    console.error(`${what} not found at ${p} (build the native and wasm presets; blender-data for the map)`);
    process.exit(1);
  }
}

// The floor (albedo 0.7) and box (albedo 0.8) scene: the synthetic glossy material goes on the
// vertices whose albedo green >= 0.75, the box; the floor keeps f0 = 0 (purely diffuse).
const BOX_MIN_GREEN = 0.75;
const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });
const gltf = path.join(workDir, 'floor.gltf');
fs.writeFileSync(gltf, floorSceneGltf());
if (caseName === 'glossy_asset_gpu_matches_reference') {
  // The default room with its glossy sphere and torus, glossy matrices CPCA-compressed.
  execFileSync(prtBake, ['--default', '--glossy', '-o', path.join(root, 'room-glossy.prt'), '--samples', '32', '--order', '4', '--compress', 'cpca8', '--quiet']);
} else {
  execFileSync(prtBake, [gltf, '-o', path.join(root, 'floor.prt'), '--samples', '256', '--order', '5', '--quiet']);
}
fs.copyFileSync(envExr, path.join(root, 'forest.exr'));

// GPU against CPU: float32 on both sides, in a different order (the GPU takes the matrix
// products per cluster before the weighted sum, the CPU after expanding; SwiftShader may fuse
// multiply-adds), so they agree to rounding: |gpu - cpu| <= TOLERANCE * max |cpu| over the pass.
const TOLERANCE = 1e-5;  // measured: 2-4e-7
function compare(gpu, cpu) {
  if (!gpu || !cpu || gpu.length !== cpu.length || gpu.length === 0) return { error: Infinity, peak: 0 };
  let peak = 0, worst = 0;
  for (let i = 0; i < cpu.length; i++) peak = Math.max(peak, Math.abs(cpu[i]));
  for (let i = 0; i < cpu.length; i++) worst = Math.max(worst, Math.abs(gpu[i] - cpu[i]));
  return { error: worst / Math.max(peak, 1e-30), peak };
}

const openScene = (browser, file = 'floor.prt') => openCatalogueScene(browser, prtServe, root, webDist, file);

const readBack = (page) => page.evaluate(() => ({
  gpu: Array.from(window.prtApp.vertexGlossy()),
  cpu: Array.from(window.prtApp.glossyReference()),
  diffuse: Array.from(window.prtApp.vertexRadiance()),
  step: window.prtApp.glossyStep,
}));

// The glossy radiance of both GPU steps for the settled view: a settled frame (lighting and
// camera unchanged) takes the view step on the cached transferred radiance; one more frame
// with the lighting marked changed (same values) takes the fused step from the cluster table.
async function bothSteps(page) {
  const view = await page.evaluate(() => ({ gpu: Array.from(window.prtApp.vertexGlossy()), step: window.prtApp.glossyStep }));
  const fused = await page.evaluate(() => {
    window.prtApp.timeFrames(1, true);
    return { gpu: Array.from(window.prtApp.vertexGlossy()), step: window.prtApp.glossyStep };
  });
  check(view.step === 'view', `a settled frame's glossy step was '${view.step}', expected 'view'`);
  check(fused.step === 'fused', `a relit frame's glossy step was '${fused.step}', expected 'fused'`);
  return [view, fused];
}

const cases = {
  // The GPU's per-vertex glossy radiance equals the CPU reference, for a 1-channel symmetric
  // (shadowed) and a 3-channel full (interreflected) pass, at the packed order and cut to fewer
  // bands, under the forest map, rotated, and from two eyes.
  async glossy_gpu_matches_reference(browser) {
    const { server, page, consoleErrors } = await openScene(browser);
    try {
      const passes = [
        { mode: 'shadowed', bands: 5, channels: 1, clusters: 12, vectors: 4, seed: 7 },
        { mode: 'interreflected', bands: 4, channels: 3, clusters: 6, vectors: 5, seed: 8 },
      ];
      for (const spec of passes) {
        await page.evaluate((s) => window.prtApp.useSyntheticGlossy({ ...s, f0: 1, exponent: 20, minGreen: 0.75 }), spec);
        const bands = await page.evaluate(() => window.prtApp.glossyBands);
        check(bands[spec.mode] === spec.bands, `${spec.mode}: ${bands[spec.mode]} glossy bands on the GPU, expected ${spec.bands}`);
        const shape = await page.evaluate(() => window.prtApp.glossyShapes);
        // One cluster more than asked for: the floor's zero cluster.
        check(JSON.stringify(shape[spec.mode]) === JSON.stringify([spec.clusters + 1, spec.vectors, spec.channels]), `${spec.mode}: shape ${shape[spec.mode]}`);
        for (const [order, yaw, orbit] of [[spec.bands, 0, 0], [2, 1.1, 0.7]]) {
          await page.evaluate((o) => window.prtApp.orbit(o, 0.2 * o), orbit);
          await capture(page, { mode: spec.mode, order, environment: 'forest', envRotation: [yaw, 0.3], glossy: { [spec.mode]: 'glossy' } });
          const { cpu } = await readBack(page);
          for (const { gpu, step } of await bothSteps(page)) {
            const { error, peak } = compare(gpu, cpu);
            const name = `${spec.mode} ${spec.channels}-channel order ${order} yaw ${yaw} orbit ${orbit}, ${step} step`;
            console.log(`  ${name}: GPU vs CPU glossy radiance max difference ${error.toExponential(2)} of the largest (${peak.toFixed(4)})`);
            check(peak > 1e-3, `${name}: the reference glossy radiance is ${peak}, nothing to compare`);
            check(error <= TOLERANCE, `${name}: GPU and CPU glossy radiance differ by ${error.toExponential(3)} (relative), allowed ${TOLERANCE}`);
            // The floor's vertices (zero matrices) have no glossy term at all.
            let zeroed = 0, zeros = 0;
            for (let v = 0; v < cpu.length / 3; v++) {
              if (cpu[3 * v] === 0 && cpu[3 * v + 1] === 0 && cpu[3 * v + 2] === 0) {
                zeros++;
                if (gpu[3 * v] === 0 && gpu[3 * v + 1] === 0 && gpu[3 * v + 2] === 0) zeroed++;
              }
            }
            check(zeros > 100 && zeroed === zeros, `${name}: ${zeroed} of ${zeros} non-glossy vertices have zero GPU glossy radiance`);
          }
        }
      }
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // A real glossy asset, streamed in parts: every glossy shell arrives (the server lists matrix
  // parts with form "matrix"), and the GPU's glossy radiance for both matrix passes equals the
  // wasm core's reference (prt::glossyExitRadiance on the pass's full decode), computed here
  // from the same file with the page's lighting and eye; orbiting changes it.
  async glossy_asset_gpu_matches_reference(browser) {
    const { server, page, consoleErrors, entry } = await openScene(browser, 'room-glossy.prt');
    try {
      const bytes = fs.readFileSync(path.join(root, 'room-glossy.prt'));
      const core = await createRequire(import.meta.url)(path.resolve(coreJs))({ wasmBinary: fs.readFileSync(coreJs.replace(/\.js$/, '.wasm')) });
      const matrixBands = (entry.parts || []).filter((p) => p.form === 'matrix' && p.kind === 'transfer-band');
      check(matrixBands.length === 8, `the catalogue lists ${matrixBands.length} glossy shell parts, expected 4 per matrix pass`);
      await page.waitForFunction(() => window.prtApp.glossyBands.shadowed === 4 && window.prtApp.glossyBands.interreflected === 4, null, { timeout: 60000 });
      // Orbiting reuses the cached transferred radiance (the lighting is unchanged); then the
      // environment turns with the camera still, so it must be remade for the new lighting.
      const steps = [{ orbit: 0, envRotation: [0.5, 0.2] }, { orbit: 0.6, envRotation: [0.5, 0.2] }, { orbit: 0, envRotation: [1.3, -0.4] }];
      for (const mode of ['shadowed', 'interreflected']) {
        for (const { orbit, envRotation } of steps) {
          await page.evaluate((o) => window.prtApp.orbit(o, 0), orbit);
          await capture(page, { mode, order: 4, environment: 'forest', envRotation, glossy: { [mode]: 'both' } });
          const lighting = (await page.evaluate(() => window.prtApp.lightSH())).flat();
          const eye = await page.evaluate(() => window.prtApp.eye);
          const r = core.glossyAssetCheck(bytes, mode, lighting, eye, true);
          if (!check(typeof r === 'object', `${mode}: ${r}`)) continue;
          const pageReference = await page.evaluate(() => Array.from(window.prtApp.glossyReference()));
          const { error: pageError } = compare(pageReference, r.reference);
          check(pageError <= 1e-5, `${mode} orbit ${orbit} environment ${envRotation}: the page's reference differs from the wasm core's by ${pageError.toExponential(3)}`);
          for (const { gpu, step } of await bothSteps(page)) {
            const { error, peak } = compare(gpu, r.reference);
            console.log(`  ${mode} orbit ${orbit} environment ${envRotation}, ${step} step: GPU vs wasm reference ${error.toExponential(2)} of the peak (${peak.toFixed(4)}); page reference ${pageError.toExponential(2)}`);
            check(peak > 1e-3, `${mode}: reference glossy radiance peaks at ${peak}`);
            check(error <= TOLERANCE, `${mode} orbit ${orbit} environment ${envRotation}, ${step} step: GPU and wasm reference differ by ${error.toExponential(3)} of the peak, allowed ${TOLERANCE}`);
          }
        }
      }
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // Orbiting the camera moves the highlight: the glossy box's pixels (and per-vertex glossy
  // radiance) change, the diffuse floor's pixels do not; the diffuse / glossy / both switch.
  async glossy_orbit_moves_highlight(browser) {
    const { server, page, consoleErrors } = await openScene(browser);
    try {
      const settings = { mode: 'shadowed', order: 5, environment: 'forest', envRotation: [0.4, 0.2], exposure: 0, glossy: { shadowed: 'diffuse' } };
      const diffuseOnly = await capture(page, settings);
      await page.evaluate(() => window.prtApp.useSyntheticGlossy({ mode: 'shadowed', bands: 5, channels: 1, clusters: 4, vectors: 2, seed: 3, f0: 0.9, exponent: 40, minGreen: 0.75 }));
      // The switch on 'diffuse' draws exactly the diffuse picture.
      const switchedOff = await capture(page, settings);
      let same = 0;
      for (let i = 0; i < diffuseOnly.data.length; i++) same = Math.max(same, Math.abs(diffuseOnly.data[i] - switchedOff.data[i]));
      check(same === 0, `with the glossy term switched off the picture changed (max byte difference ${same})`);
      // Points on the box's top and front faces (glossy) and on the floor (diffuse, f0 = 0).
      const boxPoints = [[0, 0.6, 0], [0.1, 0.6, -0.1], [0, 0.3, 0.3], [0.1, 0.45, 0.3]];
      const floorPoints = [[1.0, 0, 1.0], [-1.0, 0, 0.9], [0.9, 0, -0.6]];
      const shots = [];
      for (const orbit of [0, 0.5]) {
        await page.evaluate((o) => window.prtApp.orbit(o, 0), orbit);
        const both = await capture(page, { ...settings, glossy: { shadowed: 'both' } });
        const where = await page.evaluate((pts) => pts.map((p) => window.prtApp.project(p)), [...boxPoints, ...floorPoints]);
        const glossy = await page.evaluate(() => Array.from(window.prtApp.vertexGlossy()));
        const diffuse = await page.evaluate(() => Array.from(window.prtApp.vertexRadiance()));
        const glossyShot = await capture(page, { ...settings, glossy: { shadowed: 'glossy' } });
        shots.push({ both, glossyShot, where, glossy, diffuse });
      }
      const [a, b] = shots;
      const lum = (shot, i) => windowLuminance(shot.both, shot.where[i], 2);
      const boxChange = Math.max(...boxPoints.map((_, i) => Math.abs(lum(a, i) - lum(b, i))));
      const floorChange = Math.max(...floorPoints.map((_, k) => Math.abs(lum(a, boxPoints.length + k) - lum(b, boxPoints.length + k))));
      console.log(`  orbiting 0.5 rad: box pixels change by up to ${boxChange.toFixed(1)} (of 255), floor pixels by ${floorChange.toFixed(2)}`);
      check(boxChange > 8, `orbiting moved the highlight by only ${boxChange.toFixed(2)} luminance levels on the glossy box`);
      check(floorChange < 2, `the diffuse floor's pixels changed by ${floorChange.toFixed(2)} luminance levels when the camera orbited`);
      // Per vertex: the diffuse term ignores the camera; the glossy one follows it, and is zero on the floor.
      let diffuseMoved = 0, glossyMoved = 0, floorGlossy = 0;
      for (let i = 0; i < a.diffuse.length; i++) diffuseMoved = Math.max(diffuseMoved, Math.abs(a.diffuse[i] - b.diffuse[i]));
      for (let i = 0; i < a.glossy.length; i++) glossyMoved = Math.max(glossyMoved, Math.abs(a.glossy[i] - b.glossy[i]));
      // The floor's vertices: those the reference gives exactly zero (zero matrices).
      const reference = await page.evaluate(() => Array.from(window.prtApp.glossyReference()));
      let floorCount = 0;
      for (let v = 0; v < reference.length / 3; v++) {
        if (reference[3 * v] !== 0 || reference[3 * v + 1] !== 0 || reference[3 * v + 2] !== 0) continue;
        floorCount++;
        for (let c = 0; c < 3; c++) floorGlossy = Math.max(floorGlossy, Math.abs(a.glossy[3 * v + c]), Math.abs(b.glossy[3 * v + c]));
      }
      check(floorCount > 1000, `only ${floorCount} vertices without a glossy term; the floor has 2401`);
      check(diffuseMoved === 0, `the diffuse per-vertex radiance changed by ${diffuseMoved} when the camera orbited`);
      check(glossyMoved > 1e-3, `the glossy per-vertex radiance changed by only ${glossyMoved} when the camera orbited`);
      check(floorGlossy === 0, `floor vertices (no glossy matrices) have glossy radiance ${floorGlossy}`);
      // 'glossy' alone: the floor is black (no diffuse term, no glossy term).
      const dark = Math.max(...floorPoints.map((_, k) => windowLuminance(a.glossyShot, a.where[boxPoints.length + k], 2)));
      check(dark < 1, `with only the glossy term the diffuse floor should be black; luminance ${dark.toFixed(2)}`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },
};

await runCase(caseName, cases, checks);
