// Light-update benchmark of the web client in headless Chromium (SwiftShader WebGL2 here):
// the time to re-render the light cube map and project it onto SH (prtApp.timeLightUpdates:
// projectLightsNow + finishGpu + the result read back) for 32^2, 64^2 and 128^2 texels per face, at orders 3 and 5,
// on the GPU and CPU paths, against three.js rendering the same emitters with a CubeCamera
// into a float WebGLCubeRenderTarget of the same size and projecting with
// LightProbeGenerator.fromCubeRenderTarget (order 3 only), in the same page on its own canvas.
// Medians of many timed samples. Not a test: it prints a table and writes JSON + Markdown.
// Usage: node web_lights_bench.mjs PRT_SERVE WEB_DIST ROOT OUT_JSON OUT_MD
//   ROOT holds lights3.prt and lights5.prt (the same scene baked at orders 3 and 5).
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { lightUpdateMarkdown, ROUNDS, SAMPLES, SAMPLE_MS, SIZES } from './light_update_report.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../web/node_modules/playwright-core/index.mjs'));
const [prtServe, webDist, root, outJson, outMd] = process.argv.slice(2);
const threeDir = path.join(here, '../web/node_modules/three');

// ---- the page: the client's dist plus three.js and the three side, under one root
const site = path.join(root, 'site');
fs.rmSync(site, { recursive: true, force: true });
fs.cpSync(webDist, site, { recursive: true });
fs.mkdirSync(path.join(site, 'three/addons/lights'), { recursive: true });
for (const f of ['three.module.js', 'three.core.js']) fs.copyFileSync(path.join(threeDir, 'build', f), path.join(site, 'three', f));
fs.copyFileSync(path.join(threeDir, 'examples/jsm/lights/LightProbeGenerator.js'), path.join(site, 'three/addons/lights/LightProbeGenerator.js'));
fs.copyFileSync(path.join(here, 'web_lights_three.js'), path.join(site, 'web_lights_three.js'));
const index = fs.readFileSync(path.join(webDist, 'index.html'), 'utf8');
const benchHtml = index
  .replace('<link rel="stylesheet"', '<script type="importmap">{"imports": {"three": "./three/three.module.js", "three/addons/": "./three/addons/"}}</script>\n  <link rel="stylesheet"')
  .replace('<script type="module" src="app.js"></script>', '<script type="module" src="app.js"></script>\n  <script type="module" src="web_lights_three.js"></script>');
if (benchHtml === index) throw new Error('index.html changed shape: cannot add the three.js side');
fs.writeFileSync(path.join(site, 'lights_bench.html'), benchHtml);

async function freePort() {
  return new Promise((resolve) => {
    const s = net.createServer().listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}
const port = await freePort();
const server = spawn(prtServe, ['--root', root, '--web', site, '--bind', '127.0.0.1', '--port', String(port), '--quiet'], { stdio: 'inherit' });
const base = `http://127.0.0.1:${port}`;
for (let i = 0; i < 200; i++) {
  try {
    if ((await fetch(`${base}/api/scenes`)).ok) break;
  } catch { /* not up yet */ }
  await new Promise((r) => setTimeout(r, 50));
}

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking',
    '--disable-component-update', '--no-first-run', '--disable-sync'],
});
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
// Samples of about SAMPLE_MS each (batches of updates when one update is shorter, as the
// page's timer has 100 us resolution), SAMPLES of them after a warm-up: the median.
async function timeOurs(page, onlyLight = -1) {
  // Warm-up, then a batch estimate from 20-update batches: sub-0.1 ms updates would round to the timer.
  await page.evaluate((k) => window.prtApp.timeLightUpdates(2, 4, k), onlyLight);
  const first = median(await page.evaluate((k) => window.prtApp.timeLightUpdates(5, 20, k), onlyLight));
  const batch = Math.max(1, Math.min(2000, Math.round(SAMPLE_MS / Math.max(first, 0.0025))));
  const samples = await page.evaluate(([n, b, k]) => window.prtApp.timeLightUpdates(n, b, k), [SAMPLES, batch, onlyLight]);
  return { median_ms: median(samples), min_ms: Math.min(...samples), samples: samples.length, batch };
}

