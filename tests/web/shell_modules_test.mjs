// The page's pure JS modules under Node (no browser): the OBJ reader, the built-in torus,
// light checking and packing, the ray geometry used to pick and drag lights, each against
// independent references (hand-worked files, brute-force sampling), and the stream loader's
// part selection (texel parts skipped) against a stand-in client and server.
// Usage: node shell_modules_test.mjs
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const shell = path.join(path.dirname(fileURLToPath(import.meta.url)), '../../web/shell');
const load = (name) => import(pathToFileURL(path.join(shell, name)).href);
const { parseObj, normaliseToUnitRadius, meshRadius } = await load('obj_loader.js');
const { torusMesh } = await load('torus_mesh.js');
const { normaliseLight, normaliseLights, packLights, boundingRadius, FLOATS_PER_LIGHT } = await load('lights.js');
const { randomLights, seededRandom } = await load('random_lights.js');
const { raySphere, pickLight, rayHorizontalPlane, worldPerPixel, along } = await load('light_picking.js');
const { streamAsset, checkParts } = await load('stream_loader.js');
const { encodePermalink, decodePermalink, float32Text } = await load('permalink.js');

const failures = [];
let checks = 0;
const check = (ok, message) => {
  checks++;
  if (!ok) failures.push(message);
  return ok;
};
const throwsMatching = (fn, pattern, what) => {
  try {
    fn();
  } catch (e) {
    return check(pattern.test(e.message), `${what}: message '${e.message}' does not match ${pattern}`);
  }
  return check(false, `${what}: no error`);
};
const close = (a, b, tol = 1e-6) => Math.abs(a - b) <= tol;

// ---- OBJ: a quad and a pentagon, with normals/texcoords, comments, negative indices
{
  const text = [
    '# a unit square in z = 0 and a pentagon',
    'mtllib ignored.mtl', 'o thing', 'vn 0 0 1', 'vt 0 0',
    'v 0 0 0', 'v 1 0 0', 'v 1 1 0', 'v 0 1 0',
    'f 1/1/1 2/1/1 3/1/1 4/1/1',
    'v 2 0 0 1.0', 'v 3 0 0', 'v 3.5 1 0', 'v 2.5 2 0', 'v 1.5 1 0',
    'g part', 'usemtl red', 's off',
    'f -5 -4 -3 -2 -1  # relative to the last vertex',
  ].join('\r\n');
  const mesh = parseObj(text);
  check(mesh.positions.length === 27, `OBJ: ${mesh.positions.length / 3} vertices, expected 9`);
  // Quad -> 2 triangles, pentagon -> 3, fanned from the first corner.
  check(JSON.stringify(Array.from(mesh.indices)) === JSON.stringify([0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 4, 7, 8]),
    `OBJ indices: ${Array.from(mesh.indices)}`);
  // Fan triangulation of a convex polygon keeps its area: 1 + pentagon (shoelace).
  let area = 0;
  for (let t = 0; t < mesh.indices.length; t += 3) {
    const [a, b, c] = [0, 1, 2].map((k) => mesh.indices[t + k]);
    const p = (i) => [mesh.positions[3 * i], mesh.positions[3 * i + 1]];
    const [pa, pb, pc] = [p(a), p(b), p(c)];
    area += 0.5 * Math.abs((pb[0] - pa[0]) * (pc[1] - pa[1]) - (pc[0] - pa[0]) * (pb[1] - pa[1]));
  }
  const pent = [[2, 0], [3, 0], [3.5, 1], [2.5, 2], [1.5, 1]];
  let shoelace = 0;
  for (let i = 0; i < 5; i++) shoelace += pent[i][0] * pent[(i + 1) % 5][1] - pent[(i + 1) % 5][0] * pent[i][1];
  check(close(area, 1 + Math.abs(shoelace) / 2, 1e-5), `OBJ triangulated area ${area}, expected ${1 + Math.abs(shoelace) / 2}`);

  // Normalisation: bounding-box centre to the origin, farthest used vertex at distance 1.
  const unit = normaliseToUnitRadius(mesh.positions, mesh.indices);
  check(close(meshRadius(unit, mesh.indices), 1, 1e-6), `normalised radius ${meshRadius(unit, mesh.indices)}`);
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < 9; v++) for (let a = 0; a < 3; a++) { lo[a] = Math.min(lo[a], unit[3 * v + a]); hi[a] = Math.max(hi[a], unit[3 * v + a]); }
  check([0, 1, 2].every((a) => close(lo[a] + hi[a], 0, 1e-6)), `normalised box not centred: ${lo} .. ${hi}`);
  // The box of the input is [0, 3.5] x [0, 2] x 0: centre (1.75, 1), farthest corner (0,0) or (3.5,0)...
  const expectedRadius = Math.max(...[[0, 0], [1, 0], [1, 1], [0, 1], ...pent].map(([x, y]) => Math.hypot(x - 1.75, y - 1)));
  check(close(unit[3 * 1] - unit[0], 1 / expectedRadius, 1e-6), 'normalisation scale is not 1/(distance of the farthest vertex)');

  // Bad files: clear messages with line numbers, never a crash.
  throwsMatching(() => parseObj('v 0 0 0\nv 1 0 0\nv 0 1 0\n'), /no faces/, 'point cloud');
  throwsMatching(() => parseObj('{"not": "an obj"}'), /no vertices/, 'JSON file');
  throwsMatching(() => parseObj(''), /no vertices/, 'empty file');
  throwsMatching(() => parseObj('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n'), /line 4: vertex index 4 is out of range/, 'index past the end');
  throwsMatching(() => parseObj('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n'), /line 4: vertex index 0/, 'index 0');
  throwsMatching(() => parseObj('v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n'), /line 4: vertex index -4/, 'negative index too far back');
  throwsMatching(() => parseObj('v 0 0 0\nv 1 nan 0\n'), /line 2: vertex coordinates are not finite/, 'NaN vertex');
  throwsMatching(() => parseObj('v 0 0\n'), /line 1: a vertex needs x y z/, 'short vertex');
  throwsMatching(() => parseObj('v 0 0 0\nv 1 0 0\nf 1 2\n'), /line 3: a face needs at least 3/, 'two-corner face');
  throwsMatching(() => parseObj('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 2\n'), /'x' is not a vertex index/, 'non-numeric index');
  throwsMatching(() => normaliseToUnitRadius(new Float32Array([1, 1, 1, 1, 1, 1, 1, 1, 1]), [0, 1, 2]), /no extent/, 'degenerate mesh');
}

