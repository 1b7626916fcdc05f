// Frame time of CPCA rendering straight from the clusters (Sloan 2003) against the same
// transfer expanded to plain floats on load, in headless Chromium (SwiftShader WebGL2 here,
// a GPU where there is one). One page, so one GL context draws at a time: each round loads
// every scene drawn from its clusters, times it, reloads it expanded (prtApp.setCpca) and
// times that; best round per setting; at 1280x720 and at 128x72, where the rasteriser is
// cheap, and the per-vertex PRT pass alone (for CPCA: cluster table, copy, weighted sums).
// Plain Lambert on the same mesh for scale.
// Usage: node cpca_frame_bench.mjs BASE_URL SCENE... [--gpu]   (prints JSON)
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../web/node_modules/playwright-core/index.mjs'));
const [base, ...scenes] = process.argv.slice(2).filter((a) => a !== '--gpu');
const gpu = process.argv.includes('--gpu');
const args = ['--no-sandbox', '--disable-background-networking', '--disable-component-update', '--no-first-run'];
if (!gpu) args.push('--use-angle=swiftshader', '--enable-unsafe-swiftshader');
else args.push('--use-angle=vulkan', '--enable-features=Vulkan', '--ignore-gpu-blocklist');
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', args });
const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });

// Opens `scene` (drawn from its clusters: the default) and waits for every band.
async function openScene(scene) {
  await page.goto(`${base}/?env=forest&scene=${encodeURIComponent(scene)}`);
  await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && window.prtApp.loadedBands.every((b) => b === 0 || b === 5))),
    null, { timeout: 600000 });
}
// The displayed pass's form and CPCA shape, after reloading it `form` when given.
async function formOf(form) {
  const r = await page.evaluate(async (f) => {
    if (f) await window.prtApp.setCpca(f);
    return { error: window.prtApp.error, form: window.prtApp.passForms.interreflected, shape: window.prtApp.cpcaShapes.interreflected };
  }, form);
  if (r.error) throw new Error(r.error);
  return r;
}

const sizes = [{ width: 1280, height: 720 }, { width: 128, height: 72 }];
const best = {};
const at = (name, size) => `${name} @ ${size.width}x${size.height}`;
async function time(name, mode) {
  await page.evaluate(() => { window.prtApp.paused = true; });
  for (const size of sizes) {
    await page.setViewportSize(size);
    const ms = await page.evaluate((m) => {
      const c = document.getElementById('view');
      c.width = c.clientWidth;  // the paused page does not resize its canvas itself
      c.height = c.clientHeight;
      window.prtApp.set({ mode: m, order: 5, background: false });
      window.prtApp.timeFrames(3);
      return window.prtApp.timeFrames(10);
    }, mode);
    best[at(name, size)] = Math.min(best[at(name, size)] ?? Infinity, ms);
  }
  if (mode !== 'lambert') {
    const ms = await page.evaluate(() => { window.prtApp.timeShading(3); return window.prtApp.timeShading(20); });
    best[`${name} shading`] = Math.min(best[`${name} shading`] ?? Infinity, ms);
  }
  await page.setViewportSize(sizes[0]);
  await page.evaluate(() => { window.prtApp.paused = false; });
}

const shapes = {};
let info = null;
for (let round = 0; round < 5; round++) {
  for (const scene of scenes) {
    await openScene(scene);
    const direct = await formOf(null);
    if (direct.form !== 'cpca') throw new Error(`${scene} is drawn ${direct.form}, not from its clusters`);
    shapes[scene] = direct.shape;
    info ??= await page.evaluate(() => {
      const gl = document.getElementById('view').getContext('webgl2');
      const ext = gl.getExtension('WEBGL_debug_renderer_info');
      return { renderer: ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER), vertices: window.prtApp.stats.vertices };
    });
    await time(`${scene} direct`, 'interreflected');
    const expanded = await formOf('expanded');
    if (expanded.form !== 'expanded') throw new Error(`${scene} reloaded expanded is drawn ${expanded.form}`);
    await time(`${scene} expanded`, 'interreflected');
    if (scene === scenes[0]) await time('lambert', 'lambert');
  }
}
await browser.close();

// Per setting: frame time at each viewport and the per-vertex PRT pass alone, each also as a
// ratio to the same scene expanded (Lambert: to the first scene expanded).
const rows = [];
const row = (setting, name, reference) => {
  const r = { setting };
  for (const size of sizes) {
    const v = `${size.width}x${size.height}`;
    r[`frame_ms_${v}`] = best[at(name, size)];
    r[`frame_ratio_${v}`] = best[at(name, size)] / best[at(reference, size)];
  }
  r.shading_ms = best[`${name} shading`] ?? null;
  r.shading_ratio = r.shading_ms === null ? null : r.shading_ms / best[`${reference} shading`];
  rows.push(r);
};
for (const scene of scenes) {
  const [k, n] = shapes[scene];
  row(`${scene} from clusters (K ${k}, ${n} weights)`, `${scene} direct`, `${scene} expanded`);
  row(`${scene} expanded (uncompressed)`, `${scene} expanded`, `${scene} expanded`);
}
row('lambert', 'lambert', `${scenes[0]} expanded`);
console.log(JSON.stringify({ date: new Date().toISOString(), machine: `${os.cpus()[0].model}, ${os.cpus().length} threads`,
  renderer: info.renderer, vertices: info.vertices, cpca_shapes: shapes,
  method: 'one page; per setting 10 frames back to back after 3 unmeasured, each ended by a 1-pixel readPixels, the page\'s own ' +
          'frame loop paused; 5 rounds, each opening every scene drawn from its clusters and then reloading it expanded ' +
          '(prtApp.setCpca); best round; background off, order 5; ratios compare a scene with itself expanded; ' +
          '"PRT pass" = the per-vertex transform-feedback pass alone (prtApp.timeShading: 20 back to back, then a 1-vertex read-back)',
  rows }, null, 2));
