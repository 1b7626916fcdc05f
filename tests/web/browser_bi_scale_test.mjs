// Bi-scale radiance transfer in the page (docs/bi-scale.md, "The client"), in headless
// Chromium (SwiftShader WebGL2) against a real prt-serve, on the default room baked with
// glossy matrices and an RTT placed through its lightmap UVs (prt-bake --glossy --rtt):
//   bi_scale_flat_is_diffuse_prt: with a flat RTT of the floor's albedo the bi-scale picture
//     is the diffuse PRT picture (the paper's reduction, per fragment on the GPU), the sphere's
//     macro shadow shows on the floor, and the GPU's rotated transferred radiance equals the
//     CPU's (prt::ShRotation of the CPCA matrices' T);
//   bi_scale_weave_depends_on_view: with a weave RTT, the view-dependence switch changes the
//     picture, orbiting changes the meso image, the bi-scale switch falls back to PRT.
// Usage: node browser_bi_scale_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { makeChecks, openCatalogueScene, requireInputs, capture, windowLuminance, maxChannelDifference, runCase } from './browser_harness.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
requireInputs([['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]);
const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });
fs.copyFileSync(envExr, path.join(root, 'forest.exr'));

// The room at order 4 (quick), glossy matrices CPCA-compressed, the RTT through TEXCOORD_1.
// `placement`: the id map's options (through the lightmap UVs, or synthesised).
function bakeRoom(patch, albedo, file, placement = ['--patches-per-uv', '40']) {
  const rtt = path.join(workDir, `${patch}.rtt`);
  execFileSync(prtBake, ['rtt', '--patch', patch, '--albedo', String(albedo), '--order', '4', '--spatial', '16', '--views', '8', '-o', rtt, '--quiet']);
  execFileSync(prtBake, ['--default', '-o', path.join(root, file), '--order', '4', '--samples', '64', '--bounces', '1', '--glossy',
    '--glossy-bounces', '0', '--compress', 'cpca8', '--rtt', rtt, ...placement, '--name', file.replace('.prt', ''), '--quiet']);
}

async function openScene(browser, file) {
  const { server, page, consoleErrors } = await openCatalogueScene(browser, prtServe, root, webDist, file);
  // Every glossy shell streamed in (the macro scale is the glossy pass).
  await page.waitForFunction(() => window.prtApp.glossyBands.shadowed === 4, null, { timeout: 60000 });
  return { server, page, consoleErrors };
}

const settings = { mode: 'shadowed', order: 4, environment: 'forest', envRotation: [0.6, 0.25], exposure: 0, glossy: { shadowed: 'diffuse' } };

const cases = {
  async bi_scale_flat_is_diffuse_prt(browser) {
    bakeRoom('flat', 0.75, 'room-flat.prt');
    const { server, page, consoleErrors } = await openScene(browser, 'room-flat.prt');
    try {
      check(await page.evaluate(() => window.prtApp.biScaleOrder) === 4, 'the page holds no order-4 RTT');
      const prt = await capture(page, { ...settings, biScale: false });
      check(!(await page.evaluate(() => window.prtApp.drewBiScale)), 'with bi-scale off the frame was still drawn bi-scale');
      const bi = await capture(page, { ...settings, biScale: true });
      check(await page.evaluate(() => window.prtApp.drewBiScale), 'with bi-scale on the frame was not drawn bi-scale');
      // The GPU's rotated transferred radiance against the CPU's.
      const { gpu, cpu } = await page.evaluate(() => ({ gpu: Array.from(window.prtApp.biScaleRotated()), cpu: Array.from(window.prtApp.biScaleRotatedReference()) }));
      let peak = 0, worst = 0;
      for (let i = 0; i < cpu.length; i++) peak = Math.max(peak, Math.abs(cpu[i]));
      for (let i = 0; i < cpu.length; i++) worst = Math.max(worst, Math.abs(gpu[i] - cpu[i]));
      console.log(`  rotated T: GPU vs CPU ${(worst / peak).toExponential(2)} of the peak ${peak.toFixed(3)} (${cpu.length} values)`);
      check(cpu.length > 0 && gpu.length === cpu.length, `rotated T read-back has ${gpu.length} values, the reference ${cpu.length}`);
      check(peak > 0.05 && worst <= 1e-4 * peak, `rotated T: GPU and CPU differ by ${worst} of ${peak}`);
      // Floor points clear of the objects (whose materials differ: the RTT replaces them), and
      // close to where the sphere (centre (-0.9, 0.5, 0.5), radius 0.5) touches the floor.
      const open = [[0.2, 0.002, 1.4], [0.9, 0.002, 1.6], [-0.2, 0.002, 1.7], [1.6, 0.002, 1.5]];
      const shaded = [[-0.9, 0.002, 0.7], [-0.75, 0.002, 0.65], [-1.05, 0.002, 0.65], [-0.9, 0.002, 0.8], [-1.2, 0.002, 0.5]];
      const where = await page.evaluate((pts) => pts.map((p) => window.prtApp.project(p)), [...open, ...shaded]);
      let worstRatio = 0;
      where.forEach((p, k) => {
        const a = windowLuminance(bi, p, 3), b = windowLuminance(prt, p, 3);
        worstRatio = Math.max(worstRatio, Math.abs(a - b) / Math.max(b, 1));
        console.log(`  floor point ${k}: bi-scale luminance ${a.toFixed(1)}, diffuse PRT ${b.toFixed(1)}`);
      });
      // The flat RTT holds the clamped cosine to order 4 (the vector pass the exact cosine's
      // projection), in half floats; tone-mapped 8-bit pixels.
      check(worstRatio < 0.04, `flat-RTT bi-scale and diffuse PRT floor pixels differ by ${(100 * worstRatio).toFixed(1)}%`);
      const lit = open.map((_, k) => windowLuminance(bi, where[k], 3));
      const dark = shaded.map((_, k) => windowLuminance(bi, where[open.length + k], 3));
      const meanLit = lit.reduce((s, x) => s + x, 0) / lit.length, meanDark = dark.reduce((s, x) => s + x, 0) / dark.length;
      console.log(`  macro shadow: open floor ${meanLit.toFixed(1)}, under the sphere ${meanDark.toFixed(1)}`);
      check(meanDark < 0.75 * meanLit, `no macro shadow under the sphere: ${meanDark.toFixed(1)} against ${meanLit.toFixed(1)} in the open`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async bi_scale_weave_depends_on_view(browser) {
    bakeRoom('weave', 0.8, 'room-weave.prt');
    await weaveChecks(browser, 'room-weave.prt');
  },

  // The same with the synthesised id map (patches 8 cm wide in cells of 3, a 1024^2 atlas).
  async bi_scale_synthesised_weave(browser) {
    bakeRoom('weave', 0.8, 'room-weave-synth.prt', ['--patch-width', '0.08', '--id-map-size', '512']);
    await weaveChecks(browser, 'room-weave-synth.prt');
  },
};

// A weave RTT: the view-dependence switch changes the picture, the weave shows on the floor
// (neighbouring pixels vary far more than under PRT), orbiting changes the meso image, and
// the bi-scale switch falls back to PRT.
async function weaveChecks(browser, file) {
  {
    const { server, page, consoleErrors } = await openScene(browser, file);
    try {
      const on = await capture(page, { ...settings, biScale: true, viewDependence: true });
      check(await page.evaluate(() => window.prtApp.drewBiScale), 'the weave scene was not drawn bi-scale');
      const fixed = await capture(page, { ...settings, biScale: true, viewDependence: false });
      const switched = maxChannelDifference(on, fixed);
      console.log(`  view dependence on vs off: max channel difference ${switched}`);
      check(switched > 20, `switching the RTT's view dependence changed the picture by only ${switched}`);
      // The weave's texture is there: neighbouring floor pixels vary far more than under PRT.
      const prt = await capture(page, { ...settings, biScale: false });
      const p = await page.evaluate(() => window.prtApp.project([0.3, 0.002, 1.2]));
      const spread = (img) => {
        const s = img.width / img.cssWidth;
        const values = [];
        for (let dy = -6; dy <= 6; dy++) for (let dx = -6; dx <= 6; dx++) {
          const i = 4 * (Math.round(p[1] * s + dy) * img.width + Math.round(p[0] * s + dx));
          values.push(img.data[i + 1]);
        }
        return Math.max(...values) - Math.min(...values);
      };
      console.log(`  floor texture: green spread ${spread(on)} bi-scale, ${spread(prt)} PRT`);
      check(spread(on) > spread(prt) + 10, `the weave does not show on the floor (spread ${spread(on)} against PRT's ${spread(prt)})`);
      // Orbiting with the lighting fixed changes the meso image (masking, view-dependent shading).
      await page.evaluate(() => window.prtApp.orbit(0.35, 0.15));
      const orbited = await capture(page, { ...settings, biScale: true, viewDependence: true });
      check(maxChannelDifference(on, orbited) > 20, 'orbiting did not change the bi-scale picture');
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  }
}

await runCase(caseName, cases, checks);