// ---- the torus: outer radius 1, every edge shared by exactly two triangles (closed), consistent winding
{
  const { positions, indices } = torusMesh(24, 10, 0.3);
  check(positions.length === 24 * 10 * 3 && indices.length === 24 * 10 * 6, 'torus sizes');
  check(close(meshRadius(positions, indices), 1, 1e-6), `torus outer radius ${meshRadius(positions, indices)}`);
  let minR = Infinity;
  for (let v = 0; v < positions.length / 3; v++) minR = Math.min(minR, Math.hypot(positions[3 * v], positions[3 * v + 2]));
  check(close(minR, 0.4, 1e-6), `torus inner radius ${minR}, expected 0.4`);
  const directed = new Map();
  for (let t = 0; t < indices.length; t += 3) {
    for (let k = 0; k < 3; k++) {
      const key = `${indices[t + k]}>${indices[t + (k + 1) % 3]}`;
      directed.set(key, (directed.get(key) || 0) + 1);
    }
  }
  let manifold = true;
  for (const [key, n] of directed) {
    const [a, b] = key.split('>');
    if (n !== 1 || directed.get(`${b}>${a}`) !== 1) manifold = false;
  }
  check(manifold, 'torus is not a closed, consistently wound surface');
}

// ---- light checking and packing
{
  const meshes = new Map([['torus', { id: 7, radius: 1 }], [3, { id: 3, radius: 2 }]]);
  const sphere = normaliseLight({ shape: 'sphere', position: [1, 2, 3], radius: 0.5 }, 0, meshes);
  check(JSON.stringify(sphere) === JSON.stringify({ shape: 'sphere', position: [1, 2, 3], color: [1, 1, 1], intensity: 1, radius: 0.5 }),
    `sphere defaults: ${JSON.stringify(sphere)}`);
  const disc = normaliseLight({ shape: 'disc', position: [0, 1, 0], radius: 0.2, normal: [0, 0, -2], color: [1, 0.5, 0], intensity: 3 }, 1, meshes);
  check(JSON.stringify(disc.normal) === JSON.stringify([0, 0, -1]), `disc normal not normalised: ${disc.normal}`);
  const rect = normaliseLight({ shape: 'rect', position: [0, 1, 0], size: [0.4, 0.3] }, 2, meshes);
  check(JSON.stringify(rect.normal) === JSON.stringify([0, -1, 0]), `rect default normal ${rect.normal}`);
  const torus = normaliseLight({ shape: 'mesh', position: [0, 1, 0], mesh: 'torus', scale: 0.25 }, 3, meshes);
  const custom = normaliseLight({ shape: 'mesh', position: [0, 1, 0], mesh: 3 }, 4, meshes);
  check(custom.scale === 1, 'mesh scale defaults to 1');
  const flat = packLights([sphere, disc, rect, torus, custom], meshes);
  check(flat.length === 5 * FLOATS_PER_LIGHT, `packed length ${flat.length}`);
  const row = (i) => Array.from(flat.subarray(i * 16, i * 16 + 16));
  check(JSON.stringify(row(0)) === JSON.stringify([0, 1, 2, 3, 0.5, 0, 0, -1, 0, 1, 1, 1, 1, 0, 0, 0]), `sphere row ${row(0)}`);
  check(JSON.stringify(row(1).map((x) => +x.toFixed(6))) === JSON.stringify([1, 0, 1, 0, 0.2, 0, 0, 0, -1, 1, 0.5, 0, 3, 0, 0, 0]), `disc row ${row(1)}`);
  check(JSON.stringify(row(2).map((x) => +x.toFixed(6))) === JSON.stringify([2, 0, 1, 0, 0.4, 0.3, 0, -1, 0, 1, 1, 1, 1, 0, 0, 0]), `rect row ${row(2)}`);
  check(row(3)[0] === 3 && row(3)[4] === 0.25 && row(3)[13] === 7, `torus row ${row(3)}`);
  check(row(4)[13] === 3 && row(4)[4] === 1, `custom mesh row ${row(4)}`);
  check(close(boundingRadius(rect, meshes), 0.25, 1e-9) && boundingRadius(torus, meshes) === 0.25 && boundingRadius(custom, meshes) === 2,
    'bounding radii');

  const bad = [
    [{ shape: 'cone', position: [0, 0, 0] }, /lights\[0\]\.shape must be one of sphere, disc, rect, mesh/],
    [{ shape: 'sphere', position: [0, 0, 0], radius: -1 }, /lights\[0\]\.radius must be a finite number > 0, got -1/],
    [{ shape: 'sphere', position: [0, 0, 0], radius: 0 }, /radius must be a finite number > 0/],
    [{ shape: 'sphere', position: [0, NaN, 0], radius: 1 }, /lights\[0\]\.position\[1\] must be a finite number/],
    [{ shape: 'sphere', position: [0, 0], radius: 1 }, /position must hold 3 numbers/],
    [{ shape: 'sphere', position: 'here', radius: 1 }, /position must be an array of 3 numbers/],
    [{ shape: 'sphere', radius: 1 }, /position is required/],
    [{ shape: 'sphere', position: [0, 0, 0] }, /radius is required/],
    [{ shape: 'sphere', position: [0, 0, 0], radius: 1, size: [1, 1] }, /lights\[0\]\.size is not a field of a sphere light/],
    [{ shape: 'sphere', position: [0, 0, 0], radius: 1, intensity: -2 }, /intensity must be a finite number >= 0/],
    [{ shape: 'sphere', position: [0, 0, 0], radius: 1, intensity: '3' }, /intensity must be a finite number >= 0/],
    [{ shape: 'sphere', position: [0, 0, 0], radius: 1, color: [1, -1, 0] }, /color\[1\] must be >= 0/],
    [{ shape: 'disc', position: [0, 0, 0], radius: 1, normal: [0, 0, 0] }, /normal must not be the zero vector/],
    [{ shape: 'rect', position: [0, 0, 0], size: [1, Infinity] }, /size\[1\] must be a finite number/],
    [{ shape: 'rect', position: [0, 0, 0], size: [1, 0] }, /size\[1\] must be a finite number > 0/],
    [{ shape: 'mesh', position: [0, 0, 0], mesh: 99 }, /lights\[0\]\.mesh 99 is unknown/],
    [{ shape: 'mesh', position: [0, 0, 0] }, /mesh is required/],
    [null, /lights\[0\] must be an object/],
  ];
  for (const [spec, pattern] of bad) throwsMatching(() => normaliseLight(spec, 0, meshes), pattern, `bad light ${JSON.stringify(spec)}`);
  throwsMatching(() => normaliseLights({ shape: 'sphere' }, meshes), /lights must be an array/, 'not an array');
  throwsMatching(() => normaliseLights([sphere, { ...sphere, radius: 'big' }], meshes), /lights\[1\]\.radius/, 'second light named');
}

