// The image background in headless Chromium against a real prt-serve (docs/web-client.md,
// "Background"): the page draws the environment map itself, rotated with the lighting and
// tone-mapped with the scene's exposure, fetched only after the scene; the other modes.
// Usage: node browser_background_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR ENV_EXR
import { makeChecks, startServer, openPage, capture, runCase, requireInputs, bakeDefaultRoom } from './browser_harness.mjs';

const [caseName, prtServe, prtBake, webDist, workDir, envExr] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
requireInputs([['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist], ['environment map', envExr]]);
const root = bakeDefaultRoom(prtBake, workDir, envExr);

// GL's RGB9_E5 (EXT_texture_shared_exponent), written here from the spec, not from the server.
function decodeRgb9e5(bytes) {
  const words = new Uint32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  const out = new Float32Array(words.length * 3);
  for (let i = 0; i < words.length; i++) {
    const w = words[i];
    const scale = 2 ** ((w >>> 27) - 15 - 9);
    out[3 * i] = (w & 511) * scale;
    out[3 * i + 1] = ((w >>> 9) & 511) * scale;
    out[3 * i + 2] = ((w >>> 18) & 511) * scale;
  }
  return out;
}

// The equirect mapping of shared/prt/sh_project.h (projectEquirect): column u is longitude
// 2 pi (u - 1/2) from +x toward +z, row v from the top is latitude pi/2 - pi v.
const directionOf = (u, v) => {
  const lat = Math.PI / 2 - Math.PI * v, phi = 2 * Math.PI * (u - 0.5);
  return [Math.cos(lat) * Math.cos(phi), Math.sin(lat), Math.cos(lat) * Math.sin(phi)];
};
// GL bilinear lookup of the texture at direction m: u repeats, v clamps, texel centres at (i + 1/2) / size.
function lookup(tex, m) {
  const u = Math.atan2(m[2], m[0]) / (2 * Math.PI) + 0.5, v = Math.acos(Math.max(-1, Math.min(1, m[1]))) / Math.PI;
  const x = u * tex.width - 0.5, y = v * tex.height - 0.5;
  const x0 = Math.floor(x), y0 = Math.floor(y), fx = x - x0, fy = y - y0;
  const at = (i, j) => {
    const ii = ((i % tex.width) + tex.width) % tex.width, jj = Math.max(0, Math.min(tex.height - 1, j));
    return tex.rgb.subarray(3 * (jj * tex.width + ii), 3 * (jj * tex.width + ii) + 3);
  };
  const a = at(x0, y0), b = at(x0 + 1, y0), c = at(x0, y0 + 1), d = at(x0 + 1, y0 + 1);
  return [0, 1, 2].map((k) => (a[k] * (1 - fx) + b[k] * fx) * (1 - fy) + (c[k] * (1 - fx) + d[k] * fx) * fy);
}
// The page's tone mapping (shaders/background.frag, shade.frag): exposure, the ACES fit, sRGB.
const aces = (x) => Math.min(1, Math.max(0, (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)));
const srgb = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055);
const toneMap = (radiance, ev) => radiance.map((x) => 255 * srgb(aces(Math.max(0, x) * 2 ** ev)));

function invert4(m) {  // column-major 4x4, by cofactors
  const inv = new Array(16);
  const a = (r, c) => m[c * 4 + r];
  for (let r = 0; r < 4; r++)
    for (let c = 0; c < 4; c++) {
      const rows = [0, 1, 2, 3].filter((i) => i !== c), cols = [0, 1, 2, 3].filter((j) => j !== r);
      const s = (i, j) => a(rows[i], cols[j]);
      const minor = s(0, 0) * (s(1, 1) * s(2, 2) - s(1, 2) * s(2, 1)) - s(0, 1) * (s(1, 0) * s(2, 2) - s(1, 2) * s(2, 0)) +
        s(0, 2) * (s(1, 0) * s(2, 1) - s(1, 1) * s(2, 0));
      inv[c * 4 + r] = ((r + c) % 2 ? -1 : 1) * minor;
    }
  const det = [0, 1, 2, 3].reduce((sum, k) => sum + a(0, k) * inv[k * 4], 0);
  return inv.map((x) => x / det);
}
const mulPoint = (m, p) => {
  const out = [0, 1, 2, 3].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * p[3]);
  return out.slice(0, 3).map((x) => x / out[3]);
};
// R = R_y(yaw) R_x(pitch) (ClientApp::updateLighting), applied transposed: the map at R^T d.
function inverseRotate(yaw, pitch, d) {
  const cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
  const R = [[cy, sy * sp, sy * cp], [0, cp, -sp], [-sy, cy * sp, cy * cp]];
  return [0, 1, 2].map((j) => R[0][j] * d[0] + R[1][j] * d[1] + R[2][j] * d[2]);
}

const cases = {
  async background_shows_map(browser) {
    const server = await startServer(prtServe, root, webDist);
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/`);
      const lights = await (await fetch(`${server.base}/api/lights?order=8`)).json();
      const forest = lights.lights.find((l) => l.name === 'forest');
      check(forest && forest.background && forest.background.format === 'rgb9e5', `/api/lights has no background for forest: ${JSON.stringify(forest).slice(0, 300)}`);
      const shown = await page.evaluate(() => window.prtApp.backgroundImage);
      check(shown && shown.environment === 'forest' && shown.width === forest.background.width && shown.height === forest.background.height,
            `prtApp.backgroundImage: ${JSON.stringify(shown)}`);
      const r = await fetch(`${server.base}${forest.background.url}`);
      check(r.ok && /immutable/.test(r.headers.get('cache-control') ?? ''), `background: HTTP ${r.status}, cache-control ${r.headers.get('cache-control')}`);
      const tex = { width: forest.background.width, height: forest.background.height, rgb: decodeRgb9e5(new Uint8Array(await r.arrayBuffer())) };
      check(tex.rgb.length === 3 * tex.width * tex.height, `background: ${tex.rgb.length / 3} texels for ${tex.width}x${tex.height}`);

      // The texture is the map the lighting comes from, in the same orientation: its own SH
      // projection (bands 0 and 1, exact solid angles) matches the server's coefficients.
      const sh = Array.from({ length: 4 }, () => [0, 0, 0]);
      for (let j = 0; j < tex.height; j++) {
        const weight = (2 * Math.PI / tex.width) * (Math.cos(Math.PI * j / tex.height) - Math.cos(Math.PI * (j + 1) / tex.height));
        for (let i = 0; i < tex.width; i++) {
          const [x, y, z] = directionOf((i + 0.5) / tex.width, (j + 0.5) / tex.height);
          const basis = [0.282095, 0.488603 * y, 0.488603 * z, 0.488603 * x];
          for (let k = 0; k < 4; k++) for (let c = 0; c < 3; c++) sh[k][c] += weight * basis[k] * tex.rgb[3 * (j * tex.width + i) + c];
        }
      }
      for (let k = 0; k < 4; k++)
        for (let c = 0; c < 3; c++) {
          const want = forest.coefficients[k][c];
          check(Math.abs(sh[k][c] - want) < 0.01 * Math.abs(forest.coefficients[0][c]) + 1e-4,
                `SH of the background texture [${k}][${c}] = ${sh[k][c].toFixed(5)}, the server's lighting has ${want.toFixed(5)}`);
        }

      // The picture: rotated, tinted and exposed; background pixels are those that change
      // when the background goes (the scene's do not).
      const yaw = 0.9, pitch = 0.3, ev = 0.5, tint = [1, 224 / 255, 192 / 255].map((x) => 1.3 * x);
      const settings = { envRotation: [yaw, pitch], exposure: ev, intensity: 1.3, color: '#ffe0c0' };
      const image = await capture(page, { ...settings, background: 'image' });
      const none = await capture(page, { background: 'none' });
      const blurred = await capture(page, { background: 'blurred' });
      const colour = await capture(page, { background: 'colour', backgroundColor: '#336699' });
      const inv = invert4(await page.evaluate(() => window.prtApp.viewProjection()));
      // Background pixels: exactly the clear colour without a background and exactly #336699
      // with the colour one (no scene pixel is both), away from the scene's antialiased edges.
      const W = image.width, H = image.height;
      const pure = new Uint8Array(W * H);
      for (let i = 0; i < W * H; i++) {
        const o = 4 * i;
        pure[i] = none.data[o] === 5 && none.data[o + 1] === 5 && none.data[o + 2] === 6 &&
          colour.data[o] === 0x33 && colour.data[o + 1] === 0x66 && colour.data[o + 2] === 0x99 ? 1 : 0;
      }
      let changed = 0;  // pixels the background changes at all: the pure ones and the edges
      for (let i = 0; i < W * H; i++) if ([0, 1, 2].some((c) => image.data[4 * i + c] !== none.data[4 * i + c])) changed++;
      let background = 0, compared = 0, within = 0, worst = 0, imageVsBlurred = 0;
      for (let py = 1; py < H - 1; py++)
        for (let px = 1; px < W - 1; px++) {
          const i = py * W + px, o = 4 * i;
          if (!(pure[i] && pure[i - 1] && pure[i + 1] && pure[i - W] && pure[i + W])) continue;
          background++;
          imageVsBlurred += [0, 1, 2].reduce((s, c) => s + Math.abs(image.data[o + c] - blurred.data[o + c]), 0) / 3;
          if ((px + py) % 5) continue;  // every fifth pixel is plenty
          const ndc = [(px + 0.5) / W * 2 - 1, 1 - (py + 0.5) / H * 2];
          const far = mulPoint(inv, [...ndc, 1, 1]), near = mulPoint(inv, [...ndc, -1, 1]);
          const d = far.map((x, k) => x - near[k]);
          const len = Math.hypot(...d);
          const radiance = lookup(tex, inverseRotate(yaw, pitch, d.map((x) => x / len))).map((x, k) => x * tint[k]);
          const want = toneMap(radiance, ev);
          const error = Math.max(...[0, 1, 2].map((c) => Math.abs(image.data[o + c] - want[c])));
          compared++;
          worst = Math.max(worst, error);
          if (error <= 2) within++;
        }
      check(background > 0.2 * image.width * image.height, `only ${background} background pixels`);
      // Tone-mapping rounding: the 8-bit output (0.5 level), the texture filter's fixed-point
      // weights and float precision in the shader's atan/acos (1.8 levels at worst measured).
      check(worst <= 3, `${compared - within} of ${compared} background pixels differ from the map's texel by more than 2/255, worst ${worst.toFixed(1)}/255`);
      check(imageVsBlurred / background > 3, `the image background is barely different from the blurred one (${(imageVsBlurred / background).toFixed(2)}/255)`);
      // Everything the background changes is background or the scene's edges: not the scene.
      check(changed - background < 0.03 * background, `the background changes ${changed} pixels, only ${background} of them background`);
      console.log(`background_shows_map: ${compared} pixels compared, ${within} within 2/255, worst ${worst.toFixed(1)}`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  // The background waits for the scene: its request starts after every asset part has
  // arrived, so the first lit frame and the bands never share the connection with it.
  async background_after_scene(browser) {
    const server = await startServer(prtServe, root, webDist);
    try {
      const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
      const events = [];
      // Each part held back a little, so a background fetched alongside the scene would overlap them.
      await page.route('**/parts/**', async (route) => {
        await new Promise((resolve) => setTimeout(resolve, 150));
        await route.continue();
      });
      page.on('requestfinished', (r) => { if (/\/(parts|assets)\//.test(r.url())) events.push({ what: 'part', at: performance.now() }); });
      page.on('request', (r) => { if (r.url().includes('/api/lights/background/')) events.push({ what: 'background', at: performance.now() }); });
      await page.goto(`${server.base}/`);
      await page.waitForFunction(() => window.prtApp && (window.prtApp.error || (window.prtApp.backgroundImage && window.prtApp.ready)),
        null, { timeout: 90000 });
      const parts = events.filter((e) => e.what === 'part'), asked = events.filter((e) => e.what === 'background');
      check(parts.length > 1 && asked.length === 1, `${parts.length} asset parts, ${asked.length} background requests`);
      const lastPart = Math.max(...parts.map((e) => e.at));
      check(asked.length === 1 && asked[0].at >= lastPart, `the background was requested ${(lastPart - asked[0]?.at).toFixed(0)} ms before the last part arrived`);
      // A map change fetches its image only once; the cached one is drawn again at once.
      const again = await page.evaluate(() => {
        window.prtApp.set({ environment: 'white furnace' });
        const furnace = window.prtApp.backgroundImage;
        window.prtApp.set({ environment: 'forest' });
        return [furnace, window.prtApp.backgroundImage];
      });
      check(again[0] === null && again[1] && again[1].environment === 'forest', `furnace then forest: ${JSON.stringify(again)}`);
      check(events.filter((e) => e.what === 'background').length === 1, 'the background was fetched again');
    } finally {
      server.child.kill('SIGTERM');
    }
  },
};

await runCase(caseName, cases, checks);
