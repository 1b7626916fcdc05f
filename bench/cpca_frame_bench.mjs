// Frame time of CPCA rendering straight from the clusters (Sloan 2003) against the same
// transfer expanded to plain floats, in headless Chromium (SwiftShader WebGL2 here, a GPU
// where there is one): one page per form (?cpca=expand for the expanded one), both paused
// so only the timed page draws, interleaved rounds, best round per setting; at 1280x720 and
// at 128x72, where the rasteriser is cheap and the per-vertex shading dominates.
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

async function open(query) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(`${base}/${query}`);
  await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && window.prtApp.loadedBands.every((b) => b === 0 || b === 5))),
    null, { timeout: 600000 });
  const state = await page.evaluate(() => ({ error: window.prtApp.error, forms: window.prtApp.passForms, shapes: window.prtApp.cpcaShapes }));
  if (state.error) throw new Error(state.error);
  await page.evaluate(() => { window.prtApp.paused = true; });
  return { page, state };
}
const direct = [];
for (const scene of scenes) direct.push({ scene, ...(await open(`?env=forest&scene=${encodeURIComponent(scene)}`)) });
const expanded = await open(`?env=forest&cpca=expand&scene=${encodeURIComponent(scenes[0])}`);
for (const d of direct) {
  if (d.state.forms.interreflected !== 'cpca') throw new Error(`${d.scene} is drawn ${d.state.forms.interreflected}, not from its clusters`);
}
if (expanded.state.forms.interreflected !== 'expanded') throw new Error(`?cpca=expand draws ${expanded.state.forms.interreflected}`);
const info = await expanded.page.evaluate(() => {
  const gl = document.getElementById('view').getContext('webgl2');
  const ext = gl.getExtension('WEBGL_debug_renderer_info');
  return { renderer: ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER), vertices: window.prtApp.stats.vertices };
});

const sizes = [{ width: 1280, height: 720 }, { width: 128, height: 72 }];
const reference = { name: `${scenes[0]} expanded (uncompressed)`, page: expanded.page, mode: 'interreflected' };
const settings = [
  ...direct.map((d) => ({ name: `${d.scene} from clusters (K ${d.state.shapes.interreflected[0]}, ${d.state.shapes.interreflected[1]} weights)`,
                          page: d.page, mode: 'interreflected' })),
  reference,
  { name: 'lambert', page: expanded.page, mode: 'lambert' },
];
const key = (s, size) => `${s.name} @ ${size.width}x${size.height}`;
const best = {};
for (let round = 0; round < 5; round++) {
  for (const size of sizes) {
    for (const s of settings) {
      await s.page.setViewportSize(size);
      await s.page.evaluate((mode) => {
        const c = document.getElementById('view');
        c.width = c.clientWidth;  // the paused page does not resize its canvas itself
        c.height = c.clientHeight;
        window.prtApp.set({ mode, order: 5, background: false });
      }, s.mode);
      const ms = await s.page.evaluate(() => { window.prtApp.timeFrames(3); return window.prtApp.timeFrames(10); });
      best[key(s, size)] = Math.min(best[key(s, size)] ?? Infinity, ms);
    }
  }
}
await browser.close();
const rows = [];
for (const size of sizes) {
  const ref = best[key(reference, size)];
  for (const s of settings) {
    rows.push({ setting: s.name, viewport: `${size.width}x${size.height}`, ms_per_frame: best[key(s, size)],
                over_expanded: best[key(s, size)] / ref });
  }
}
console.log(JSON.stringify({ date: new Date().toISOString(), machine: `${os.cpus()[0].model}, ${os.cpus().length} threads`,
  renderer: info.renderer, vertices: info.vertices,
  cpca_shapes: Object.fromEntries(direct.map((d) => [d.scene, d.state.shapes.interreflected])),
  method: 'per setting 10 frames back to back, each ended by a 1-pixel readPixels; 5 interleaved rounds, best round; background off, order 5',
  rows }, null, 2));
