// Wavefront OBJ to a triangle mesh for emissive mesh lights, and the normalisation every
// user mesh gets before it becomes a light: centred on its bounding box, scaled to unit
// radius, so a light's `scale` is its radius in world units whatever the file's units were.
// Pure functions (no DOM): tests/web/shell_modules_test.mjs runs them under Node.

const MAX_TRIANGLES = 1000000;  // the client's addLightMesh limit

// Parses OBJ text: `v x y z [w]` and `f a b c ...` (vertex indices 1-based or negative =
// relative to the end; `a/t/n` forms use the first number; polygons fan-triangulated).
// Everything else (normals, texture coordinates, groups, materials) is ignored.
// Returns {positions: Float32Array xyz, indices: Uint32Array}; throws Error with the line
// number when the file is not a usable mesh.
export function parseObj(text) {
  if (typeof text !== 'string') throw new Error('OBJ: expected the file as text');
  const positions = [];
  const indices = [];
  const lines = text.split(/\r?\n/);
  for (let ln = 0; ln < lines.length; ln++) {
    const line = lines[ln].replace(/#.*/, '').trim();
    if (!line) continue;
    const parts = line.split(/\s+/);
    const where = `OBJ line ${ln + 1}`;
    if (parts[0] === 'v') {
      if (parts.length < 4) throw new Error(`${where}: a vertex needs x y z, got '${line}'`);
      const xyz = parts.slice(1, 4).map(Number);
      if (!xyz.every(Number.isFinite)) throw new Error(`${where}: vertex coordinates are not finite numbers: '${line}'`);
      positions.push(...xyz);
    } else if (parts[0] === 'f') {
      if (parts.length < 4) throw new Error(`${where}: a face needs at least 3 vertices, got '${line}'`);
      const vertexCount = positions.length / 3;
      const corners = parts.slice(1).map((token) => {
        const first = token.split('/')[0];
        if (!/^-?\d+$/.test(first)) throw new Error(`${where}: '${token}' is not a vertex index`);
        const k = Number(first);
        // Negative indices count back from the last vertex defined so far (OBJ spec).
        const index = k > 0 ? k - 1 : vertexCount + k;
        if (k === 0 || index < 0 || index >= vertexCount) {
          throw new Error(`${where}: vertex index ${k} is out of range (${vertexCount} vertices defined so far)`);
        }
        return index;
      });
      for (let i = 1; i + 1 < corners.length; i++) indices.push(corners[0], corners[i], corners[i + 1]);
      if (indices.length / 3 > MAX_TRIANGLES) throw new Error(`OBJ: more than ${MAX_TRIANGLES} triangles`);
    }
  }
  if (!positions.length) throw new Error('OBJ: no vertices (v lines) found: is this an OBJ file?');
  if (!indices.length) throw new Error('OBJ: no faces (f lines) found: a light needs a surface, not a point cloud');
  return { positions: new Float32Array(positions), indices: new Uint32Array(indices) };
}

// Copy of xyz `positions` translated so the bounding-box centre of the vertices the faces
// use is the origin, and scaled so the farthest such vertex is at distance 1. Throws when
// the mesh has no extent (every vertex at one point).
export function normaliseToUnitRadius(positions, indices) {
  const used = new Uint8Array(positions.length / 3);
  for (const i of indices) used[i] = 1;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < used.length; v++) {
    if (!used[v]) continue;
    for (let a = 0; a < 3; a++) {
      lo[a] = Math.min(lo[a], positions[3 * v + a]);
      hi[a] = Math.max(hi[a], positions[3 * v + a]);
    }
  }
  const centre = lo.map((l, a) => 0.5 * (l + hi[a]));
  let radius = 0;
  for (let v = 0; v < used.length; v++) {
    if (!used[v]) continue;
    radius = Math.max(radius, Math.hypot(positions[3 * v] - centre[0], positions[3 * v + 1] - centre[1], positions[3 * v + 2] - centre[2]));
  }
  if (!(radius > 0) || !Number.isFinite(radius)) throw new Error('OBJ: the mesh has no extent (all vertices coincide)');
  const out = new Float32Array(positions.length);
  for (let v = 0; v < used.length; v++) {
    for (let a = 0; a < 3; a++) out[3 * v + a] = (positions[3 * v + a] - centre[a]) / radius;
  }
  return out;
}

// Largest distance of a used vertex from the origin: a mesh light's bounding radius at
// scale 1, for picking.
export function meshRadius(positions, indices) {
  let r = 0;
  for (const i of indices) r = Math.max(r, Math.hypot(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]));
  return r;
}
