// Permalinks in headless Chromium against a real prt-serve (docs/web-client.md,
// "Permalinks"): a view changed in every field a link holds, copied with the panel's
// "copy link" button, opens as the same view and the same pixels; junk links open the
// default view with a notice naming each bad value, and no console error.
// Usage: node browser_permalink_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { makeChecks, startServer as startServerAt, openPage, settle, capture, runCase } from './browser_harness.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
for (const [what, p] of [['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]) {
  if (!fs.existsSync(p)) {
    console.error(`${what} not found at ${p} (build the native and wasm presets; blender-data for the map)`);
    process.exit(1);
  }
}

const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });
execFileSync(prtBake, ['--default', '-o', path.join(root, 'room.prt'), '--samples', '256', '--order', '5', '--quiet']);
fs.copyFileSync(envExr, path.join(root, 'forest.exr'));

const view = (page) => page.evaluate(() => window.prtApp.view);
// Field-by-field equality, naming the first field that differs.
function sameView(a, b, what) {
  for (const key of new Set([...Object.keys(a), ...Object.keys(b)])) {
    if (JSON.stringify(a[key]) !== JSON.stringify(b[key])) {
      return check(false, `${what}: ${key} is ${JSON.stringify(b[key])}, expected ${JSON.stringify(a[key])}`);
    }
  }
  return true;
}
function pixelDifference(a, b) {
  let max = 0, differing = 0;
  for (let i = 0; i < a.data.length; i++) {
    const d = Math.abs(a.data[i] - b.data[i]);
    max = Math.max(max, d);
    if (d) differing++;
  }
  return { max, differing };
}

const cases = {
  async permalink_round_trip(browser) {
    const server = await startServerAt(prtServe, root, webDist);
    try {
      const first = await openPage(browser, `${server.base}/`);
      const { page } = first;
      const defaults = await view(page);
      // Change every field a link holds (the camera by an orbit, as a drag does).
      await page.evaluate(() => {
        const c = window.prtApp.lightCenter;
        window.prtApp.set({
          mode: 'shadowed', order: 3, exposure: 0.7, envRotation: [1.1, -0.4], intensity: 1.7, color: '#ffd0a0',
          environment: 'forest', projection: 'cpu', cubeSize: 32, glossy: { shadowed: 'diffuse' },
          lights: [{ shape: 'sphere', position: [c[0] + 0.4, c[1] + 0.6, c[2] + 0.2], radius: 0.15, color: [1, 0.8, 0.6], intensity: 25 },
            { shape: 'mesh', mesh: 'torus', position: [c[0] - 0.5, c[1] + 0.5, c[2]], scale: 0.3, intensity: 5 }],
        });
        window.prtApp.orbit(0.6, 0.25);
      });
      const changed = await view(page);
      for (const key of ['camera', 'mode', 'order', 'exposure', 'envYaw', 'intensity', 'color', 'lights', 'projection', 'cubeSize']) {
        check(JSON.stringify(changed[key]) !== JSON.stringify(defaults[key]), `${key} did not change from the default ${JSON.stringify(defaults[key])}`);
      }
      await page.context().grantPermissions(['clipboard-read', 'clipboard-write'], { origin: server.base });
      await page.getByText('copy link', { exact: true }).click();
      await page.waitForFunction(() => window.prtApp.link !== null, null, { timeout: 10000 });
      const copied = await page.evaluate(() => navigator.clipboard.readText());
      const [hookLink, address] = await page.evaluate(() => [window.prtApp.link, location.href]);
      check(copied === hookLink && address === hookLink, `clipboard '${copied}', prtApp.link '${hookLink}', address bar '${address}'`);
      check(copied.startsWith(`${server.base}/#`), `the link is not this page with a fragment: ${copied}`);
      check(/Link copied/.test(await page.textContent('#notice')), `notice: ${await page.textContent('#notice')}`);
      const before = await capture(page);
      // The link opens in a fresh page: the same view and, drawn the same way, the same pixels.
      const second = await openPage(browser, copied);
      const restored = await view(second.page);
      sameView(changed, restored, 'the link\'s view');
      const after = await capture(second.page);
      const diff = pixelDifference(before, after);
      check(diff.max === 0, `the link's picture differs: ${diff.differing} channel values, by up to ${diff.max}/255`);
      check(await second.page.evaluate(() => window.prtApp.linkProblems.length === 0 && document.getElementById('notice').hidden),
            `a good link gave a notice: ${await second.page.evaluate(() => window.prtApp.notice)}`);
      // The panel shows the link's values (it is built from them).
      const exposureField = await second.page.evaluate(() => [...document.querySelectorAll('.lil-controller')]
        .find((c) => c.querySelector('.lil-name')?.textContent === 'exposure (EV)')?.querySelector('input')?.value);
      check(Number(exposureField) === 0.7, `the panel's exposure reads ${exposureField}`);
      const errors = [...first.consoleErrors, ...second.consoleErrors];
      check(errors.length === 0, `console errors: ${errors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async permalink_junk(browser) {
    const server = await startServerAt(prtServe, root, webDist);
    try {
      const plain = await openPage(browser, `${server.base}/`);
      const defaults = await view(plain.page);
      const defaultPixels = await capture(plain.page);
      const junkLinks = [
        ['#scene=nowhere&camera=1,2,x&env=mars&exposure=banana&mode=glow&order=99&color=blue&bogus=1&lights=%5B%7B',
          [/scene="nowhere"/, /camera=/, /env="mars"/, /exposure="banana"/, /mode="glow"/, /order="99"/, /color="blue"/, /'bogus'/, /lights is not JSON/]],
        // Well-formed JSON but not a light: refused by the page's light checks.
        [`#lights=${encodeURIComponent(JSON.stringify([{ shape: 'cube', position: [0, 0, 0] }]))}&source=texel`,
          [/lights\[0\]\.shape must be one of/, /source=texel: scene '[^']+' has no texel passes/]],
        ['#v=7&scene=room', [/version 1/]],
        ['#%E0%A4%A&&&===', [/is not a view setting/]],
      ];
      for (const [fragment, patterns] of junkLinks) {
        const { page, consoleErrors } = await openPage(browser, `${server.base}/${fragment}`);
        const state = await page.evaluate(() => ({ error: window.prtApp.error, problems: window.prtApp.linkProblems,
          notice: document.getElementById('notice').textContent, shown: !document.getElementById('notice').hidden }));
        check(state.error === null, `${fragment}: the page failed: ${state.error}`);
        check(state.shown && /defaults shown instead/.test(state.notice), `${fragment}: no visible notice (${JSON.stringify(state.notice)})`);
        for (const p of patterns) {
          check(state.problems.some((x) => p.test(x)) && p.test(state.notice), `${fragment}: no problem matching ${p}: ${state.notice}`);
        }
        sameView(defaults, await view(page), `${fragment} falls back to the defaults`);
        const pixels = await capture(page);
        const diff = pixelDifference(defaultPixels, pixels);
        check(diff.max === 0, `${fragment}: the fallback picture differs from the default one (${diff.differing} values, up to ${diff.max}/255)`);
        check(consoleErrors.length === 0, `${fragment}: console errors: ${consoleErrors.join(' | ')}`);
        await page.close();
      }
      // A link with one bad value keeps the good ones.
      const { page } = await openPage(browser, `${server.base}/#exposure=1.5&mode=glow`);
      await settle(page);
      const partial = await view(page);
      check(partial.exposure === 1.5 && partial.mode === defaults.mode, `partly bad link: exposure ${partial.exposure}, mode ${partial.mode}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },
};

await runCase(caseName, cases, checks);