const results = [];
const threeRows = [];
const analyticRows = [];
const COUNTS = [1, 4, 16, 64, 256];
// Analytic path against the GPU cube path at 64^2 for N seeded random sphere/disc/rect
// lights (prtApp.randomLights): every light re-projected, and one light moved (the cached
// others summed), as a drag does.
async function timeAnalytic(page, order) {
  for (const n of COUNTS) {
    const lights = await page.evaluate((k) => window.prtApp.randomLights(k, 11), n);
    await page.evaluate((l) => window.prtApp.set({ environment: null, lights: l, projection: 'analytic', cubeSize: 64 }), lights);
    const row = { order, lights: n };
    for (let round = 0; round < ROUNDS; round++) {
      await page.evaluate(() => window.prtApp.set({ projection: 'analytic' }));
      const all = await timeOurs(page, -1), one = await timeOurs(page, 0);
      await page.evaluate(() => window.prtApp.set({ projection: 'gpu' }));
      const cube = await timeOurs(page, -1);
      if (!row.all || all.median_ms < row.all.median_ms) row.all = all;
      if (!row.one || one.median_ms < row.one.median_ms) row.one = one;
      if (!row.cube || cube.median_ms < row.cube.median_ms) row.cube = cube;
    }
    analyticRows.push(row);
    console.log(`analytic order ${order}, ${n} lights: all ${row.all.median_ms.toFixed(4)} ms, one moved ${row.one.median_ms.toFixed(4)} ms; ` +
      `GPU cube 64^2 ${row.cube.median_ms.toFixed(3)} ms`);
  }
}
let info = null, crossCheck = null;
const browserVersion = browser.version();
try {
  const scenes = (await (await fetch(`${base}/api/scenes`)).json()).scenes;
  for (const order of [3, 5, 8]) {
    const entry = scenes.find((s) => s.file === `lights${order}.prt`);
    if (!entry) throw new Error(`lights${order}.prt missing under ${root}`);
    // The three.js side needs its inline import map, which the server's CSP forbids.
    const page = await browser.newPage({ viewport: { width: 640, height: 480 }, bypassCSP: true });
    page.on('pageerror', (e) => console.error(`page: ${e.message}`));
    await page.goto(`${base}/lights_bench.html?scene=${encodeURIComponent(entry.name)}`);
    await page.waitForFunction(() => window.prtApp && window.threeBench && (window.prtApp.error || (window.prtApp.ready && window.prtApp.frames > 2)), null, { timeout: 600000 });
    const error = await page.evaluate(() => window.prtApp.error);
    if (error) throw new Error(error);
    info ??= await page.evaluate(() => {
      const gl = document.getElementById('view').getContext('webgl2');
      const ext = gl.getExtension('WEBGL_debug_renderer_info');
      return { renderer: ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
        userAgent: navigator.userAgent, three: window.threeBench.revision, lightingModel: window.prtApp.lightingModel };
    });
    const c = await page.evaluate(() => window.prtApp.lightCenter);
    const r = await page.evaluate(() => window.prtApp.lightingRadius) || 1;
    const add = (v) => v.map((x, i) => c[i] + x * r);
    // Four emitters of every kind around the light centre, sized to the scene.
    const lights = [
      { shape: 'sphere', position: add([0.25, 0.15, 0.1]), radius: 0.07 * r, color: [1, 0.9, 0.8], intensity: 40 },
      { shape: 'disc', position: add([-0.2, 0.3, 0]), radius: 0.1 * r, normal: [0.3, -1, 0], color: [0.3, 0.6, 1], intensity: 20 },
      { shape: 'rect', position: add([0, 0.1, -0.35]), size: [0.15 * r, 0.1 * r], normal: [0, -0.2, 1], intensity: 15 },
      { shape: 'mesh', mesh: 'torus', position: add([0.15, -0.1, 0.25]), scale: 0.1 * r, color: [0.5, 1, 0.5], intensity: 20 },
    ];
    await page.evaluate((l) => window.prtApp.set({ environment: null, lights: l, order: 8 }), lights);
    // Our projection order is the baked order; check it is the one this row claims.
    const projected = await page.evaluate(() => window.prtApp.cubeSH().length);
    if (projected !== order * order) throw new Error(`lights${order}.prt projects ${projected} coefficients, expected ${order * order}`);
    if (order === 8) {
      await timeAnalytic(page, order);
      await page.close();
      continue;
    }
    // Interleaved rounds, best round per setting: other work on the machine only slows a round.
    const best = new Map();
    const keep = (key, value) => { if (!best.has(key) || value.median_ms < best.get(key).median_ms) best.set(key, value); };
    for (let round = 0; round < ROUNDS; round++) {
      for (const size of SIZES) {
        for (const projection of ['gpu', 'cpu']) {
          await page.evaluate((o) => window.prtApp.set(o), { cubeSize: size, projection });
          keep(`${projection} ${size}`, await timeOurs(page));
        }
        if (order !== 5) continue;
        // three.js in the same page: LightProbeGenerator with synchronous read-back, and the
        // cube render + synchronous read-back alone.
        await page.evaluate(([l, centre, s]) => window.threeBench.setup(l, centre, s), [lights, c, size]);
        await page.evaluate(() => window.threeBench.time(2, { syncReadback: true }));
        const sync = await page.evaluate((n) => window.threeBench.time(n, { syncReadback: true }), SAMPLES);
        const floor = await page.evaluate((n) => { window.threeBench.timeRenderAndReadback(3); return window.threeBench.timeRenderAndReadback(n); }, SAMPLES);
        keep(`three sync ${size}`, { median_ms: median(sync), samples: sync.length });
        keep(`three floor ${size}`, { median_ms: median(floor), samples: floor.length });
        if (round === 0) {
          // As shipped (async read-back): seconds per call here, so fewer samples, one round.
          const shipped = await page.evaluate(() => window.threeBench.time(7));
          keep(`three shipped ${size}`, { median_ms: median(shipped), samples: shipped.length });
        }
      }
    }
    for (const size of SIZES) {
      for (const projection of ['gpu', 'cpu']) {
        const t = best.get(`${projection} ${size}`);
        results.push({ implementation: 'ours', projection, order, size, ...t });
        console.log(`ours ${projection} order ${order} ${size}^2: ${t.median_ms.toFixed(3)} ms (best of ${ROUNDS} rounds, median of ${t.samples} samples of ${t.batch})`);
      }
      if (order !== 5) continue;
      const [shipped, sync, floor] = ['shipped', 'sync', 'floor'].map((k) => best.get(`three ${k} ${size}`));
      threeRows.push({ size, shipped_median_ms: shipped.median_ms, shipped_samples: shipped.samples, sync_readback_median_ms: sync.median_ms,
        sync_readback_samples: sync.samples, render_readback_median_ms: floor.median_ms });
      console.log(`three.js ${size}^2: LightProbeGenerator as shipped ${shipped.median_ms.toFixed(1)} ms, with sync readback ${sync.median_ms.toFixed(2)} ms; ` +
        `cube render + sync readback alone ${floor.median_ms.toFixed(2)} ms`);
    }
    await timeAnalytic(page, order);
    await page.evaluate((l) => window.prtApp.set({ lights: l }), lights);
    if (order === 5) {
      // Same emitters? Compare three's order-3 SH with ours (CPU path, 64^2, first 9 coefficients).
      await page.evaluate(([l, centre]) => window.threeBench.setup(l, centre, 64), [lights, c]);
      await page.evaluate(() => { window.prtApp.set({ projection: 'cpu', cubeSize: 64 }); window.prtApp.timeLightUpdates(1); });
      const ours = (await page.evaluate(() => window.prtApp.cubeSH())).slice(0, 9).flat();
      const theirs = (await page.evaluate(() => window.threeBench.sh())).flat();
      crossCheck = Math.hypot(...ours.map((x, i) => x - theirs[i])) / Math.hypot(...ours);
      console.log(`three.js vs ours, order-3 SH of the same emitters at 64^2: ${(100 * crossCheck).toFixed(2)}% (relative L2)`);
    }
    await page.close();
  }
} finally {
  await browser.close();
  server.kill('SIGTERM');
}