// ---- ray geometry against brute force
{
  let seed = 12345;
  const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  let agree = 0, total = 0;
  for (let trial = 0; trial < 300; trial++) {
    const origin = [random() * 4 - 2, random() * 4 - 2, random() * 4 - 2];
    let dir = [random() - 0.5, random() - 0.5, random() - 0.5];
    const n = Math.hypot(...dir);
    dir = dir.map((x) => x / n);
    const centre = [random() * 2 - 1, random() * 2 - 1, random() * 2 - 1];
    const radius = 0.2 + random();
    const ray = { origin, dir };
    const t = raySphere(ray, centre, radius);
    // Brute force: march the ray in small steps and find the first point inside the sphere.
    let first = null;
    for (let s = 0; s <= 10; s += 1e-3) {
      const p = along(ray, s);
      if (Math.hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]) <= radius) { first = s; break; }
    }
    total++;
    if ((t === null && first === null) || (t !== null && first !== null && Math.abs(t - first) < 2e-3)) agree++;
  }
  check(agree === total, `raySphere disagrees with ray marching in ${total - agree} of ${total} cases`);

  const ray = { origin: [0, 1, 5], dir: [0, 0, -1] };
  check(pickLight(ray, [[0, 1, 0], [0, 1, 2], [3, 1, 0]], [0.5, 0.5, 0.5], 0.001) === 1, 'pickLight should pick the nearer of two lights on the ray');
  check(pickLight(ray, [[3, 1, 0]], [0.5], 0.001) === -1, 'pickLight picked a light off the ray');
  // A tiny light 0.06 off the ray at distance 5 is picked when 8 pixels there are wider than that.
  check(pickLight(ray, [[0.06, 1, 0]], [0.001], 0.002) === 0 && pickLight(ray, [[0.06, 1, 0]], [0.001], 0.001) === -1,
    'the minimum on-screen pick size is not applied as stated');

  const down = { origin: [1, 3, 1], dir: [0.6, -0.8, 0] };
  const hit = rayHorizontalPlane(down, 1);
  check(hit && close(hit[1], 1) && close(hit[0], 1 + 1.5), `rayHorizontalPlane: ${hit}`);
  check(rayHorizontalPlane({ origin: [0, 3, 0], dir: [1, 0, 0] }, 1) === null, 'a parallel ray must not hit the plane');
  check(rayHorizontalPlane({ origin: [0, 3, 0], dir: [0, 1, 0] }, 1) === null, 'a plane behind the ray must not be hit');
  const a = 0.01;
  const wpp = worldPerPixel({ origin: [0, 0, 0], dir: [0, 0, -1] }, { origin: [0, 0, 0], dir: [Math.sin(a), 0, -Math.cos(a)] }, [0, 0, -10]);
  check(close(wpp, 10 * Math.tan(a), 1e-9), `worldPerPixel ${wpp}`);
}

