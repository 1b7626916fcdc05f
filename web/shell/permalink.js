// Permalinks: the page's view (scene, camera, environment and its rotation, intensity,
// colour and exposure, transfer mode, order, source, glossy mix, dynamic lights and their
// projection) written into the URL's fragment and read back, every value checked on the
// way in (docs/web-client.md, "Permalinks"). Pure (no DOM, no wasm): tests/web/
// shell_modules_test.mjs runs it under Node.
//
// The fragment (#...), not the query: it never reaches the server (no new routes, the
// page and the assets stay cacheable under one URL, a long list of lights cannot hit a
// request-line limit), and replacing it does not reload the page. ?scene= and ?env= still
// work as before; the fragment wins where both are given.

export const PERMALINK_VERSION = 1;
const PASSES = ['unshadowed', 'shadowed', 'interreflected'];
const GLOSSY_MIXES = ['diffuse', 'glossy', 'both'];
const SOURCES = ['vertex', 'texel'];
const BACKGROUNDS = ['image', 'blurred', 'colour', 'none'];
// The panel's ranges: a link can say nothing the panel could not.
export const RANGES = { envYaw: [-Math.PI, Math.PI], envPitch: [-1.5, 1.5], intensity: [0, 10], exposure: [-8, 8], cubeSize: [8, 512] };

// The shortest decimal that reads back as the same float32: camera values come from the
// client's float32 camera, and a rounded value would move the picture by a pixel.
export function float32Text(x) {
  const f = Math.fround(x);
  for (let p = 1; p <= 9; p++) {
    const s = Number(f.toPrecision(p)).toString();
    if (Math.fround(Number(s)) === f) return s;
  }
  return String(f);
}

