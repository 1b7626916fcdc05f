// The web client in headless Chromium (Debian's, driven by playwright-core) against a real
// prt-serve on loopback serving a freshly baked default scene and a blender-data
// environment. One ctest test per case (shared harness: browser_harness.mjs).
// Usage: node browser_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
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

  // The scene picker shows the server's thumbnails (docs/server.md, "Thumbnails"): a second
  // scene and a broken asset beside the room; the room's thumbnail decodes in the page at
  // 160x120 and is not blank; the second scene's thumbnail fails to load (held back here) and
  // its tile shows a placeholder; the broken asset is listed without a thumbnail and has no
  // tile; the keyboard moves between the tiles and picks a scene.
  async scene_thumbnails(browser) {
    execFileSync(prtBake, ['--default', '-o', path.join(root, 'second.prt'), '--samples', '16', '--order', '2', '--name', 'second room', '--quiet']);
    fs.writeFileSync(path.join(root, 'broken.prt'), fs.readFileSync(path.join(root, 'room.prt')).subarray(0, 4000));
    const server = await startServer();
    try {
      const catalogue = await (await fetch(`${server.base}/api/scenes`)).json();
      const byFile = Object.fromEntries(catalogue.scenes.map((e) => [e.file, e]));
      const room = byFile['room.prt'], second = byFile['second.prt'], broken = byFile['broken.prt'];
      check(room && room.usable && /^\/api\/scenes\/thumbnail\/[0-9a-f]{16}\.png$/.test(room.thumbnail || ''), `room entry: ${JSON.stringify(room).slice(0, 300)}`);
      check(second && second.usable && second.thumbnail && second.thumbnail !== room.thumbnail, `second entry's thumbnail: ${second && second.thumbnail}`);
      check(broken && !broken.usable && !('thumbnail' in broken), `broken entry: ${JSON.stringify(broken)}`);
      const thumb = await fetch(`${server.base}${room.thumbnail}`);
      check(thumb.status === 200 && thumb.headers.get('content-type') === 'image/png' &&
        /immutable/.test(thumb.headers.get('cache-control') || ''), `thumbnail response ${thumb.status} ${thumb.headers.get('content-type')}`);

      const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
      const consoleErrors = [];
      page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
      page.on('pageerror', (e) => consoleErrors.push(`uncaught: ${e.message}`));
      await page.route(`**${second.thumbnail}`, (route) => route.fulfill({ status: 404, contentType: 'text/plain', body: 'held back by the test' }));
      await page.goto(`${server.base}/`);
      await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.ready && document.querySelector('.scene-tile'))),
        null, { timeout: 90000 });
      check(await page.evaluate(() => window.prtApp.error) === null, 'page error');
      const tiles = await page.$$eval('.scene-tile', (els) => els.map((e) => e.dataset.scene));
      check(JSON.stringify(tiles) === JSON.stringify([room.name, second.name]), `tiles: ${JSON.stringify(tiles)} (the broken asset must have none)`);
      // The room's thumbnail, decoded by the browser, drawn into a canvas and read back.
      await page.waitForFunction((name) => {
        const img = document.querySelector(`.scene-tile[data-scene="${name}"] img`);
        return img && img.complete && img.naturalWidth > 0;
      }, room.name, { timeout: 30000 });
      const picture = await page.evaluate((name) => {
        const img = document.querySelector(`.scene-tile[data-scene="${name}"] img`);
        const c = document.createElement('canvas');
        c.width = img.naturalWidth;
        c.height = img.naturalHeight;
        const ctx = c.getContext('2d');
        ctx.drawImage(img, 0, 0);
        const d = ctx.getImageData(0, 0, c.width, c.height).data;
        let opaque = 0, clear = 0, lo = 255, hi = 0;
        for (let i = 0; i < d.length; i += 4) {
          if (d[i + 3] === 0) clear++;
          if (d[i + 3] === 255) {
            opaque++;
            lo = Math.min(lo, d[i + 1]);
            hi = Math.max(hi, d[i + 1]);
          }
        }
        const shown = img.getBoundingClientRect();
        return { width: img.naturalWidth, height: img.naturalHeight, opaque, clear, lo, hi, shownWidth: shown.width };
      }, room.name);
      check(picture.width === 160 && picture.height === 120, `thumbnail is ${picture.width}x${picture.height}, expected 160x120`);
      check(picture.opaque > 160 * 120 / 10 && picture.clear > 160 * 120 / 20, `thumbnail coverage: ${picture.opaque} opaque, ${picture.clear} clear pixels`);
      check(picture.hi - picture.lo > 40, `thumbnail looks flat (green ${picture.lo}..${picture.hi})`);
      check(picture.shownWidth > 40, `thumbnail shown ${picture.shownWidth} px wide`);
      // The second scene's image failed: its tile has a placeholder instead.
      await page.waitForSelector(`.scene-tile[data-scene="${second.name}"] .scene-placeholder`, { timeout: 30000 });
      check(await page.$(`.scene-tile[data-scene="${second.name}"] img`) === null, 'the failed image is still in the tile');
      await page.screenshot({ path: path.join(workDir, 'scene-picker.png') });
      // Keyboard: focus the room's tile, arrow to the next, Enter picks it.
      const pressed = (name) => page.getAttribute(`.scene-tile[data-scene="${name}"]`, 'aria-pressed');
      check(await pressed(room.name) === 'true' && await pressed(second.name) === 'false', 'the room is not marked as shown');
      await page.focus(`.scene-tile[data-scene="${room.name}"]`);
      await page.keyboard.press('ArrowRight');
      const focused = await page.evaluate(() => document.activeElement && document.activeElement.dataset.scene);
      check(focused === second.name, `ArrowRight focused ${focused}`);
      await page.keyboard.press('Enter');
      await page.waitForFunction((name) => window.prtApp.error || window.prtApp.scene === name, second.name, { timeout: 90000 });
      check(await page.evaluate(() => window.prtApp.scene) === second.name, 'Enter did not load the second scene');
      check(await pressed(second.name) === 'true' && await pressed(room.name) === 'false', 'the picker does not mark the second scene as shown');
      // The mark shows: the pressed tile's border differs from the other's (lil-gui's button
      // rules must not flatten it).
      const borders = await page.$$eval('.scene-tile', (els) => els.map((e) => `${getComputedStyle(e).borderTopStyle} ${getComputedStyle(e).borderTopColor}`));
      check(borders.every((b) => b.startsWith('solid')) && borders[0] !== borders[1], `tile borders: ${JSON.stringify(borders)}`);
      // The only console error allowed is the thumbnail the test held back.
      const others = consoleErrors.filter((e) => !/404/.test(e));
      check(others.length === 0, `console errors: ${others.join(' | ')}`);
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
