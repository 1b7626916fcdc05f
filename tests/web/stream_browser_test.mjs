// Progressive loading in headless Chromium (web/shell/stream_loader.js) against a real
// prt-serve serving a default room baked with a compressed (CPCA) transfer: the page must
// show a lit picture from band 0 while most of the transfer is still on its way, sharpen to
// the same picture a whole-asset load gives, and turn damaged parts into the error box.
// Usage: node stream_browser_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { makeChecks, startServer as startServerAt, capture, luminance, meanAbsDifference, runCase, maxChannelDifference } from './browser_harness.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
for (const [what, p] of [['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]) {
  if (!p || !fs.existsSync(p)) {
    console.error(`${what} not found at ${p} (build the native and wasm presets; blender-data for the map)`);
    process.exit(1);
  }
}

const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });
execFileSync(prtBake, ['--default', '-o', path.join(root, 'room.prt'), '--samples', '256', '--order', '5',
  '--compress', 'cpca8@0.015', '--quiet']);
fs.copyFileSync(envExr, path.join(root, 'forest.exr'));

const startServer = () => startServerAt(prtServe, root, webDist);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
// Fixed view: the forest map, no background (the clear colour), order 5.
const VIEW = { background: false, envRotation: [0.6, 0.2], order: 5 };

async function catalogueEntry(base) {
  const catalogue = await (await fetch(`${base}/api/scenes`)).json();
  const entry = catalogue.scenes.find((s) => s.usable);
  if (!entry || !Array.isArray(entry.parts)) throw new Error(`no usable scene with parts: ${JSON.stringify(catalogue).slice(0, 300)}`);
  return entry;
}

async function newPage(browser) {
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  const consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`uncaught: ${e.message}`));
  return { page, consoleErrors };
}

// Fraction of pixels brighter than the clear colour by a clear margin, and their mean luminance.
function litStats(img) {
  let lit = 0, sum = 0;
  const n = img.width * img.height;
  for (let y = 0; y < img.height; y++)
    for (let x = 0; x < img.width; x++) {
      const l = luminance(img, x, y);
      sum += l;
      if (l > 40) lit++;
    }
  return { litFraction: lit / n, mean: sum / n };
}

const waitReady = (page) => page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && window.prtApp.frames > 2)),
  null, { timeout: 90000 });

