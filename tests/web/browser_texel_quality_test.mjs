// What a user of transfer textures looks at first, measured in the page (headless Chromium,
// SwiftShader, a real prt-serve), on small glTF scenes baked here with --texels:
//   texel_seams_in_picture: chart cuts show no line in the rendered picture, neither where one
//     surface continues across a cut (a floor in two charts, under a floating cube's soft
//     shadow) nor at a cube's creases (six face charts, lit so that the faces differ: a face
//     that took its neighbour's transfer over the crease changes by 7 display levels at its
//     edge); the same scenes baked without gutters (--dilation 0) show the lines, so the
//     measure can see them.
//   texel_normal_map_moving_light: a flat quad with a striped normal map, lit by one light on
//     either side: the texels whose mapped normals lean towards the light are the bright ones,
//     and the pattern reverses when the light moves across; the same quad without the map is
//     uniform.
//   texel_sets_render: an asset with texture sets (one mesh instanced twice, one copy under a
//     roof: three atlases) is drawn per texel, every atlas read back in UV space equal to the
//     baker's texels of that atlas, the roofed copy dark and the open one lit.
// Usage: node browser_texel_quality_test.mjs CASE PRT_SERVE PRT_BAKE WEB_DIST WORK_DIR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { makeChecks, startServer, openPage, capture, windowLuminance, runCase } from './browser_harness.mjs';
import { gltfText, stripeQuadGltf, stripeSlope } from './floor_scene_gltf.mjs';
import { merge, quad as lightmapQuad, texturedSceneGltf } from '../cli/texture_sets_gltf.mjs';

const [caseName, prtServe, prtBake, webDist, workDir] = process.argv.slice(2);
const checks = makeChecks();
const { check } = checks;
for (const [what, p] of [['prt-serve', prtServe], ['prt-bake', prtBake], ['web dist', webDist]]) {
  if (!p || !fs.existsSync(p)) {
    console.error(`${what} not found at ${p} (build the native and wasm presets)`);
    process.exit(1);
  }
}
const root = path.join(workDir, 'root');
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(root, { recursive: true });

const ATLAS = 64;  // texels a side; every chart below is laid out on this grid

