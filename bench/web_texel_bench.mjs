// Frame time of transfer textures in the web client (docs/web-client.md, "Transfer textures";
// docs/bench/transfer-textures.md) against vertex PRT of the same asset, side by side in one
// page and one run at 1280x720: Lambert, vertex PRT and texel PRT (interreflected), each with
// a still lighting and with the lights moving (the lighting vector remade every frame); and,
// when the scene has a TPFL visibility pass (prt-bake --texel-glossy), texel diffuse + TPFL
// glossy beside texel diffuse alone (rows "texel PRT + TPFL glossy", with the ratio to "texel
// PRT" as vs_texel), still and moving (moving remakes P(L) in wasm every frame, after a
// read-back of the lighting block).
// Headless Chromium on SwiftShader (or a real GPU with --gpu); interleaved rounds, best round.
// Writes JSON (and prints a Markdown table).
// Usage: node web_texel_bench.mjs BASE_URL SCENE OUT_JSON [--order N] [--gpu] [--rounds R]
// SCENE is the catalogue name of a scene baked with --texels (vertex and texel passes).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../web/node_modules/playwright-core/index.mjs'));
const argv = process.argv.slice(2);
const [base, scene, outJson] = argv;
if (!base || !scene || !outJson) {
  console.error('usage: node web_texel_bench.mjs BASE_URL SCENE OUT_JSON [--order N] [--gpu] [--rounds R]');
  process.exit(2);
}
const option = (name) => { const i = argv.indexOf(name); return i >= 0 ? argv[i + 1] : undefined; };
const gpu = argv.includes('--gpu');
const order = Number(option('--order') || 5);
const ROUNDS = Number(option('--rounds') || 5), FRAMES = 10;

const args = ['--no-sandbox', '--disable-background-networking', '--disable-component-update', '--no-first-run'];
if (!gpu) args.push('--use-angle=swiftshader', '--enable-unsafe-swiftshader');
else args.push('--use-angle=vulkan', '--enable-features=Vulkan', '--ignore-gpu-blocklist');
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', args });
const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
await page.goto(`${base}/?env=forest&scene=${encodeURIComponent(scene)}`);
await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && window.prtApp.frames > 2 &&
  !(window.prtApp.bytesReceived < window.prtApp.bytesTotal))), null, { timeout: 600000 });
const error = await page.evaluate(() => window.prtApp.error);
if (error) throw new Error(error);
await page.evaluate(() => { window.prtApp.paused = true; });
const info = await page.evaluate(() => {
  const gl = document.getElementById('view').getContext('webgl2');
  const ext = gl.getExtension('WEBGL_debug_renderer_info');
  return { renderer: ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
           vertices: window.prtApp.stats.vertices, atlases: window.prtApp.atlases, visibilityOrder: window.prtApp.texelGlossyBands };
});
if (!info.atlases || info.atlases.length === 0) throw new Error(`scene '${scene}' has no transfer textures (bake it with --texels)`);

const mode = 'interreflected';
const diffuse = { glossy: { [mode]: 'diffuse' } }, both = { glossy: { [mode]: 'both' } };
const settings = [
  { name: 'lambert', set: { mode: 'lambert', order, source: 'vertex' } },
  { name: 'vertex PRT', set: { mode, order, source: 'vertex', ...diffuse } },
  { name: 'texel PRT', set: { mode, order, source: 'texel', ...diffuse } },
  { name: 'vertex PRT, lights moving', set: { mode, order, source: 'vertex', ...diffuse }, relight: true },
  { name: 'texel PRT, lights moving', set: { mode, order, source: 'texel', ...diffuse }, relight: true },
];
if (info.visibilityOrder > 0) {
  settings.push({ name: 'texel PRT + TPFL glossy', set: { mode, order, source: 'texel', ...both }, versus: 'texel PRT' },
    { name: 'texel PRT + TPFL glossy, lights moving', set: { mode, order, source: 'texel', ...both }, relight: true, versus: 'texel PRT, lights moving' });
}
const best = Object.fromEntries(settings.map((s) => [s.name, Infinity]));
for (let round = 0; round < ROUNDS; round++) {
  for (const s of settings) {
    await page.evaluate((o) => window.prtApp.set({ ...o, background: false }), s.set);
    const ms = await page.evaluate(([relight, n]) => {
      window.prtApp.timeFrames(2, relight);
      return window.prtApp.timeFrames(n, relight);
    }, [!!s.relight, FRAMES]);
    best[s.name] = Math.min(best[s.name], ms);
  }
}
await browser.close();

const cpu = os.cpus()[0]?.model?.trim() ?? 'unknown CPU';
const result = {
  date: new Date().toISOString(),
  machine: `${cpu}, ${os.cpus().length} threads, load average ${os.loadavg().map((x) => x.toFixed(1)).join(' ')}`,
  renderer: info.renderer, vertices: info.vertices, atlases: info.atlases, order, visibility_order: info.visibilityOrder, width: 1280, height: 720,
  method: `${FRAMES} frames back to back, each ended by a 1-pixel readPixels; ${ROUNDS} interleaved rounds, best round`,
  rows: settings.map((s) => ({ setting: s.name, ms: best[s.name], vs_vertex: best[s.name] / best['vertex PRT'],
    ...(s.versus ? { vs_texel: best[s.name] / best[s.versus] } : {}) })),
};
fs.writeFileSync(outJson, JSON.stringify(result, null, 2) + '\n');
for (const r of result.rows) console.log(`| ${r.setting} | ${r.ms.toFixed(2)} | ${r.vs_vertex.toFixed(2)}x | ${r.vs_texel ? `${r.vs_texel.toFixed(2)}x` : ''} |`);
