// The web client in headless Chromium (Debian's, driven by playwright-core) against a real
// prt-serve on loopback serving a freshly baked default scene and a blender-data
// environment. One ctest test per case.
// Usage: node browser_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../../web/node_modules/playwright-core/index.mjs'));
const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);

const failures = [];
let checks = 0;
const check = (ok, message) => {
  checks++;
  if (!ok) failures.push(message);
  return ok;
};
for (const [what, p] of [['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]) {
  if (!fs.existsSync(p)) {
    console.error(`${what} not found at ${p} (build the native and wasm presets; blender-data for the map)`);
    process.exit(1);
  }
}

// ---- fixtures: a root with a baked default scene and one environment map
const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });
execFileSync(prtBake, ['--default', '-o', path.join(root, 'room.prt'), '--samples', '256', '--order', '5', '--quiet']);
fs.copyFileSync(envExr, path.join(root, 'forest.exr'));

async function freePort() {
  return new Promise((resolve, reject) => {
    const s = net.createServer();
    s.once('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

async function startServer() {
  const port = await freePort();
  const child = spawn(prtServe, ['--root', root, '--web', webDist, '--bind', '127.0.0.1', '--port', String(port), '--quiet'],
    { stdio: ['ignore', 'ignore', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  const base = `http://127.0.0.1:${port}`;
  for (let i = 0; i < 200; i++) {
    try {
      const r = await fetch(`${base}/api/scenes`);
      if (r.ok) return { child, base, stderr: () => stderr };
    } catch { /* not up yet */ }
    if (child.exitCode !== null) break;
    await new Promise((r) => setTimeout(r, 50));
  }
  child.kill('SIGKILL');
  throw new Error(`prt-serve did not come up on ${base}: ${stderr}`);
}

const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking',
    '--disable-component-update', '--no-first-run', '--disable-sync'],
});

async function openPage(url, { waitReady = true } = {}) {
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  const consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`uncaught: ${e.message}`));
  await page.goto(url);
  if (waitReady) {
    await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && window.prtApp.frames > 2)),
      null, { timeout: 90000 });
  }
  return { page, consoleErrors };
}

// Renders a few frames after a change, then returns the canvas as RGBA bytes.
async function capture(page, settings) {
  const before = await page.evaluate((s) => window.prtApp.set(s), settings || {});
  await page.waitForFunction((n) => window.prtApp.frames > n + 2, before, { timeout: 30000 });
  return page.evaluate(() => {
    const c = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = c.width;
    copy.height = c.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(c, 0, 0);
    return { width: c.width, height: c.height, cssWidth: c.clientWidth, data: Array.from(ctx.getImageData(0, 0, c.width, c.height).data) };
  });
}

const luminance = (img, x, y) => {
  const i = 4 * (Math.round(y) * img.width + Math.round(x));
  return 0.2126 * img.data[i] + 0.7152 * img.data[i + 1] + 0.0722 * img.data[i + 2];
};
// Mean luminance over a square window around CSS-pixel point p.
function windowLuminance(img, p, radius = 4) {
  const s = img.width / img.cssWidth;
  let sum = 0, n = 0;
  for (let dy = -radius; dy <= radius; dy++)
    for (let dx = -radius; dx <= radius; dx++) {
      sum += luminance(img, p[0] * s + dx, p[1] * s + dy);
      n++;
    }
  return sum / n;
}
function meanAbsDifference(a, b) {
  let d = 0;
  for (let i = 0; i < a.data.length; i += 4) d += Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) + Math.abs(a.data[i + 2] - b.data[i + 2]);
  return d / (a.data.length / 4) / 3;
}