// The fragment (without '#') for `view`: {scene, camera: [tx, ty, tz, yaw, pitch, distance],
// environment, envYaw, envPitch, intensity, color ('#rrggbb'), exposure, background,
// backgroundColor ('#rrggbb'), mode, order, source,
// glossyMix: {pass: mix}, lights: [light descriptions], projection, cubeSize, environmentOn}.
// Doubles are written as JavaScript's shortest round-trip text, so they read back exactly.
export function encodePermalink(view) {
  const p = new URLSearchParams();
  p.set('v', String(PERMALINK_VERSION));
  p.set('scene', view.scene);
  p.set('camera', view.camera.map(float32Text).join(','));
  p.set('env', view.environment);
  p.set('envOn', view.environmentOn ? '1' : '0');
  p.set('yaw', String(view.envYaw));
  p.set('pitch', String(view.envPitch));
  p.set('intensity', String(view.intensity));
  p.set('color', view.color.replace(/^#/, '').toLowerCase());
  p.set('exposure', String(view.exposure));
  p.set('bg', view.background);
  p.set('bgColor', view.backgroundColor.replace(/^#/, '').toLowerCase());
  p.set('mode', view.mode);
  p.set('order', String(view.order));
  p.set('source', view.source);
  p.set('glossy', PASSES.map((n) => view.glossyMix[n]).join(','));
  p.set('biscale', view.biScale ? '1' : '0');
  p.set('rttView', view.viewDependence ? '1' : '0');
  p.set('projection', view.projection);
  p.set('cube', String(view.cubeSize));
  p.set('lights', JSON.stringify(view.lights));
  return p.toString();
}

const describe = (v) => JSON.stringify(v);

function number(text, key, problems, [lo, hi]) {
  const x = Number(text);
  if (text.trim() === '' || !Number.isFinite(x)) {
    problems.push(`${key}=${describe(text)} is not a number`);
    return undefined;
  }
  if (x < lo || x > hi) {
    problems.push(`${key}=${text} is outside ${lo.toFixed(2)}..${hi.toFixed(2)}`);
    return undefined;
  }
  return x;
}

function oneOf(text, key, names, problems) {
  if (names.includes(text)) return text;
  problems.push(`${key}=${describe(text)} is not one of ${names.join(', ')}`);
  return undefined;
}

// Reads a fragment (with or without '#'). `known` gives what the page can show: {scenes,
// environments (names), modes, maxOrder, projections}. Returns {view, problems}: view holds
// only the fields given and valid (the page keeps its defaults for the rest), problems one
// sentence per field that was given but bad (unknown keys too). An empty fragment gives
// {view: {}, problems: []}. Lights are checked for shape here, by LightSet.set in the page.
export function decodePermalink(fragment, known) {
  const text = fragment.replace(/^#/, '');
  const view = {};
  const problems = [];
  if (!text) return { view, problems };
  let p;
  try {
    p = new URLSearchParams(text);
  } catch (e) {
    return { view, problems: [`the link's view cannot be read (${e.message})`] };
  }
  const keys = ['v', 'scene', 'camera', 'env', 'envOn', 'yaw', 'pitch', 'intensity', 'color', 'exposure', 'bg', 'bgColor', 'mode', 'order', 'source',
    'glossy', 'biscale', 'rttView', 'projection', 'cube', 'lights'];
  for (const key of p.keys()) if (!keys.includes(key)) problems.push(`'${key}' is not a view setting`);
  if (p.has('v') && p.get('v') !== String(PERMALINK_VERSION)) {
    problems.push(`v=${describe(p.get('v'))}: this page reads version ${PERMALINK_VERSION} links`);
    return { view, problems };
  }
  const get = (key) => (p.has(key) ? p.get(key) : null);
  if (get('scene') !== null) view.scene = oneOf(get('scene'), 'scene', known.scenes, problems);
  if (get('camera') !== null) {
    const parts = get('camera').split(',');
    const values = parts.map(Number);
    if (parts.length !== 6 || parts.some((s) => s.trim() === '') || !values.every(Number.isFinite)) {
      problems.push(`camera=${describe(get('camera'))} must be six numbers: target x, y, z, yaw, pitch, distance`);
    } else if (!(values[5] > 0)) {
      problems.push(`camera distance ${values[5]} must be > 0`);
    } else {
      view.camera = values.map(Math.fround);  // the client's camera is float32
    }
  }
  if (get('env') !== null) view.environment = oneOf(get('env'), 'env', known.environments, problems);
  if (get('envOn') !== null) {
    const on = oneOf(get('envOn'), 'envOn', ['0', '1'], problems);
    if (on !== undefined) view.environmentOn = on === '1';
  }
  const numbers = [['yaw', 'envYaw'], ['pitch', 'envPitch'], ['intensity', 'intensity'], ['exposure', 'exposure']];
  for (const [key, field] of numbers) if (get(key) !== null) view[field] = number(get(key), key, problems, RANGES[field]);
  for (const [key, field] of [['color', 'color'], ['bgColor', 'backgroundColor']]) {
    if (get(key) === null) continue;
    if (/^[0-9a-f]{6}$/i.test(get(key))) view[field] = `#${get(key).toLowerCase()}`;
    else problems.push(`${key}=${describe(get(key))} must be six hex digits (rrggbb)`);
  }
  if (get('bg') !== null) view.background = oneOf(get('bg'), 'bg', BACKGROUNDS, problems);
  if (get('mode') !== null) view.mode = oneOf(get('mode'), 'mode', known.modes, problems);
  if (get('order') !== null) {
    const order = Number(get('order'));
    if (Number.isInteger(order) && order >= 1 && order <= known.maxOrder) view.order = order;
    else problems.push(`order=${describe(get('order'))} must be an integer 1..${known.maxOrder}`);
  }
  if (get('source') !== null) view.source = oneOf(get('source'), 'source', SOURCES, problems);
  for (const [key, field] of [['biscale', 'biScale'], ['rttView', 'viewDependence']]) {
    if (get(key) === null) continue;
    const on = oneOf(get(key), key, ['0', '1'], problems);
    if (on !== undefined) view[field] = on === '1';
  }
  if (get('glossy') !== null) {
    const mixes = get('glossy').split(',');
    if (mixes.length === PASSES.length && mixes.every((m) => GLOSSY_MIXES.includes(m))) {
      view.glossyMix = Object.fromEntries(PASSES.map((n, i) => [n, mixes[i]]));
    } else {
      problems.push(`glossy=${describe(get('glossy'))} must be three of ${GLOSSY_MIXES.join(', ')} (${PASSES.join(', ')})`);
    }
  }
  if (get('projection') !== null) view.projection = oneOf(get('projection'), 'projection', known.projections, problems);
  if (get('cube') !== null) {
    const size = Number(get('cube'));
    const [lo, hi] = RANGES.cubeSize;
    if (Number.isInteger(size) && size >= lo && size <= hi) view.cubeSize = size;
    else problems.push(`cube=${describe(get('cube'))} must be an integer ${lo}..${hi}`);
  }
  if (get('lights') !== null) {
    let lights;
    try {
      lights = JSON.parse(get('lights'));
    } catch (e) {
      problems.push(`lights is not JSON (${e.message})`);
    }
    if (lights !== undefined) {
      if (Array.isArray(lights)) view.lights = lights;
      else problems.push('lights must be a JSON array of light descriptions');
    }
  }
  for (const key of Object.keys(view)) if (view[key] === undefined) delete view[key];
  return { view, problems };
}
