// What the browser tests share: Debian's headless Chromium (SwiftShader WebGL2) driven by
// playwright-core, a real prt-serve on a free loopback port, pixel read-back and the
// check/report bookkeeping. Used by browser_test.mjs and browser_lights_test.mjs.
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../../web/node_modules/playwright-core/index.mjs'));

export function makeChecks() {
  const failures = [];
  let count = 0;
  const check = (ok, message) => {
    count++;
    if (!ok) failures.push(message);
    return ok;
  };
  return { failures, check, count: () => count };
}

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

// Starts prt-serve on `root` with the page from `webDist` (and `extraArgs`, e.g. --max-parts-mib 0
// for whole-file loads); resolves once /api/scenes answers.
export async function startServer(prtServe, root, webDist, extraArgs = []) {
  const port = await freePort();
  const child = spawn(prtServe, ['--root', root, '--web', webDist, '--bind', '127.0.0.1', '--port', String(port), '--quiet', ...extraArgs],
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

export async function launchBrowser() {
  return chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking',
      '--disable-component-update', '--no-first-run', '--disable-sync'],
  });
}

// Opens `url` at 640x480 (or `viewport`) and (by default) waits until the page has drawn a
// few frames or failed; collects console errors and uncaught exceptions.
export async function openPage(browser, url, { waitReady = true, viewport = { width: 640, height: 480 } } = {}) {
  const page = await browser.newPage({ viewport });
  const consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`uncaught: ${e.message}`));
  await page.goto(url);
  if (waitReady) {
    // A scene streamed in parts is ready at its first band: wait for every part too.
    // And for the background image, which is fetched after the scene (docs/web-client.md, "Background").
    await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && window.prtApp.frames > 2 &&
      !(window.prtApp.bytesReceived < window.prtApp.bytesTotal) && !window.prtApp.backgroundLoading)),
      null, { timeout: 90000 });
  }
  return { page, consoleErrors };
}

// Waits for a few frames after the last change, and for a background image being fetched:
// once the scene has streamed (before that the page does not fetch it, and the stream may
// be held back on purpose).
export async function settle(page) {
  const before = await page.evaluate(() => window.prtApp.frames);
  await page.waitForFunction((n) => window.prtApp.frames > n + 2 &&
    !(window.prtApp.backgroundLoading && !(window.prtApp.bytesReceived < window.prtApp.bytesTotal)), before, { timeout: 30000 });
}

// Applies `settings` with prtApp.set, renders a few frames, returns the canvas pixels.
export async function capture(page, settings) {
  await page.evaluate((s) => window.prtApp.set(s), settings || {});
  await settle(page);
  // The pixels cross over as base64: as a JSON array of 1.2M numbers they took seconds.
  const img = await page.evaluate(() => {
    const c = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = c.width;
    copy.height = c.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(c, 0, 0);
    const bytes = ctx.getImageData(0, 0, c.width, c.height).data;
    let s = '';
    for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return { width: c.width, height: c.height, cssWidth: c.clientWidth, base64: btoa(s) };
  });
  return { width: img.width, height: img.height, cssWidth: img.cssWidth, data: Array.from(Buffer.from(img.base64, 'base64')) };
}

export const luminance = (img, x, y) => {
  const i = 4 * (Math.round(y) * img.width + Math.round(x));
  return 0.2126 * img.data[i] + 0.7152 * img.data[i + 1] + 0.0722 * img.data[i + 2];
};

// Mean luminance over a square window around CSS-pixel point p.
export function windowLuminance(img, p, radius = 4) {
  const s = img.width / img.cssWidth;
  let sum = 0, n = 0;
  for (let dy = -radius; dy <= radius; dy++)
    for (let dx = -radius; dx <= radius; dx++) {
      sum += luminance(img, p[0] * s + dx, p[1] * s + dy);
      n++;
    }
  return sum / n;
}

// The largest difference of one RGB channel value between two captures (alpha ignored).
export function maxChannelDifference(a, b) {
  let m = 0;
  for (let i = 0; i < a.data.length; i += 4)
    for (let c = 0; c < 3; c++) m = Math.max(m, Math.abs(a.data[i + c] - b.data[i + c]));
  return m;
}

export function meanAbsDifference(a, b) {
  let d = 0;
  for (let i = 0; i < a.data.length; i += 4) d += Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) + Math.abs(a.data[i + 2] - b.data[i + 2]);
  return d / (a.data.length / 4) / 3;
}

// A prt-serve of `root` and a page showing its catalogue entry for `file` (which must be
// usable): {server, page, consoleErrors, entry}. Throws naming the catalogue or page error.
export async function openCatalogueScene(browser, prtServe, root, webDist, file) {
  const server = await startServer(prtServe, root, webDist);
  const scenes = (await (await fetch(`${server.base}/api/scenes`)).json()).scenes;
  const entry = scenes.find((s) => s.file === file);
  if (!entry || !entry.usable) throw new Error(`${file} missing from the catalogue: ${JSON.stringify(scenes)}`);
  const { page, consoleErrors } = await openPage(browser, `${server.base}/?scene=${encodeURIComponent(entry.name)}`);
  const error = await page.evaluate(() => window.prtApp.error);
  if (error) throw new Error(`page error: ${error}`);
  return { server, page, consoleErrors, entry };
}

// Exits with status 1 naming the first of `inputs` ([what, path] pairs) that is missing.
export function requireInputs(inputs) {
  for (const [what, p] of inputs) {
    if (!p || !fs.existsSync(p)) {
      console.error(`${what} not found at ${p} (build the native and wasm presets; blender-data for the map)`);
      process.exit(1);
    }
  }
}

// A fresh WORK_DIR/root holding the default room baked at 256 samples, order 5 (room.prt)
// and the environment map `envExr` as forest.exr; returns the root.
export function bakeDefaultRoom(prtBake, workDir, envExr) {
  const root = path.join(workDir, 'root');
  fs.rmSync(workDir, { recursive: true, force: true });
  fs.mkdirSync(root, { recursive: true });
  execFileSync(prtBake, ['--default', '-o', path.join(root, 'room.prt'), '--samples', '256', '--order', '5', '--quiet']);
  fs.copyFileSync(envExr, path.join(root, 'forest.exr'));
  return root;
}

// Runs cases[caseName](browser) with a fresh browser, prints the verdict and exits 1 on failure.
export async function runCase(caseName, cases, checks) {
  const browser = await launchBrowser();
  try {
    if (!Object.hasOwn(cases, caseName)) throw new Error(`unknown case ${caseName}; known: ${Object.keys(cases).join(', ')}`);
    await cases[caseName](browser);
  } catch (e) {
    checks.failures.push(`${caseName}: ${e.stack || e}`);
  } finally {
    await browser.close();
  }
  if (checks.failures.length) {
    console.error(`${caseName}: ${checks.failures.length} of ${checks.count()} checks failed:\n  ${checks.failures.join('\n  ')}`);
    process.exit(1);
  }
  console.log(`${caseName}: ${checks.count()} checks passed`);
}
