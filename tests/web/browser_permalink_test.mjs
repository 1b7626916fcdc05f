// Permalinks in headless Chromium against a real prt-serve (docs/web-client.md,
// "Permalinks"): a view changed in every field a link holds, copied with the panel's
// "copy link" button, opens as the same view and the same pixels; junk links open the
// default view with a notice naming each bad value, and no console error.
// Usage: node browser_permalink_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { makeChecks, startServer as startServerAt, openPage, settle, capture, runCase, requireInputs, bakeDefaultRoom,
  maxChannelDifference } from './browser_harness.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
requireInputs([['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]);
const root = bakeDefaultRoom(prtBake, workDir, envExr);

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
      const diff = maxChannelDifference(before, after);
      check(diff === 0, `the link's picture differs from the original by up to ${diff}/255`);
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
        const diff = maxChannelDifference(defaultPixels, pixels);
        check(diff === 0, `${fragment}: the fallback picture differs from the default one by up to ${diff}/255`);
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