// Seeded random lights: reproducible, valid, in front of the centre, bad counts refused.
{
  const a = randomLights(50, [1, 2, 3], 2, 9), b = randomLights(50, [1, 2, 3], 2, 9), c = randomLights(50, [1, 2, 3], 2, 10);
  check(JSON.stringify(a) === JSON.stringify(b) && JSON.stringify(a) !== JSON.stringify(c), 'randomLights: same seed, same lights; other seed, other lights');
  let ok = true;
  try { normaliseLights(a, new Map()); } catch (e) { ok = false; check(false, `randomLights gave an invalid light: ${e.message}`); }
  check(ok && a.length === 50 && ['sphere', 'disc', 'rect'].every((s) => a.some((l) => l.shape === s)), 'randomLights: 50 lights of all three shapes');
  for (const l of a) {
    const rel = l.position.map((x, k) => x - [1, 2, 3][k]), d = Math.hypot(...rel);
    if (!check(d >= 1.2 - 1e-9 && d <= 2.4 + 1e-9 && rel[1] > 0, `random light at distance ${d}, height ${rel[1]}`)) break;
    if (l.normal && !check(l.normal.reduce((s, x, k) => s + x * rel[k], 0) < 0, 'a one-sided random light faces away from the centre')) break;
  }
  const r = seededRandom(3);
  const xs = Array.from({ length: 1000 }, r);
  check(xs.every((x) => x >= 0 && x < 1) && Math.abs(xs.reduce((s, x) => s + x, 0) / 1000 - 0.5) < 0.05, 'seededRandom: uniform on [0, 1)');
  for (const bad of [-1, 1.5, 2000]) {
    let threw = false;
    try { randomLights(bad, [0, 0, 0], 1); } catch (e) { threw = /count/.test(e.message); }
    check(threw, `randomLights(${bad}) should throw naming the count`);
  }
}

