// glTF scenes for the texture-set tests (bake_cli_test.mjs texture_sets*), as .gltf text with
// the buffer in a data URI: meshes of axis-aligned quads with a TEXCOORD_1 lightmap each, and
// nodes that place them (several nodes may instance one mesh, so they share its UVs).

// A quad: `origin` + s `edgeU` + t `edgeV` for s, t in [0, 1], facing cross(edgeU, edgeV),
// mapped to the UV rectangle [u0, u1] x [v0, v1].
export function quad(origin, edgeU, edgeV, [u0, v0, u1, v1]) {
  const at = (s, t) => [0, 1, 2].map((k) => origin[k] + s * edgeU[k] + t * edgeV[k]);
  const n = [edgeU[1] * edgeV[2] - edgeU[2] * edgeV[1], edgeU[2] * edgeV[0] - edgeU[0] * edgeV[2],
             edgeU[0] * edgeV[1] - edgeU[1] * edgeV[0]];
  const len = Math.hypot(...n);
  return {
    positions: [...at(0, 0), ...at(1, 0), ...at(1, 1), ...at(0, 1)],
    normals: [0, 1, 2, 3].flatMap(() => n.map((x) => x / len)),
    uv: [u0, v0, u1, v0, u1, v1, u0, v1],
    indices: [0, 1, 2, 0, 2, 3],
  };
}

// A closed axis-aligned box from `lo` to `hi`, outward faces, its six faces in a 3 x 2 grid of
// UV cells inside [u0, u1] x [v0, v1] with a gap between cells.
export function box(lo, hi, [u0, v0, u1, v1]) {
  const [x0, y0, z0] = lo, [x1, y1, z1] = hi;
  const dx = x1 - x0, dy = y1 - y0, dz = z1 - z0;
  const faces = [
    [[x0, y0, z1], [dx, 0, 0], [0, dy, 0]], [[x1, y0, z0], [-dx, 0, 0], [0, dy, 0]],
    [[x1, y0, z1], [0, 0, -dz], [0, dy, 0]], [[x0, y0, z0], [0, 0, dz], [0, dy, 0]],
    [[x0, y1, z1], [dx, 0, 0], [0, 0, -dz]], [[x0, y0, z0], [dx, 0, 0], [0, 0, dz]],
  ];
  const cw = (u1 - u0) / 3, ch = (v1 - v0) / 2, gap = 0.25;  // wide gutters: the box atlas is small
  return merge(faces.map(([o, a, b], k) => {
    const cu = u0 + (k % 3) * cw, cv = v0 + Math.floor(k / 3) * ch;
    return quad(o, a, b, [cu + gap * cw, cv + gap * ch, cu + (1 - gap) * cw, cv + (1 - gap) * ch]);
  }));
}

export function merge(parts) {
  const m = { positions: [], normals: [], uv: [], indices: [] };
  for (const p of parts) {
    const base = m.positions.length / 3;
    m.positions.push(...p.positions);
    m.normals.push(...p.normals);
    m.uv.push(...p.uv);
    m.indices.push(...p.indices.map((i) => i + base));
  }
  return m;
}

// `meshes`: [{positions, normals, uv, indices}]; `nodes`: [{mesh, translation?, name?}].
// `texcoord`: the attribute the uv go in (1, the lightmap set, by default).
export function texturedSceneGltf(meshes, nodes, { texcoord = 1 } = {}) {
  const chunks = [], views = [], accessors = [];
  let offset = 0;
  const add = (array, type, count, target, extra = {}) => {
    const bytes = Buffer.from(array.buffer);
    chunks.push(bytes);
    views.push({ buffer: 0, byteOffset: offset, byteLength: bytes.length, target });
    offset += bytes.length;
    accessors.push({ bufferView: views.length - 1, componentType: array instanceof Uint32Array ? 5125 : 5126, count, type, ...extra });
    return accessors.length - 1;
  };
  const gltfMeshes = meshes.map((m) => {
    const count = m.positions.length / 3;
    const lo = [0, 1, 2].map((k) => Math.min(...m.positions.filter((_, i) => i % 3 === k)));
    const hi = [0, 1, 2].map((k) => Math.max(...m.positions.filter((_, i) => i % 3 === k)));
    const attributes = {
      POSITION: add(new Float32Array(m.positions), 'VEC3', count, 34962, { min: lo, max: hi }),
      NORMAL: add(new Float32Array(m.normals), 'VEC3', count, 34962),
      [`TEXCOORD_${texcoord}`]: add(new Float32Array(m.uv), 'VEC2', count, 34962),
    };
    const indices = add(new Uint32Array(m.indices), 'SCALAR', m.indices.length, 34963);
    return { primitives: [{ attributes, indices, material: 0 }] };
  });
  const bytes = Buffer.concat(chunks);
  return JSON.stringify({
    asset: { version: '2.0', generator: 'tests/cli/texture_sets_gltf.mjs' },
    scene: 0,
    scenes: [{ nodes: nodes.map((_, i) => i) }],
    nodes: nodes.map((n) => ({ mesh: n.mesh, ...(n.translation ? { translation: n.translation } : {}), ...(n.name ? { name: n.name } : {}) })),
    meshes: gltfMeshes,
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [0.7, 0.7, 0.7, 1], metallicFactor: 0, roughnessFactor: 1 } }],
    buffers: [{ byteLength: bytes.length, uri: `data:application/octet-stream;base64,${bytes.toString('base64')}` }],
    bufferViews: views,
    accessors,
  });
}
