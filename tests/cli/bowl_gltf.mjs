// A white-furnace test scene: the lower half of the unit sphere (a bowl, open at y = 0) with
// inward normals and one albedo, as a .gltf text with its buffer in a data URI.
//
// Why a hemisphere: from any point inside a sphere the cosine-weighted fraction of the view
// that a patch of the sphere covers is its area / (4 pi r^2), so every point of the bowl sees
// exactly half bowl and half sky. Under constant radiance 1 the exit radiance after the
// direct term and N bounces is therefore the same everywhere:
//   B_N = sum_{k=0..N} (rho/2)^(k+1),  which is 1 - 2^-(N+1) for rho = 1 (limit 1)
// and rho/2 / (1 - rho/2) in the limit otherwise (0.905 for rho = 0.95).

// Returns the .gltf text: `rings` rings of `slices` quads from the rim down, a fan at the pole.
export function bowlGltf({ albedo = 1, rings = 24, slices = 48 } = {}) {
  const positions = [], normals = [], indices = [];
  const vertex = (theta, phi) => {
    const p = [Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi)];
    positions.push(...p);
    normals.push(...p.map((x) => -x));  // inward
    return positions.length / 3 - 1;
  };
  const ring = [];
  for (let k = 0; k < rings; k++) {
    const theta = Math.PI / 2 + (k * Math.PI) / 2 / rings;  // k = 0: the rim, y = 0
    ring.push(Array.from({ length: slices }, (_, i) => vertex(theta, (2 * Math.PI * i) / slices)));
  }
  const pole = vertex(Math.PI, 0);
  // Each triangle wound counter-clockwise seen from inside: (b - a) x (c - a) along the normal.
  const triangle = (a, b, c) => {
    const P = (v) => positions.slice(3 * v, 3 * v + 3);
    const [pa, pb, pc] = [P(a), P(b), P(c)];
    const e1 = pb.map((x, i) => x - pa[i]), e2 = pc.map((x, i) => x - pa[i]);
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const inward = normals.slice(3 * a, 3 * a + 3);
    if (n[0] * inward[0] + n[1] * inward[1] + n[2] * inward[2] >= 0) indices.push(a, b, c);
    else indices.push(a, c, b);
  };
  for (let k = 0; k + 1 < rings; k++) {
    for (let i = 0; i < slices; i++) {
      const j = (i + 1) % slices;
      triangle(ring[k][i], ring[k + 1][i], ring[k][j]);
      triangle(ring[k][j], ring[k + 1][i], ring[k + 1][j]);
    }
  }
  for (let i = 0; i < slices; i++) triangle(ring[rings - 1][i], pole, ring[rings - 1][(i + 1) % slices]);

  const pos = new Float32Array(positions), nrm = new Float32Array(normals), idx = new Uint32Array(indices);
  const bytes = Buffer.concat([Buffer.from(pos.buffer), Buffer.from(nrm.buffer), Buffer.from(idx.buffer)]);
  const count = pos.length / 3;
  return JSON.stringify({
    asset: { version: '2.0', generator: 'tests/cli/bowl_gltf.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [albedo, albedo, albedo, 1], metallicFactor: 0 } }],
    buffers: [{ byteLength: bytes.length, uri: `data:application/octet-stream;base64,${bytes.toString('base64')}` }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: pos.byteLength, target: 34962 },
      { buffer: 0, byteOffset: pos.byteLength, byteLength: nrm.byteLength, target: 34962 },
      { buffer: 0, byteOffset: pos.byteLength + nrm.byteLength, byteLength: idx.byteLength, target: 34963 },
    ],
    accessors: [
      { bufferView: 0, componentType: 5126, count, type: 'VEC3', min: [-1, -1, -1], max: [1, 0, 1] },
      { bufferView: 1, componentType: 5126, count, type: 'VEC3' },
      { bufferView: 2, componentType: 5125, count: idx.length, type: 'SCALAR' },
    ],
  });
}