// ---- Stream loader: an asset with vertex and texel passes fetches the atlas sections with the
// geometry, then streams the displayed domain's pass first and the other domain's after it
// (streamPass for vertex passes, streamTexelPass for texel passes, band by band); a texel-only
// asset streams its texel passes; unknown domains are refused.
{
  const kinds = { unshadowed: 'U', shadowed: 'S', interreflected: 'I' };  // stand-ins for the embind enum values
  const domains = { vertex: 'V', texel: 'T' };
  const parts = [];
  const add = (size, fields) => parts.push({ offset: parts.reduce((s, p) => s + p.size, 0), size, url: `/parts/${parts.length}`, ...fields });
  add(64, { kind: 'head' });
  add(32, { kind: 'section', section: 0 });                                                     // geometry
  add(48, { kind: 'section', section: 1, domain: 'texel' });                                    // atlas uv
  add(16, { kind: 'section', section: 2, domain: 'texel' });                                    // coverage
  add(80, { kind: 'section', section: 3, pass: 'shadowed', domain: 'vertex' });                 // float32 vertex pass
  add(24, { kind: 'transfer-head', section: 4, pass: 'shadowed', domain: 'texel' });
  add(40, { kind: 'transfer-band', section: 4, pass: 'shadowed', domain: 'texel', band: 0 });
  add(40, { kind: 'transfer-band', section: 4, pass: 'shadowed', domain: 'texel', band: 1 });
  const entry = { name: 'mixed', bytes: parts.reduce((s, p) => s + p.size, 0), parts };
  checkParts(parts, entry.bytes);
  throwsMatching(() => checkParts([parts[0], { ...parts[1], size: entry.bytes - 64, domain: 'pixel' }], entry.bytes),
                 /unknown domain 'pixel'/, 'checkParts on a bad domain');
  let fetched = [];
  globalThis.fetch = async (url) => {
    fetched.push(url);
    const part = parts.find((p) => p.url === url);
    return { ok: true, status: 200, statusText: 'OK', arrayBuffer: async () => new Uint8Array(part.size).fill(7).buffer };
  };
  let streamed = [];
  let buffer = null, source = domains.vertex, geometryAt = -1;
  const app = {
    reserveStream: (n) => { buffer = new Uint8Array(n); return true; },
    streamBuffer: () => buffer,
    streamGeometry: () => { geometryAt = fetched.length; return ''; },
    mode: () => kinds.shadowed,
    source: () => source,
    hasGlossy: () => false,
    hasTexelGlossy: () => false,
    streamVisibilityPass: (bands) => { streamed.push(['visibility', bands]); return ''; },
    hasAnyPass: () => true,
    streamPass: (k, bands) => { streamed.push(['vertex', k, bands]); return ''; },
    streamTexelPass: (k, bands) => { streamed.push(['texel', k, bands]); return ''; },
    streamGlossyPass: () => 'no glossy pass here',
    loadedBands: () => 0,
    texelBands: () => 0,
    endStream: () => {},
  };
  const settle = () => new Promise((resolve) => setTimeout(resolve, 10));  // the background part of the stream
  const progress = {};
  await streamAsset(app, entry, { kinds, domains, progress });
  await settle();
  const atlasUrls = parts.filter((p) => p.domain === 'texel' && !p.pass).map((p) => p.url);
  check(atlasUrls.every((u) => fetched.indexOf(u) >= 0 && fetched.indexOf(u) < geometryAt), `atlas sections not fetched before the geometry step: ${fetched.join(' ')}`);
  check(fetched.length === parts.length, `fetched ${fetched.length} of ${parts.length} parts: ${fetched.join(' ')}`);
  check(JSON.stringify(streamed) === JSON.stringify([['vertex', kinds.shadowed, 0], ['texel', kinds.shadowed, 1], ['texel', kinds.shadowed, 2]]),
        `vertex displayed, passes streamed: ${JSON.stringify(streamed)}`);
  check(progress.bytesTotal === entry.bytes && progress.bytesReceived === entry.bytes, `progress ${progress.bytesReceived} of ${progress.bytesTotal}, file ${entry.bytes}`);
  // The texel domain displayed: its pass goes first and the first picture waits for its band 0.
  source = domains.texel;
  streamed = [];
  fetched = [];
  await streamAsset(app, entry, { kinds, domains });
  check(streamed.length > 0 && streamed[0][0] === 'texel', `texel displayed, first pass streamed: ${JSON.stringify(streamed)}`);
  await settle();
  check(streamed.some(([d]) => d === 'vertex'), `texel displayed, the vertex pass never streamed: ${JSON.stringify(streamed)}`);
  // Only texel passes: nothing else to stream, the texel pass gives the first picture.
  const texelOnly = parts.filter((p) => p.pass !== 'shadowed' || p.domain === 'texel');
  let offset = 0;
  const only = texelOnly.map((p) => { const q = { ...p, offset }; offset += p.size; return q; });
  streamed = [];
  await streamAsset(app, { name: 'texel-only', bytes: offset, parts: only }, { kinds, domains });
  await settle();
  check(JSON.stringify(streamed) === JSON.stringify([['texel', kinds.shadowed, 1], ['texel', kinds.shadowed, 2]]), `texel-only: ${JSON.stringify(streamed)}`);
  // A TPFL visibility pass (form 'visibility') streams band by band after the displayed pass,
  // through streamVisibilityPass; it never counts as the displayed pass.
  const withVisibility = [...only];
  for (const [kind, band] of [['transfer-head', undefined], ['transfer-band', 0], ['transfer-band', 1]]) {
    withVisibility.push({ offset, size: 8, url: `/parts/v${band ?? 'h'}`, kind, section: 9, pass: 'shadowed', form: 'visibility', domain: 'texel', ...(band === undefined ? {} : { band }) });
    offset += 8;
  }
  const plainFetch = globalThis.fetch;
  globalThis.fetch = async (url) => {
    const part = withVisibility.find((p) => p.url === url);
    return { ok: true, status: 200, statusText: 'OK', arrayBuffer: async () => new Uint8Array(part.size).fill(7).buffer };
  };
  streamed = [];
  await streamAsset(app, { name: 'texel-glossy', bytes: offset, parts: withVisibility }, { kinds, domains });
  await settle();
  globalThis.fetch = plainFetch;
  check(JSON.stringify(streamed) === JSON.stringify([['texel', kinds.shadowed, 1], ['texel', kinds.shadowed, 2], ['visibility', 1], ['visibility', 2]]),
        `texel pass then visibility pass: ${JSON.stringify(streamed)}`);
  throwsMatching(() => streamAsset(app, entry, { kinds }), /domains must give/, 'streamAsset without domains');
  // A geometry error (here: a made-up one) rejects the stream with the scene's name.
  app.streamGeometry = () => 'corrupt: section 2 (indices): index 5 is out of range';
  let message = '';
  try {
    await streamAsset(app, entry, { kinds, domains });
  } catch (e) {
    message = e.message;
  }
  check(/Scene 'mixed' could not be loaded: .*index 5/.test(message), `geometry error: '${message}'`);
}