// A quad part: centre c, unit axes a and b with a x b = its normal, half sizes ha and hb, and
// its chart: the texel rectangle [u0, u1] x [v0, v1] of the atlas, u along b and v along a.
function quad(c, a, b, ha, hb, [u0, u1, v0, v1]) {
  const n = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const part = { positions: [], normals: [], uv: [], indices: [] };
  for (const [sa, sb] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {  // counter-clockwise about n
    part.positions.push(...[0, 1, 2].map((k) => c[k] + sa * ha * a[k] + sb * hb * b[k]));
    part.normals.push(...n);
    part.uv.push((u0 + (u1 - u0) * (sb + 1) / 2) / ATLAS, (v0 + (v1 - v0) * (sa + 1) / 2) / ATLAS);
  }
  part.indices.push(0, 1, 2, 0, 2, 3);
  return part;
}

// The seam scene: the floor [-1.5, 1.5]^2 cut along x = 0 into two charts 8 texels apart
// (0.0625 m a texel), and a cube of side 0.9 floating 0.5 m above it across the cut, each
// face its own 7 x 7 texel chart in a row below the floor's (0.129 m a texel).
const CUBE = { centre: [0.15, 0.95, 0], half: 0.45 };
const FLOOR_TEXEL = 1.5 / 24, CUBE_TEXEL = 0.9 / 7;
const CUBE_FACES = [  // normal, then axes a, b with a x b = normal
  { n: [1, 0, 0], a: [0, 1, 0], b: [0, 0, 1] }, { n: [-1, 0, 0], a: [0, 0, 1], b: [0, 1, 0] },
  { n: [0, 1, 0], a: [0, 0, 1], b: [1, 0, 0] }, { n: [0, -1, 0], a: [1, 0, 0], b: [0, 0, 1] },
  { n: [0, 0, 1], a: [1, 0, 0], b: [0, 1, 0] }, { n: [0, 0, -1], a: [0, 1, 0], b: [1, 0, 0] },
];
function seamSceneGltf() {
  const z = [0, 0, 1], x = [1, 0, 0];
  const floor = { ...merge([quad([-0.75, 0, 0], z, x, 1.5, 0.75, [4, 28, 4, 52]), quad([0.75, 0, 0], z, x, 1.5, 0.75, [36, 60, 4, 52])]),
    color: [0.7, 0.7, 0.7, 1] };
  const cube = { ...merge(CUBE_FACES.map(({ n, a, b }, k) => quad(CUBE.centre.map((c, i) => c + CUBE.half * n[i]), a, b, CUBE.half, CUBE.half,
    [3 + 10 * k, 10 + 10 * k, 55, 62]))), color: [0.8, 0.8, 0.8, 1] };
  return gltfText([floor, cube]);
}

// The normal-map scene (stripeQuadGltf): the quad [-1, 1]^2 at y = 0 over the whole 64 x 64
// atlas, its normal map stripes leaning along x (tangent-space normal normalize(s(u), 0, 1),
// s = stripeSlope, up to 31 degrees).
const slope = stripeSlope;

function bake(name, gltf, extra = []) {
  const scene = path.join(workDir, `${name}.gltf`);
  fs.writeFileSync(scene, gltf);
  const t0 = Date.now();
  execFileSync(prtBake, [scene, '-o', path.join(root, `${name}.prt`), '--texels', '--texture-size', String(ATLAS), '--samples', '256',
    '--order', '4', '--bounces', '1', '--passes', 'shadowed,interreflected', '--name', name, '--quiet',
    // One atlas, the layout above (auto would give the cube, half the floor's texel density,
    // an atlas of its own).
    '--texture-sets', 'scene', '--unwrap', 'never', ...extra]);
  console.log(`bake ${name}: ${((Date.now() - t0) / 1000).toFixed(1)} s`);
}

const FURNACE = '?env=white%20furnace';
const VIEWPORT = { width: 960, height: 720 };
const mean = (xs) => xs.reduce((s, x) => s + x, 0) / xs.length;

// Luminance (8-bit display units) of the texel picture of `scene` at world points, after
// orbiting by `orbit` radians; also the eye, for which faces are visible.
async function pictureAt(browser, base, scene, orbit, pointsOf) {
  const { page, consoleErrors } = await openPage(browser, `${base}/${FURNACE}&scene=${scene}&source=texel`, { viewport: VIEWPORT });
  await page.evaluate(([dx, dy]) => window.prtApp.orbit(dx, dy), orbit);
  // One light high on the eye's side, no environment: the faces of the cube differ, so a face
  // carrying its neighbour's transfer over their crease would show it.
  const img = await capture(page, { background: false, environment: null,
    lights: [{ shape: 'sphere', position: [2.5, 3, 2], radius: 0.3, intensity: 150 }] });
  const eye = await page.evaluate(() => window.prtApp.eye);
  const points = pointsOf(eye);
  const pixels = await page.evaluate((pts) => pts.map((p) => window.prtApp.project(p)), points.flat());
  const state = await page.evaluate(() => ({ error: window.prtApp.error, source: window.prtApp.source }));
  check(state.error === null && state.source === 'texel', `${scene}: error ${state.error}, source ${state.source}`);
  check(consoleErrors.length === 0, `${scene}: console errors: ${consoleErrors.join(' | ')}`);
  await page.screenshot({ path: path.join(workDir, `${scene}.png`) });
  await page.close();
  const lum = pixels.map((p) => windowLuminance(img, p, 0));
  const out = [];
  for (let i = 0, k = 0; i < points.length; k += points[i].length, i++) out.push(lum.slice(k, k + points[i].length));
  return out;
}

// World points for the seam measures, as groups of [near, inside] pairs ([left, right] of the
// cut for the floor). Floor: along the cut x = 0 in front of the cube, a quarter texel either
// side of it, and a texel and a quarter out. Cube: on every face turned to the eye, along each
// of its four edges, a quarter texel inside and a texel and a half inside.
function seamPoints(eye) {
  const floor = [];
  for (let k = 0; k < 12; k++) {
    const z = 0.6 + 0.8 * k / 11, q = 0.25 * FLOOR_TEXEL, far = 1.25 * FLOOR_TEXEL;
    floor.push([-q, 0, z], [q, 0, z], [-far, 0, z], [far, 0, z]);
  }
  const cube = [];
  for (const { n, a, b } of CUBE_FACES) {
    const centre = CUBE.centre.map((c, i) => c + CUBE.half * n[i]);
    if ([0, 1, 2].reduce((s, i) => s + n[i] * (eye[i] - centre[i]), 0) <= 0) continue;  // turned away
    for (const [axis, along] of [[a, b], [b, a]])
      for (const side of [-1, 1])
        for (const t of [-0.5, 0, 0.5]) {
          const at = (inset) => centre.map((c, i) => c + side * (CUBE.half - inset) * axis[i] + t * CUBE.half * along[i]);
          cube.push(at(0.25 * CUBE_TEXEL), at(1.5 * CUBE_TEXEL));
        }
  }
  return [floor, cube];
}

// Seam measures from pictureAt's luminances: on the floor cut, the step across it (|right -
// left|) and the dip of a line along it (the mean of the two outer points minus the mean of
// the two inner ones); at the cube's edges, |edge - inside|. Means over the points.
function seamMeasures([floor, cube]) {
  const step = [], dip = [], edge = [];
  for (let i = 0; i < floor.length; i += 4) {
    step.push(Math.abs(floor[i + 1] - floor[i]));
    dip.push((floor[i + 2] + floor[i + 3]) / 2 - (floor[i] + floor[i + 1]) / 2);
  }
  for (let i = 0; i < cube.length; i += 2) edge.push(Math.abs(cube[i] - cube[i + 1]));
  return { step: mean(step), dip: mean(dip), edge: mean(edge), edges: edge.length, floorLevel: mean(floor) };
}

// Pearson correlation of two equal-length arrays (0 when either is constant).
function correlation(xs, ys) {
  const mx = mean(xs), my = mean(ys);
  let sxy = 0, sxx = 0, syy = 0;
  for (let i = 0; i < xs.length; i++) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) ** 2;
    syy += (ys[i] - my) ** 2;
  }
  return sxx > 0 && syy > 0 ? sxy / Math.sqrt(sxx * syy) : 0;
}

