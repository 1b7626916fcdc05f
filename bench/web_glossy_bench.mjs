// Frame time of glossy rendering in the web client (docs/web-client.md, "Glossy rendering";
// docs/bench/glossy.md), side by side in one page and one run at 1280x720: Lambert, diffuse
// PRT (the pass's vector term alone), diffuse + glossy, each with the camera moving (lighting
// unchanged) and with the lights moving (lighting changed every frame), and the glossy work
// alone: the cluster table (every cluster's matrices times the lighting), table + transferred
// radiance + view step, and the per-vertex view step alone. Headless Chromium on SwiftShader (or a real GPU with --gpu); interleaved
// rounds, best round per setting. Writes JSON (and prints a Markdown table).
// Usage: node web_glossy_bench.mjs BASE_URL SCENE OUT_JSON [--mode shadowed|interreflected]
//          [--order N] [--gpu] [--synthetic BANDS,CHANNELS,CLUSTERS,VECTORS] [--rounds R (default 5)]
//          [--bi-scale]
// --bi-scale adds the scene's bi-scale frames (docs/bi-scale.md; the scene needs an RTT): camera
// moving, lights moving, and view dependence off.
// SCENE is the catalogue name of a scene with a glossy matrix pass; --synthetic puts a
// synthetic CPCA matrix pass of that shape on it instead (any baked scene; stated in the JSON).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../web/node_modules/playwright-core/index.mjs'));
const argv = process.argv.slice(2);
const [base, scene, outJson] = argv;
if (!base || !scene || !outJson) {
  console.error('usage: node web_glossy_bench.mjs BASE_URL SCENE OUT_JSON [--mode M] [--order N] [--gpu] [--synthetic B,C,K,N]');
  process.exit(2);
}
const option = (name) => { const i = argv.indexOf(name); return i >= 0 ? argv[i + 1] : undefined; };
const gpu = argv.includes('--gpu');
const mode = option('--mode') || 'interreflected';
const order = Number(option('--order') || 5);
const synthetic = option('--synthetic');
const ROUNDS = Number(option('--rounds') || 5), FRAMES = 10;
const biScale = argv.includes('--bi-scale');

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
if (synthetic) {
  const [bands, channels, clusters, vectors] = synthetic.split(',').map(Number);
  await page.evaluate((s) => window.prtApp.useSyntheticGlossy(s), { mode, bands, channels, clusters, vectors, seed: 1, f0: 0.5, exponent: 30, minGreen: 0 });
}
if (biScale && !(await page.evaluate(() => window.prtApp.biScaleOrder))) throw new Error(`scene '${scene}' has no RTT (--bi-scale)`);
const info = await page.evaluate((m) => {
  const gl = document.getElementById('view').getContext('webgl2');
  const ext = gl.getExtension('WEBGL_debug_renderer_info');
  return { renderer: ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
           vertices: window.prtApp.stats.vertices, glossyBands: window.prtApp.glossyBands[m], glossyShape: window.prtApp.glossyShapes[m] };
}, mode);
if (!info.glossyBands) throw new Error(`scene '${scene}' has no glossy ${mode} pass (use --synthetic B,C,K,N)`);

// "camera moving": frames whose lighting is unchanged (the glossy term re-evaluates its cached
// transferred radiance at the new view); "lights moving": every frame's lighting changed, so
// the cluster table and the transferred radiance are remade too.
const settings = [
  { name: 'lambert', set: { mode: 'lambert', order } },
  { name: 'diffuse PRT', set: { mode, order, glossy: { [mode]: 'diffuse' } } },
  { name: 'diffuse + glossy, camera moving', set: { mode, order, glossy: { [mode]: 'both' } } },
  { name: 'diffuse PRT, lights moving', set: { mode, order, glossy: { [mode]: 'diffuse' } }, relight: true },
  { name: 'diffuse + glossy, lights moving', set: { mode, order, glossy: { [mode]: 'both' } }, relight: true },
  { name: 'glossy: cluster table alone', set: { mode, order, glossy: { [mode]: 'both' } }, glossy: 'table' },
  { name: 'glossy: table + fused step (lights moving)', set: { mode, order, glossy: { [mode]: 'both' } }, glossy: 'relight' },
  { name: 'glossy: table + transferred radiance + view step', set: { mode, order, glossy: { [mode]: 'both' } }, glossy: 'transfer' },
  { name: 'glossy: view step alone', set: { mode, order, glossy: { [mode]: 'both' } }, glossy: 'view' },
  ...(biScale ? [
    { name: 'bi-scale, camera moving', set: { mode, order, biScale: true, viewDependence: true } },
    { name: 'bi-scale, lights moving', set: { mode, order, biScale: true, viewDependence: true }, relight: true },
    { name: 'bi-scale, view dependence off', set: { mode, order, biScale: true, viewDependence: false } },
  ] : []),
];
// The PRT rows draw without the meso scale.
for (const s of settings) if (!('biScale' in s.set)) s.set.biScale = false;
const best = Object.fromEntries(settings.map((s) => [s.name, Infinity]));
for (let round = 0; round < ROUNDS; round++) {
  for (const s of settings) {
    await page.evaluate((o) => window.prtApp.set({ ...o, background: false }), s.set);
    const ms = await page.evaluate(([g, relight, n]) => {
      if (g) {
        window.prtApp.timeGlossy(2, g);
        return window.prtApp.timeGlossy(n, g);
      }
      window.prtApp.timeFrames(2, relight);
      return window.prtApp.timeFrames(n, relight);
    }, [s.glossy, !!s.relight, FRAMES]);
    best[s.name] = Math.min(best[s.name], ms);
  }
}
await browser.close();

const diffuse = best['diffuse PRT'];
const rows = settings.map((s) => ({ setting: s.name, ms: best[s.name], over_diffuse_prt: best[s.name] / diffuse }));
const machine = `${os.cpus()[0].model}, ${os.cpus().length} threads`;
const [clusters, vectors, channels] = info.glossyShape;
const result = {
  date: new Date().toISOString(), machine, renderer: info.renderer, scene, mode, order, vertices: info.vertices, viewport: '1280x720',
  glossy: { bands: info.glossyBands, clusters, vectors, channels, synthetic: synthetic || null },
  method: `${FRAMES} frames (or glossy passes) back to back, each frame ended by a 1-pixel readPixels; ${ROUNDS} interleaved rounds, best round`,
  rows,
};
fs.writeFileSync(outJson, JSON.stringify(result, null, 2) + '\n');
let md = `| setting | ms | / diffuse PRT |\n|---|---:|---:|\n`;
for (const r of rows) md += `| ${r.setting} | ${r.ms.toFixed(2)} | ${r.over_diffuse_prt.toFixed(2)}x |\n`;
console.log(`${info.renderer}; ${info.vertices} vertices; glossy ${mode} order ${info.glossyBands}, ${clusters} clusters, N' = ${vectors}, ${channels} channel(s)${synthetic ? ' (synthetic)' : ''}\n\n${md}`);