// ---- permalinks: a view round-trips exactly; each bad field is named and left out
{
  const known = { scenes: ['room', 'a&b #1'], environments: ['white furnace', 'forest'], modes: ['unshadowed', 'shadowed', 'interreflected', 'lambert'],
    maxOrder: 8, projections: ['analytic', 'gpu', 'cpu'] };
  const camera = [0.1, -2.5, 3.25, 7.123456, 0.35, 4.2].map(Math.fround);
  const view = {
    scene: 'a&b #1', camera, environment: 'forest', environmentOn: false, envYaw: -1.2345678901234, envPitch: 0.3, intensity: 2.5,
    color: '#ffa07a', exposure: -1.7, background: 'colour', backgroundColor: '#102030', mode: 'shadowed', order: 4, source: 'texel',
    glossyMix: { unshadowed: 'both', shadowed: 'glossy', interreflected: 'diffuse' }, biScale: false, viewDependence: true, projection: 'cpu', cubeSize: 128,
    lights: [{ shape: 'sphere', position: [0.1, 1 / 3, -2], radius: 0.07, color: [1, 0.92, 0.8], intensity: 40 },
      { shape: 'mesh', mesh: 'torus', position: [0, 1, 0], scale: 0.5, color: [1, 1, 1], intensity: 3 }],
  };
  const fragment = encodePermalink(view);
  const back = decodePermalink(`#${fragment}`, known);
  check(back.problems.length === 0, `round trip problems: ${back.problems.join('; ')}`);
  const canonical = (v) => JSON.stringify(v, (k, x) => (x && typeof x === 'object' && !Array.isArray(x)
    ? Object.fromEntries(Object.keys(x).sort().map((key) => [key, x[key]])) : x));
  check(canonical(back.view) === canonical(view), `round trip: ${canonical(back.view)} vs ${canonical(view)}`);
  // float32 values take their shortest text, and read back as the same float32.
  check(float32Text(Math.fround(0.35)) === '0.35' && float32Text(Math.fround(7.123456)) === '7.123456', `float32Text: ${float32Text(Math.fround(0.35))}`);
  for (const x of [Math.fround(Math.PI), Math.fround(1e-7), Math.fround(-123456.78), 0]) {
    check(Math.fround(Number(float32Text(x))) === x, `float32Text(${x}) = ${float32Text(x)} does not read back`);
  }
  check(JSON.stringify(decodePermalink('', known)) === JSON.stringify({ view: {}, problems: [] }), 'an empty fragment');
  // Junk: every bad field named, none of them in the view; the good one kept.
  const junk = decodePermalink('#scene=nowhere&camera=1,2,x&env=mars&yaw=99&pitch=abc&color=red&mode=glow&order=0&source=pixel' +
    '&glossy=both&projection=magic&cube=7&lights=%5B%7B&intensity=3&bogus=1&bg=sky&bgColor=12345&biscale=yes', known);
  for (const [key, pattern] of [['scene', /scene="nowhere" is not one of/], ['camera', /camera=.*six numbers/], ['env', /env="mars"/],
    ['yaw', /yaw=99 is outside/], ['pitch', /pitch="abc" is not a number/], ['color', /color="red" must be six hex/],
    ['mode', /mode="glow"/], ['order', /order="0" must be an integer 1\.\.8/], ['source', /source="pixel"/], ['glossy', /glossy="both" must be three/],
    ['projection', /projection="magic"/], ['bg', /bg="sky" is not one of image/], ['bgColor', /bgColor="12345" must be six hex/], ['cube', /cube="7"/], ['lights', /lights is not JSON/], ['bogus', /'bogus' is not a view setting/], ['biscale', /biscale="yes"/]]) {
    check(junk.problems.some((p) => pattern.test(p)), `junk ${key}: no problem matching ${pattern} in ${junk.problems.join('; ')}`);
  }
  check(JSON.stringify(junk.view) === JSON.stringify({ intensity: 3 }), `junk view keeps only the good field: ${JSON.stringify(junk.view)}`);
  const future = decodePermalink('#v=2&scene=room', known);
  check(Object.keys(future.view).length === 0 && /version 1/.test(future.problems[0]), `a version-2 link: ${JSON.stringify(future)}`);
  const lightsObject = decodePermalink('#lights=%7B%7D', known);
  check(!('lights' in lightsObject.view) && /JSON array/.test(lightsObject.problems[0]), `lights {}: ${JSON.stringify(lightsObject)}`);
  const zeroDistance = decodePermalink('#camera=0,0,0,0,0,0', known);
  check(!('camera' in zeroDistance.view) && /distance 0 must be > 0/.test(zeroDistance.problems[0]), `distance 0: ${JSON.stringify(zeroDistance)}`);
}

if (failures.length) {
  console.error(`${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`page modules: ${checks} checks passed`);