const ours = (projection, order, size) => results.find((x) => x.projection === projection && x.order === order && x.size === size).median_ms;
const three64 = threeRows.find((t) => t.size === 64);
const headline = {
  ours_gpu_order5_64_ms: ours('gpu', 5, 64),
  ours_cpu_order5_64_ms: ours('cpu', 5, 64),
  three_order3_64_sync_readback_ms: three64.sync_readback_median_ms,
  three_order3_64_as_shipped_ms: three64.shipped_median_ms,
  speedup_gpu: three64.sync_readback_median_ms / ours('gpu', 5, 64),
  speedup_cpu: three64.sync_readback_median_ms / ours('cpu', 5, 64),
  speedup_gpu_vs_as_shipped: three64.shipped_median_ms / ours('gpu', 5, 64),
  speedup_gpu_vs_three_render_readback: three64.render_readback_median_ms / ours('gpu', 5, 64),
};
const cpu = os.cpus();
const machine = `${cpu[0].model}, ${cpu.length} hardware threads, ${(os.totalmem() / 2 ** 30).toFixed(0)} GiB, ${os.type()} ${os.release()}`;
const result = {
  date: new Date().toISOString(), machine, chromium: browserVersion, userAgent: info.userAgent, renderer: info.renderer,
  three_revision: info.three, node: process.version, lighting_model: info.lightingModel, load_average_at_end: os.loadavg(),
  method: `best of ${ROUNDS} interleaved rounds of the median of ${SAMPLES} samples of ~${SAMPLE_MS} ms (batches of updates) after warm-up; ours: prtApp.timeLightUpdates ` +
    '(projectLightsNow + finishGpu + cubeSH read-back per update); three.js: CubeCamera.update + await LightProbeGenerator.fromCubeRenderTarget, ' +
    'as shipped (7 samples) and with readRenderTargetPixelsAsync swapped for the synchronous readRenderTargetPixels',
  emitters: 'sphere, disc, rect, torus mesh (4 lights)', headline, ours: results, three: threeRows,
  three_vs_ours_order3_sh_relative_l2_at_64: crossCheck,
  analytic: analyticRows,
};
fs.writeFileSync(outJson, JSON.stringify(result, null, 2) + '\n');

const md = lightUpdateMarkdown(result);
fs.writeFileSync(outMd, md);
console.log(`\n${md}`);
