// A glossy test scene: one 2 m x 2 m quad at y = 0 facing +y, alone under the sky, with a
// lightmap atlas (TEXCOORD_1, one chart well inside [0, 1]) so it bakes transfer textures, as
// a .gltf text with its buffer in a data URI.
//
// Why a lone plane: nothing occludes it, so each texel's visibility is the hemisphere above
// it, and glossy exit radiance under uniform white light has a closed form (docs/glossy.md):
// the Phong lobe about the mirror direction R integrated above the horizon, (1 + cos theta)/2
// for exponent 1 with theta the angle between R and the normal, times Schlick's k_s.

// Returns the .gltf text. `base`: base colour, `metallic`, `roughness`: its material.
export function planeGltf({ base = [0.8, 0.4, 0.2], metallic = 0.5, roughness = 0.5 } = {}) {
  const positions = [-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1];
  const normals = [0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0];
  // u along x, v along z, inside [0.1, 0.9]: a gutter far wider than any padding asked for.
  const uv = [];
  for (let v = 0; v < 4; v++) uv.push(0.1 + 0.4 * (positions[3 * v] + 1), 0.1 + 0.4 * (positions[3 * v + 2] + 1));
  const indices = [0, 3, 2, 0, 2, 1];  // counter-clockwise seen from +y
  const pos = new Float32Array(positions), nrm = new Float32Array(normals), tex = new Float32Array(uv);
  const idx = new Uint32Array(indices);
  const parts = [pos, nrm, tex, idx].map((a) => Buffer.from(a.buffer));
  const bytes = Buffer.concat(parts);
  const views = [];
  let offset = 0;
  for (const [i, p] of parts.entries()) {
    views.push({ buffer: 0, byteOffset: offset, byteLength: p.length, target: i === 3 ? 34963 : 34962 });
    offset += p.length;
  }
  return JSON.stringify({
    asset: { version: '2.0', generator: 'tests/cli/plane_gltf.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_1: 2 }, indices: 3, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [...base, 1], metallicFactor: metallic, roughnessFactor: roughness } }],
    buffers: [{ byteLength: bytes.length, uri: `data:application/octet-stream;base64,${bytes.toString('base64')}` }],
    bufferViews: views,
    accessors: [
      { bufferView: 0, componentType: 5126, count: 4, type: 'VEC3', min: [-1, 0, -1], max: [1, 0, 1] },
      { bufferView: 1, componentType: 5126, count: 4, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: 4, type: 'VEC2' },
      { bufferView: 3, componentType: 5125, count: 6, type: 'SCALAR' },
    ],
  });
}