const cases = {
  async texel_seams_in_picture(browser) {
    bake('seams', seamSceneGltf());
    bake('seams-bare', seamSceneGltf(), ['--dilation', '0']);
    const server = await startServer(prtServe, root, webDist);
    try {
      // A quarter turn of yaw and a little more pitch show three faces of the cube and its
      // shadow's side of the floor cut.
      const orbit = [0.5, 0.25];
      const good = seamMeasures(await pictureAt(browser, server.base, 'seams', orbit, seamPoints));
      const bare = seamMeasures(await pictureAt(browser, server.base, 'seams-bare', orbit, seamPoints));
      const show = (m) => `floor cut: step ${m.step.toFixed(2)}, line dip ${m.dip.toFixed(2)} (floor level ${m.floorLevel.toFixed(0)}); ` +
        `cube edges: |edge - inside| ${m.edge.toFixed(2)} over ${m.edges} points`;
      console.log(`with gutters (default): ${show(good)}`);
      console.log(`without gutters (--dilation 0): ${show(bare)}`);
      check(good.edges >= 3 * 12, `only ${good.edges / 12} cube faces are turned to the eye`);
      check(good.floorLevel > 40, `the floor at the cut is dark (${good.floorLevel.toFixed(0)}): nothing to measure`);
      // In 8-bit display units. One level is the picture's quantisation; the soft shadow's own
      // gradient over a quarter texel is below it.
      check(good.step <= 1.0 && Math.abs(good.dip) <= 1.0,
        `a line at the floor's chart cut: step ${good.step.toFixed(2)}, dip ${good.dip.toFixed(2)} display levels (want <= 1)`);
      check(good.edge <= 1.5, `the cube's faces change by ${good.edge.toFixed(2)} display levels within a texel of their edges (want <= 1.5)`);
      // The measure sees lines where there are some: without gutters the bilinear filter
      // blends the empty background in at every chart edge.
      check(bare.dip > 10 * Math.max(1, Math.abs(good.dip)), `without gutters the floor cut's dip is only ${bare.dip.toFixed(2)}`);
      check(bare.edge > 10 * Math.max(1, good.edge), `without gutters the cube's edges change by only ${bare.edge.toFixed(2)}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async texel_normal_map_moving_light(browser) {
    bake('stripes', stripeQuadGltf(ATLAS, true));
    bake('stripes-flat', stripeQuadGltf(ATLAS, false));
    const server = await startServer(prtServe, root, webDist);
    try {
      // Per texel in UV space: the shadowed pass's radiance (luminance) under one sphere light
      // low on either side, environment off; and the stripe's slope at the texel.
      const measure = async (scene) => {
        const { page, consoleErrors } = await openPage(browser, `${server.base}/?scene=${scene}&source=texel`);
        const out = {};
        for (const [side, x] of [['+x', 3], ['-x', -3]]) {
          await capture(page, { environment: null, mode: 'shadowed', lights: [{ shape: 'sphere', position: [x, 1.2, 0], radius: 0.3, intensity: 40 }] });
          const r = await page.evaluate(() => {
            const { width, height, data } = window.prtApp.texelAtlasRadiance('shadowed', 0);
            const lum = [], slopes = [];
            for (let y = 0; y < height; y++)
              for (let x = 0; x < width; x++) {
                const i = 4 * (y * width + x);
                if (data[i + 3] !== 1) continue;
                lum.push(0.2126 * data[i] + 0.7152 * data[i + 1] + 0.0722 * data[i + 2]);
                slopes.push((x + 0.5) / width);
              }
            return { lum, u: slopes };
          });
          out[side] = { lum: r.lum, slope: r.u.map(slope) };
        }
        check(consoleErrors.length === 0, `${scene}: console errors: ${consoleErrors.join(' | ')}`);
        await page.close();
        return out;
      };
      const mapped = await measure('stripes'), flat = await measure('stripes-flat');
      const spread = (xs) => { const m = mean(xs); return Math.sqrt(mean(xs.map((x) => (x - m) ** 2))) / m; };
      for (const side of ['+x', '-x']) {
        const { lum, slope: s } = mapped[side];
        const r = correlation(lum, s), contrast = spread(lum), flatContrast = spread(flat[side].lum);
        console.log(`light at ${side}: ${lum.length} texels, correlation of radiance with the stripes' slope ${r.toFixed(3)}, ` +
          `relative spread ${contrast.toFixed(3)} (without the map ${flatContrast.toExponential(1)})`);
        check(lum.length > 0.9 * ATLAS * ATLAS, `light at ${side}: only ${lum.length} texels drawn`);
        // Towards the light at +x the normals leaning +x (slope > 0) are the bright ones.
        check(side === '+x' ? r > 0.9 : r < -0.9, `light at ${side}: correlation ${r.toFixed(3)} of radiance with the slope`);
        check(contrast > 0.1, `light at ${side}: the stripes change the radiance by only ${(100 * contrast).toFixed(1)} %`);
        check(flatContrast < 0.01, `light at ${side}: the quad without a normal map varies by ${(100 * flatContrast).toFixed(2)} %`);
      }
    } finally {
      server.child.kill('SIGTERM');
    }
  },

  async texel_sets_render(browser) {
    // The scene of bake_cli_test's texture_sets case: a 1 m patch instanced at x = -3 (open) and
    // x = 3 (under a roof 0.25 m up), each object its own atlas at 32 texels a metre.
    const patch = lightmapQuad([-0.5, 0, -0.5], [0, 0, 1], [1, 0, 0], [0.1, 0.1, 0.9, 0.9]);
    const roof = lightmapQuad([-1.5, 0.25, -1.5], [3, 0, 0], [0, 0, 3], [0.1, 0.1, 0.9, 0.9]);
    const scene = path.join(workDir, 'sets.gltf'), asset = path.join(root, 'sets.prt');
    fs.writeFileSync(scene, texturedSceneGltf([patch, roof], [
      { mesh: 0, translation: [-3, 0, 0], name: 'open' }, { mesh: 0, translation: [3, 0, 0], name: 'roofed' }, { mesh: 1, translation: [3, 0, 0], name: 'roof' },
    ]));
    execFileSync(prtBake, [scene, '-o', asset, '--samples', '256', '--order', '3', '--texels', '--texels-per-unit', '32', '--unwrap', 'never',
      '--passes', 'shadowed', '--name', 'sets', '--quiet']);
    const reference = JSON.parse(execFileSync(prtBake, ['shade', asset, '--texels', '--light', 'constant', '--pass', 'shadowed', '--json'],
      { encoding: 'utf8', maxBuffer: 1 << 28 }));
    const server = await startServer(prtServe, root, webDist);
    try {
      const { page, consoleErrors } = await openPage(browser, `${server.base}/${FURNACE}&scene=sets&source=texel`);
      const state = await page.evaluate(() => ({ error: window.prtApp.error, source: window.prtApp.source, atlases: window.prtApp.atlases }));
      check(state.error === null && state.source === 'texel', `error ${state.error}, source ${state.source}`);
      const sizes = (state.atlases ?? []).map((a) => `${a.width}x${a.height}`).join(', ');
      check(sizes === reference.atlases.map((a) => `${a.width}x${a.height}`).join(', ') && reference.atlases.length === 3,
        `the page has atlases ${sizes}; the asset ${JSON.stringify(reference.atlases)}`);
      const means = [];
      for (let a = 0; a < reference.atlases.length; a++) {
        const gpu = await page.evaluate((atlas) => {
          const { width, data } = window.prtApp.texelAtlasRadiance('shadowed', atlas);
          return { width, data: Array.from(data) };
        }, a);
        const texels = reference.texels.filter((t) => t.atlas === a);
        let compared = 0, bad = 0, sum = 0, firstBad = '';
        for (const t of texels) {
          const i = 4 * (t.y * gpu.width + t.x);
          if (gpu.data[i + 3] !== 1) continue;  // centre outside every triangle
          compared++;
          sum += t.radiance[0];
          const error = Math.abs(gpu.data[i] - t.radiance[0]);
          if (!(error <= 1e-3 * Math.abs(t.radiance[0]) + 1e-4)) {
            if (!bad) firstBad = `texel (${t.x}, ${t.y}): GPU ${gpu.data[i]}, baker ${t.radiance[0]}`;
            bad++;
          }
        }
        means.push(sum / compared);
        console.log(`atlas ${a} (${reference.atlases[a].width}x${reference.atlases[a].height}): ${compared} of ${texels.length} texels compared, mean radiance ${(sum / compared).toFixed(4)}`);
        check(compared > 0.5 * texels.length, `atlas ${a}: only ${compared} of ${texels.length} texels drawn in UV space`);
        check(bad === 0, `atlas ${a}: ${bad} texels beyond 1e-3 relative + 1e-4 (${firstBad})`);
      }
      check(means[0] > 0.6 && means[1] < 0.2 * means[0], `the open copy's mean radiance ${means[0]}, the roofed copy's ${means[1]}`);
      check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
    } finally {
      server.child.kill('SIGTERM');
    }
  },
};

await runCase(caseName, cases, checks);