const cases = {
  async loads_and_renders() {
    const server = await startServer();
    try {
      const { page, consoleErrors } = await openPage(`${server.base}/`);
      const state = await page.evaluate(() => ({ error: window.prtApp.error, frames: window.prtApp.frames, sh: window.prtApp.lightSH() }));
      check(state.error === null, `page error: ${state.error}`);
      check(state.frames > 2, `only ${state.frames} frames`);
      check(state.sh.length === 25 && state.sh[0][0] > 0, `lightSH: ${JSON.stringify(state.sh).slice(0, 200)}`);
      const img = await capture(page);
      let lo = 255, hi = 0;
      for (let i = 0; i < img.data.length; i += 4) {
        const l = img.data[i + 1];
        lo = Math.min(lo, l);
        hi = Math.max(hi, l);
      }
      check(hi - lo > 60, `screenshot looks blank (green range ${lo}..${hi})`);
      await page.screenshot({ path: path.join(workDir, 'loaded.png') });
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
      const statsText = await page.textContent('#stats');
      check(/vertices/.test(statsText) && /SH order 5/.test(statsText) && /MB loaded/.test(statsText), `stats line: ${statsText}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async shadows_order_rotation() {
    const server = await startServer();
    try {
      const { page, consoleErrors } = await openPage(`${server.base}/`);
      // Constant white light, no background: only transfer differs between modes.
      const furnace = { environment: null, background: false, envRotation: [0, 0], order: 5 };
      const unshadowed = await capture(page, { ...furnace, mode: 'unshadowed' });
      const shadowed = await capture(page, { ...furnace, mode: 'shadowed' });
      // The floor just in front of where the sphere (centre (-0.9, 0.5, 0.5), r 0.5) meets it.
      const contact = await page.evaluate(() => window.prtApp.project([-0.9, 0.0, 1.05]));
      const open = await page.evaluate(() => window.prtApp.project([0.3, 0.0, 1.9]));
      const ratioContact = windowLuminance(shadowed, contact) / windowLuminance(unshadowed, contact);
      const ratioOpen = windowLuminance(shadowed, open) / windowLuminance(unshadowed, open);
      check(ratioContact < 0.9, `shadowed/unshadowed at the sphere's contact is ${ratioContact.toFixed(3)}, expected clearly darker`);
      check(ratioContact < ratioOpen - 0.03, `contact ratio ${ratioContact.toFixed(3)} not below the open floor's ${ratioOpen.toFixed(3)}`);
      // Environment rotation and SH order change the image.
      const lit = { environment: 'forest', background: true, mode: 'interreflected' };
      const a = await capture(page, { ...lit, envRotation: [0, 0], order: 5 });
      const b = await capture(page, { ...lit, envRotation: [2.0, 0], order: 5 });
      const c = await capture(page, { ...lit, envRotation: [0, 0], order: 1 });
      const rotated = meanAbsDifference(a, b), truncated = meanAbsDifference(a, c);
      check(rotated > 2, `rotating the environment changed the image by only ${rotated.toFixed(2)}/255`);
      check(truncated > 2, `switching order 5 -> 1 changed the image by only ${truncated.toFixed(2)}/255`);
      const sh = await page.evaluate(() => window.prtApp.lightSH());
      check(sh.length === 1, `order 1 lighting should have 1 coefficient, got ${sh.length}`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async corrupt_asset() {
    const server = await startServer();
    try {
      const page = await browser.newPage();
      // The asset arrives cut short (a broken proxy or connection): the decoder must say so.
      await page.route('**/assets/**', async (route) => {
        const response = await route.fetch();
        const body = await response.body();
        await route.fulfill({ response, body: body.subarray(0, Math.floor(body.length / 3)), headers: { ...response.headers(), 'content-length': String(Math.floor(body.length / 3)) } });
      });
      await page.goto(`${server.base}/`);
      await page.waitForFunction(() => window.prtApp && window.prtApp.error, null, { timeout: 60000 });
      const error = await page.evaluate(() => window.prtApp.error);
      check(/truncated/.test(error), `error for a truncated asset: ${error}`);
      check(await page.isVisible('#error'), 'the error message is not visible');
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async dead_server() {
    const server = await startServer();
    const page = await browser.newPage();
    // Hold the catalogue request until the server is gone, then let it through.
    await page.route('**/api/scenes', async (route) => {
      server.child.kill('SIGKILL');
      await new Promise((r) => server.child.once('exit', r));
      await route.continue().catch(() => route.abort('connectionrefused'));
    });
    await page.goto(`${server.base}/`);
    await page.waitForFunction(() => window.prtApp && window.prtApp.error, null, { timeout: 60000 });
    const error = await page.evaluate(() => window.prtApp.error);
    check(/Cannot reach the server/.test(error), `error for a dead server: ${error}`);
    check(await page.isVisible('#error'), 'the error message is not visible');
    const text = await page.textContent('#error');
    check(text.length > 10, 'the error box is empty');
  },
};

try {
  if (!(caseName in cases)) throw new Error(`unknown case ${caseName}; known: ${Object.keys(cases).join(', ')}`);
  await cases[caseName]();
} catch (e) {
  failures.push(`${caseName}: ${e.stack || e}`);
} finally {
  await browser.close();
}
if (failures.length) {
  console.error(`${caseName}: ${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`${caseName}: ${checks} checks passed`);