const cases = {
  // Bands 1.. of every pass are held back until the first picture has been checked; every
  // part is also delayed, so the page really works on a slow stream.
  async stream_first_picture_then_sharpens(browser) {
    const server = await startServer();
    try {
      const entry = await catalogueEntry(server.base);
      const byUrl = new Map(entry.parts.map((p) => [p.url, p]));
      const transferTotal = entry.parts.filter((p) => p.pass).reduce((s, p) => s + p.size, 0);
      const kinds = [...new Set(entry.parts.filter((p) => p.pass).map((p) => p.pass))];
      check(entry.parts.some((p) => p.kind === 'transfer-band' && p.pass === 'interreflected' && p.band === 4),
        `the compressed bake has no band parts: ${JSON.stringify(entry.parts.map((p) => p.kind))}`);
      // One gate per band 1..4 of every pass, opened in order once the first picture is checked.
      const release = [], gates = [];
      for (let b = 0; b < 5; b++) gates.push(new Promise((r) => { release.push(r); }));
      const { page, consoleErrors } = await newPage(browser);
      let partsServed = 0;
      const servedBands = new Set();  // bands of the displayed pass let through
      await page.route('**/parts/**', async (route) => {
        const part = byUrl.get(new URL(route.request().url()).pathname);
        await sleep(30);
        if (part && part.kind === 'transfer-band' && part.band >= 1) await gates[part.band];
        if (part && part.kind === 'transfer-band' && part.pass === 'interreflected') servedBands.add(part.band);
        partsServed++;
        await route.continue();
      });
      await page.goto(`${server.base}/`);
      await waitReady(page);
      const early = await page.evaluate(() => ({ error: window.prtApp.error, bands: window.prtApp.loadedBands,
        received: window.prtApp.transferBytesReceived, total: window.prtApp.transferBytesTotal,
        bytes: window.prtApp.bytesReceived, bytesTotal: window.prtApp.bytesTotal }));
      check(early.error === null, `page error: ${early.error}`);
      check(early.total === transferTotal, `transferBytesTotal ${early.total}, the catalogue's transfer parts sum to ${transferTotal}`);
      check(early.bands && early.bands[2] === 1, `displayed (interreflected) pass should hold band 0 only, loadedBands ${JSON.stringify(early.bands)}`);
      // The displayed pass goes first: the others wait behind its held-back bands.
      check(early.bands && early.bands[0] === 0 && early.bands[1] === 0, `other passes before the displayed one: ${JSON.stringify(early.bands)}`);
      const first = await capture(page, VIEW);
      const firstState = await page.evaluate(() => ({ bands: window.prtApp.loadedBands, received: window.prtApp.transferBytesReceived }));
      const fraction = firstState.received / transferTotal;
      check(firstState.bands[2] === 1, `the first picture was taken at ${JSON.stringify(firstState.bands)} bands`);
      check(fraction < 0.25, `first picture with ${(100 * fraction).toFixed(1)}% of the transfer bytes (must be < 25%)`);
      const firstLit = litStats(first);
      check(firstLit.litFraction > 0.2, `first picture is not lit: ${(100 * firstLit.litFraction).toFixed(1)}% of pixels above the clear colour, mean ${firstLit.mean.toFixed(1)}`);
      await page.screenshot({ path: path.join(workDir, 'first.png') });
      // Band 2 arriving before band 1 must wait for it: bands are applied strictly in order.
      release[2]();
      await page.waitForFunction(() => window.prtApp.transferBytesReceived > 0 && window.prtApp.frames > 0, null, { timeout: 10000 });
      for (let i = 0; i < 100 && !servedBands.has(2); i++) await sleep(50);
      check(servedBands.has(2), 'band 2 of the displayed pass was not served after its gate opened');
      await sleep(500);
      const heldBack = await page.evaluate(() => window.prtApp.loadedBands[2]);
      check(heldBack === 1, `band 2 without band 1: the displayed pass holds ${heldBack} bands (must stay 1)`);
      // Then band by band: each arrival re-uploads the pass at a higher order and changes the picture.
      let previous = first;
      for (const [gate, expected] of [[1, 3], [3, 4]]) {
        release[gate]();
        await page.waitForFunction((n) => window.prtApp.error || window.prtApp.loadedBands[2] >= n, expected, { timeout: 60000 });
        const bands = await page.evaluate(() => window.prtApp.loadedBands[2]);
        check(bands === expected, `after releasing band ${gate} the displayed pass holds ${bands} bands, expected ${expected}`);
        const img = await capture(page, VIEW);
        const change = meanAbsDifference(previous, img);
        check(change > 0.05, `band ${gate} did not change the picture (mean difference ${change.toFixed(3)})`);
        previous = img;
      }
      release[4]();
      await page.waitForFunction((n) => window.prtApp.error || window.prtApp.loadedBands.filter((b) => b === 5).length === n,
        kinds.length, { timeout: 120000 });
      const done = await page.evaluate(() => ({ error: window.prtApp.error, bands: window.prtApp.loadedBands,
        received: window.prtApp.bytesReceived, total: window.prtApp.bytesTotal }));
      check(done.error === null, `page error after streaming: ${done.error}`);
      check(done.received === done.total && done.total === entry.bytes, `received ${done.received} of ${done.total} bytes (file ${entry.bytes})`);
      check(partsServed === entry.parts.length, `${partsServed} parts fetched, the catalogue lists ${entry.parts.length}`);
      const final = await capture(page, VIEW);
      await page.screenshot({ path: path.join(workDir, 'final.png') });
      const sharpening = meanAbsDifference(first, final);
      check(sharpening > 1, `order 5 looks like order 1: mean difference ${sharpening.toFixed(3)} / 255`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
      await page.close();

      // The same scene fetched whole (a catalogue without parts) must give the same picture.
      const whole = await newPage(browser);
      let assetFetched = false;
      await whole.page.route('**/api/scenes', async (route) => {
        const response = await route.fetch();
        const doc = await response.json();
        for (const s of doc.scenes) delete s.parts;
        await route.fulfill({ response, body: JSON.stringify(doc), headers: { 'content-type': 'application/json' } });
      });
      await whole.page.route('**/assets/**', async (route) => { assetFetched = true; await route.continue(); });
      await whole.page.goto(`${server.base}/`);
      await waitReady(whole.page);
      check(assetFetched, 'the whole-asset load did not fetch /assets/');
      const reference = await capture(whole.page, VIEW);
      const mean = meanAbsDifference(final, reference), max = maxChannelDifference(final, reference);
      check(mean < 0.05 && max <= 2, `streamed vs whole-asset picture: mean ${mean.toFixed(4)}, max ${max} / 255`);
      check(whole.consoleErrors.length === 0, `console errors (whole): ${whole.consoleErrors.join(' | ')}`);
      console.log(`first picture at ${(100 * fraction).toFixed(1)}% of ${transferTotal} transfer bytes; first vs final ${sharpening.toFixed(2)}; ` +
        `streamed vs whole mean ${mean.toFixed(4)} max ${max}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // Rendering straight from CPCA (the default) against the same passes expanded on load
  // (?cpca=expand), in two pages side by side: per-vertex exit radiance read back from the
  // GPU and the pictures must agree, for RGB and scalar passes, at the baked order and cut.
  async cpca_direct_matches_expanded(browser) {
    const server = await startServer();
    try {
      const entry = await catalogueEntry(server.base);
      const open = async (query) => {
        const { page, consoleErrors } = await newPage(browser);
        await page.goto(`${server.base}/${query}`);
        await waitReady(page);
        await page.waitForFunction(() => window.prtApp.error || window.prtApp.loadedBands.every((b) => b === 5), null, { timeout: 120000 });
        return { page, consoleErrors };
      };
      const direct = await open('');
      const expanded = await open('?cpca=expand');
      const forms = await direct.page.evaluate(() => ({ forms: window.prtApp.passForms, shapes: window.prtApp.cpcaShapes, error: window.prtApp.error }));
      const formsExpanded = await expanded.page.evaluate(() => window.prtApp.passForms);
      check(forms.error === null, `page error: ${forms.error}`);
      for (const kind of ['unshadowed', 'shadowed', 'interreflected']) {
        check(forms.forms[kind] === 'cpca', `${kind} is drawn ${forms.forms[kind]}, not from its clusters`);
        check(formsExpanded[kind] === 'expanded', `${kind} with ?cpca=expand is drawn ${formsExpanded[kind]}`);
        const [clusters, weights] = forms.shapes[kind];
        check(clusters >= 1 && weights >= 1 && weights <= 3 * 25, `${kind}: ${clusters} clusters, ${weights} weights per vertex`);
      }
      const statsLine = await direct.page.textContent('#stats');
      check(/CPCA: \d+ clusters, \d+ weights/.test(statsLine), `stats line does not say CPCA: ${statsLine}`);
      for (const view of [{ mode: 'interreflected', order: 5 }, { mode: 'interreflected', order: 3 }, { mode: 'shadowed', order: 5 }]) {
        const settings = { ...VIEW, ...view };
        const a = await capture(direct.page, settings), b = await capture(expanded.page, settings);
        const ra = await direct.page.evaluate(() => Array.from(window.prtApp.vertexRadiance()));
        const rb = await expanded.page.evaluate(() => Array.from(window.prtApp.vertexRadiance()));
        const name = `${view.mode} order ${view.order}`;
        if (!check(ra.length === entry.vertices * 3 && rb.length === ra.length, `${name}: read back ${ra.length} / ${rb.length} values for ${entry.vertices} vertices`)) continue;
        let peak = 0, worst = 0;
        for (let i = 0; i < rb.length; i++) peak = Math.max(peak, Math.abs(rb[i]));
        for (let i = 0; i < rb.length; i++) worst = Math.max(worst, Math.abs(ra[i] - rb[i]));
        check(peak > 0.05, `${name}: the expanded pass gives peak radiance ${peak}`);
        check(worst <= 1e-4 * peak, `${name}: CPCA-direct radiance differs from expanded by ${worst} (peak ${peak})`);
        const mean = meanAbsDifference(a, b), max = maxChannelDifference(a, b);
        check(mean < 0.05 && max <= 2, `${name}: direct vs expanded picture: mean ${mean.toFixed(4)}, max ${max} / 255`);
        console.log(`${name}: per-vertex max difference ${worst.toExponential(2)} of peak ${peak.toFixed(3)}; pictures mean ${mean.toFixed(4)} max ${max}`);
      }
      await direct.page.screenshot({ path: path.join(workDir, 'cpca-direct.png') });
      for (const p of [direct, expanded]) {
        check(p.consoleErrors.length === 0, `console errors: ${p.consoleErrors.join(' | ')}`);
        await p.page.close();
      }
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // A damaged band after the first picture, a truncated mesh part before it: both end in the
  // error box with the reader's words, never an uncaught exception.
  async stream_damaged_parts(browser) {
    const server = await startServer();
    try {
      const entry = await catalogueEntry(server.base);
      const byUrl = new Map(entry.parts.map((p) => [p.url, p]));
      const damage = [
        { what: 'a flipped byte in band 2 of the displayed pass', match: (p) => p.kind === 'transfer-band' && p.pass === 'interreflected' && p.band === 2,
          change: (b) => { const c = Buffer.from(b); c[Math.floor(c.length / 2)] ^= 0x40; return c; }, expect: /checksum/i },
        { what: 'a truncated mesh part', match: (p) => p.kind === 'section' && !p.pass && p.size > 1000,
          change: (b) => b.subarray(0, Math.floor(b.length / 2)), expect: /truncated/i },
      ];
      for (const d of damage) {
        const { page, consoleErrors } = await newPage(browser);
        let hit = false;
        await page.route('**/parts/**', async (route) => {
          const part = byUrl.get(new URL(route.request().url()).pathname);
          if (!part || !d.match(part) || hit) return route.continue();
          hit = true;
          const response = await route.fetch();
          const body = d.change(await response.body());
          await route.fulfill({ status: 200, body, headers: { 'content-type': 'application/octet-stream', 'content-length': String(body.length) } });
        });
        await page.goto(`${server.base}/`);
        await page.waitForFunction(() => window.prtApp && window.prtApp.error, null, { timeout: 90000 });
        const error = await page.evaluate(() => window.prtApp.error);
        check(hit, `${d.what}: the damaged part was never requested`);
        check(d.expect.test(error), `${d.what}: error ${error}`);
        check(await page.isVisible('#error'), `${d.what}: the error box is not visible`);
        check(!consoleErrors.some((e) => e.startsWith('uncaught')), `${d.what}: ${consoleErrors.join(' | ')}`);
        await page.close();
      }
      // A catalogue whose parts leave a gap in the file is refused before anything is fetched.
      const { page, consoleErrors } = await newPage(browser);
      await page.route('**/api/scenes', async (route) => {
        const response = await route.fetch();
        const doc = await response.json();
        for (const s of doc.scenes) if (s.parts) s.parts.splice(2, 1);
        await route.fulfill({ response, body: JSON.stringify(doc), headers: { 'content-type': 'application/json' } });
      });
      await page.goto(`${server.base}/`);
      await page.waitForFunction(() => window.prtApp && window.prtApp.error, null, { timeout: 90000 });
      const error = await page.evaluate(() => window.prtApp.error);
      check(/part list is unusable: part 2 starts at \d+, not where part 1 ends/.test(error), `a gap in the part list: ${error}`);
      check(!consoleErrors.some((e) => e.startsWith('uncaught')), `gap: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },
};

await runCase(caseName, cases, checks);
