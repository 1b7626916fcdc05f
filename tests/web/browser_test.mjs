// The web client in headless Chromium (Debian's, driven by playwright-core) against a real
// prt-serve on loopback serving a freshly baked default scene and a blender-data
// environment. One ctest test per case (shared harness: browser_harness.mjs).
// Usage: node browser_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import path from 'node:path';
import { makeChecks, startServer as startServerAt, openPage, settle, capture, windowLuminance, meanAbsDifference, runCase, requireInputs,
  bakeDefaultRoom } from './browser_harness.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
requireInputs([['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]);

// ---- fixtures: a root with a baked default scene and one environment map
const root = bakeDefaultRoom(prtBake, workDir, envExr);

const startServer = () => startServerAt(prtServe, root, webDist);

const cases = {
  async loads_and_renders(browser) {
    const server = await startServer();
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/`);
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
      // The page ran under the server's Content-Security-Policy, which allows wasm but not
      // eval: embind's glue is built without `new Function` (-sDYNAMIC_EXECUTION=0).
      const csp = (await fetch(`${server.base}/`)).headers.get('content-security-policy') ?? '';
      check(csp.includes("'wasm-unsafe-eval'") && !csp.includes("'unsafe-eval'"), `page CSP: ${csp}`);
      const statsText = await page.textContent('#stats');
      check(/vertices/.test(statsText) && /SH order 5/.test(statsText) && /MB loaded/.test(statsText), `stats line: ${statsText}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async shadows_order_rotation(browser) {
    const server = await startServer();
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/`);
      // Constant white light, no background: only transfer differs between modes.
      const furnace = { environment: 'white furnace', background: false, envRotation: [0, 0], order: 5 };
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

  async corrupt_asset(browser) {
    const server = await startServer();
    try {
      const page = await browser.newPage();
      // The asset arrives cut short (a broken proxy or connection): the decoder must say so.
      // Whole assets and progressive parts alike (the page streams parts when listed).
      await page.route(/\/(assets|parts)\//, async (route) => {
        try {
          const response = await route.fetch();
          const body = await response.body();
          await route.fulfill({ response, body: body.subarray(0, Math.floor(body.length / 3)), headers: { ...response.headers(), 'content-length': String(Math.floor(body.length / 3)) } });
        } catch (e) {
          // Parts still in flight when the test has its answer and closes the browser: playwright
          // then disposes their responses ("Response has been disposed"); nothing to check there.
          if (!/disposed|closed/i.test(e.message)) throw e;
        }
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

  // The default room framed on a landscape and a portrait (phone) screen, and kept framed
  // when the landscape page turns portrait: the scene's bounding sphere must lie inside the
  // view in both width and height. The sphere is inside the frustum's four side planes
  // (rows 3 +- 0 and 3 +- 1 of the view-projection matrix) iff its silhouette is inside NDC
  // [-1, 1]^2: the exact test, tangent planes included. The six axis-extreme points must
  // project inside as well, and the binding side must be close (the framing margin), so a
  // view that merely shrinks the scene does not pass.
  async framing_portrait(browser) {
    const checkFraming = async (page, what, viewport) => {
      const s = await page.evaluate(() => ({ m: window.prtApp.viewProjection(), sphere: window.prtApp.sceneSphere, error: window.prtApp.error,
        canvas: [document.getElementById('view').width, document.getElementById('view').height] }));
      check(s.error === null, `${what}: page error: ${s.error}`);
      check(Math.abs(s.canvas[0] / s.canvas[1] - viewport.width / viewport.height) < 0.01, `${what}: canvas is ${s.canvas.join('x')}`);
      const { m, sphere: { center: c, radius: r } } = s;
      if (!check(m.length === 16 && m.every(Number.isFinite) && r > 0, `${what}: matrix ${m} radius ${r}`)) return;
      const row = (i) => [m[i], m[4 + i], m[8 + i], m[12 + i]];
      const clip = (p) => [0, 1, 2, 3].map((i) => row(i)[0] * p[0] + row(i)[1] * p[1] + row(i)[2] * p[2] + row(i)[3]);
      const w = row(3);
      check(clip(c)[3] > r, `${what}: the sphere is not wholly in front of the camera (w at the centre ${clip(c)[3]}, radius ${r})`);
      // Signed distance from the centre to each side plane, in radii: >= 1 means inside.
      const planes = { left: [0, 1], right: [0, -1], bottom: [1, 1], top: [1, -1] };
      const margins = Object.fromEntries(Object.entries(planes).map(([name, [axis, sign]]) => {
        const p = row(axis).map((x, k) => w[k] + sign * x);
        return [name, (p[0] * c[0] + p[1] * c[1] + p[2] * c[2] + p[3]) / Math.hypot(p[0], p[1], p[2]) / r];
      }));
      const text = Object.entries(margins).map(([n, v]) => `${n} ${v.toFixed(3)}`).join(', ');
      console.log(`${what}: centre-to-side-plane distances in radii: ${text}`);
      for (const [name, v] of Object.entries(margins)) check(v >= 1, `${what}: the bounding sphere crosses the ${name} edge of the view (${text})`);
      const tightest = Math.min(...Object.values(margins));
      check(tightest <= 1.1, `${what}: the scene is framed loosely: the nearest edge is ${tightest.toFixed(3)} radii from the centre (${text})`);
      for (let axis = 0; axis < 3; axis++)
        for (const sign of [-1, 1]) {
          const p = c.map((x, k) => x + (k === axis ? sign * r : 0));
          const [x, y, , pw] = clip(p);
          check(pw > 0 && Math.abs(x / pw) <= 1 && Math.abs(y / pw) <= 1,
            `${what}: extreme point ${p.map((v) => v.toFixed(2))} projects to NDC (${(x / pw).toFixed(3)}, ${(y / pw).toFixed(3)})`);
        }
    };
    const server = await startServer();
    try {
      const landscape = { width: 1280, height: 720 }, portrait = { width: 390, height: 844 };
      for (const viewport of [landscape, portrait]) {
        const what = `${viewport.width}x${viewport.height}`;
        const { page, consoleErrors } = await openPage(browser, `${server.base}/`, { viewport });
        await checkFraming(page, what, viewport);
        if (viewport === landscape) {  // the phone turned: the framed scene stays framed
          await page.setViewportSize(portrait);
          await settle(page);
          await checkFraming(page, `${what} turned to ${portrait.width}x${portrait.height}`, portrait);
        }
        check(consoleErrors.length === 0, `${what}: console errors: ${consoleErrors.join(' | ')}`);
        await page.close();
      }
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async dead_server(browser) {
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

await runCase(caseName, cases, checks);
