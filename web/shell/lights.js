// The page's model of the dynamic local lights: checking the light descriptions that
// prtApp.set({lights}) and the panel produce, and packing them into the 16 floats per
// light that ClientApp.setLights takes (docs/web-client.md). Pure (no DOM, no wasm):
// tests/web/shell_modules_test.mjs runs it under Node.

export const SHAPES = ['sphere', 'disc', 'rect', 'mesh'];  // index = the client's shape code
export const FLOATS_PER_LIGHT = 16;
export const MAX_LIGHTS = 1024;  // the client's limit (kMaxEmitters)

// The fields each shape takes, beyond position, color and intensity.
const SHAPE_FIELDS = {
  sphere: ['radius'],
  disc: ['radius', 'normal'],
  rect: ['size', 'normal'],
  mesh: ['mesh', 'scale'],
};
const COMMON_FIELDS = ['shape', 'position', 'color', 'intensity'];

const describe = (v) => (typeof v === 'string' ? `'${v}'` : JSON.stringify(v) ?? String(v));

function vector(value, n, where) {
  if (!Array.isArray(value) && !ArrayBuffer.isView(value)) throw new Error(`${where} must be an array of ${n} numbers, got ${describe(value)}`);
  if (value.length !== n) throw new Error(`${where} must hold ${n} numbers, got ${value.length}`);
  const out = Array.from(value, Number);
  out.forEach((x, i) => {
    if (typeof value[i] !== 'number' || !Number.isFinite(x)) throw new Error(`${where}[${i}] must be a finite number, got ${describe(value[i])}`);
  });
  return out;
}

function positiveNumber(value, where) {
  if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0) throw new Error(`${where} must be a finite number > 0, got ${describe(value)}`);
  return value;
}

// Checks one light description and returns it completed with defaults (color [1,1,1],
// intensity 1, normal [0,-1,0] normalised, mesh scale 1), or throws an Error naming
// lights[index] and the field. `meshes` maps known mesh names and ids to their entries.
export function normaliseLight(spec, index, meshes) {
  const at = `lights[${index}]`;
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) throw new Error(`${at} must be an object, got ${describe(spec)}`);
  if (!SHAPES.includes(spec.shape)) throw new Error(`${at}.shape must be one of ${SHAPES.join(', ')}; got ${describe(spec.shape)}`);
  const allowed = [...COMMON_FIELDS, ...SHAPE_FIELDS[spec.shape]];
  for (const key of Object.keys(spec)) {
    if (!allowed.includes(key)) throw new Error(`${at}.${key} is not a field of a ${spec.shape} light (fields: ${allowed.join(', ')})`);
  }
  if (!('position' in spec)) throw new Error(`${at}.position is required ([x, y, z] in world units)`);
  const light = {
    shape: spec.shape,
    position: vector(spec.position, 3, `${at}.position`),
    color: 'color' in spec ? vector(spec.color, 3, `${at}.color`) : [1, 1, 1],
    intensity: 'intensity' in spec ? spec.intensity : 1,
  };
  light.color.forEach((c, i) => { if (c < 0) throw new Error(`${at}.color[${i}] must be >= 0, got ${c}`); });
  if (typeof light.intensity !== 'number' || !Number.isFinite(light.intensity) || light.intensity < 0) {
    throw new Error(`${at}.intensity must be a finite number >= 0, got ${describe(light.intensity)}`);
  }
  if (spec.shape === 'sphere' || spec.shape === 'disc') {
    if (!('radius' in spec)) throw new Error(`${at}.radius is required for a ${spec.shape} light`);
    light.radius = positiveNumber(spec.radius, `${at}.radius`);
  }
  if (spec.shape === 'rect') {
    if (!('size' in spec)) throw new Error(`${at}.size is required for a rect light ([width, height])`);
    light.size = vector(spec.size, 2, `${at}.size`).map((s, i) => positiveNumber(s, `${at}.size[${i}]`));
  }
  if (spec.shape === 'disc' || spec.shape === 'rect') {
    const n = 'normal' in spec ? vector(spec.normal, 3, `${at}.normal`) : [0, -1, 0];
    const length = Math.hypot(...n);
    if (!(length > 1e-6)) throw new Error(`${at}.normal must not be the zero vector`);
    light.normal = n.map((x) => x / length);
  }
  if (spec.shape === 'mesh') {
    if (!('mesh' in spec)) throw new Error(`${at}.mesh is required for a mesh light ('torus' or an id from prtApp.addMesh)`);
    if (!meshes.has(spec.mesh)) {
      throw new Error(`${at}.mesh ${describe(spec.mesh)} is unknown; use 'torus' or an id from prtApp.addMesh (known: ${[...meshes.keys()].map(describe).join(', ')})`);
    }
    light.mesh = spec.mesh;
    light.scale = 'scale' in spec ? positiveNumber(spec.scale, `${at}.scale`) : 1;
  }
  return light;
}

// Checks a whole list (throws on the first bad light; nothing is applied).
export function normaliseLights(list, meshes) {
  if (!Array.isArray(list)) throw new Error(`lights must be an array of light objects, got ${describe(list)}`);
  if (list.length > MAX_LIGHTS) throw new Error(`at most ${MAX_LIGHTS} lights, got ${list.length}`);
  return list.map((spec, i) => normaliseLight(spec, i, meshes));
}

// Packs checked lights into ClientApp.setLights' layout:
// [shape, px, py, pz, sizeX, sizeY, nx, ny, nz, r, g, b, intensity, meshId, 0, 0] per light.
// `meshes` maps light.mesh to {id} (the client's mesh id).
export function packLights(lights, meshes) {
  const flat = new Float32Array(lights.length * FLOATS_PER_LIGHT);
  lights.forEach((l, i) => {
    const sizeX = l.shape === 'rect' ? l.size[0] : l.shape === 'mesh' ? l.scale : l.radius;
    const sizeY = l.shape === 'rect' ? l.size[1] : 0;
    const n = l.normal || [0, -1, 0];
    const meshId = l.shape === 'mesh' ? meshes.get(l.mesh).id : 0;
    flat.set([SHAPES.indexOf(l.shape), ...l.position, sizeX, sizeY, ...n, ...l.color, l.intensity, meshId, 0, 0], i * FLOATS_PER_LIGHT);
  });
  return flat;
}

// Radius of a sphere about light.position that holds the whole emitter (for picking).
export function boundingRadius(light, meshes) {
  switch (light.shape) {
    case 'sphere':
    case 'disc': return light.radius;
    case 'rect': return 0.5 * Math.hypot(light.size[0], light.size[1]);
    default: return light.scale * meshes.get(light.mesh).radius;
  }
}

// A deep copy, so callers of prtApp.lights cannot edit the page's state behind its back.
export function copyLight(light) {
  return JSON.parse(JSON.stringify(light));
}
