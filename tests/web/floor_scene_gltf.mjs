// A tiny glTF test scene for the light tests: a grey floor grid on y = 0 over
// [-half, half]^2 and a white box standing on it, written as one .gltf with its buffer in a
// data URI, so prt-bake can bake it in well under a second. gltfText writes any such parts,
// with texture coordinates and normal maps for the transfer-texture tests.
import zlib from 'node:zlib';

// Returns the .gltf text. The floor has cells x cells quads; the box
// {centre: [x, z], half: [hx, hy, hz]} sits on the floor (its bottom at y = 0).
export function floorSceneGltf({ half = 1.5, cells = 48, box = { centre: [0, 0], half: [0.3, 0.3, 0.3] } } = {}) {
  const floor = { positions: [], normals: [], indices: [], color: [0.7, 0.7, 0.7, 1] };
  for (let j = 0; j <= cells; j++) {
    for (let i = 0; i <= cells; i++) {
      floor.positions.push(-half + (2 * half * i) / cells, 0, -half + (2 * half * j) / cells);
      floor.normals.push(0, 1, 0);
    }
  }
  for (let j = 0; j < cells; j++) {
    for (let i = 0; i < cells; i++) {
      const a = j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
      floor.indices.push(a, c, b, b, c, d);  // counter-clockwise seen from +y
    }
  }
  // Box: 4x4 cells per face, each face its own vertices (flat normals).
  const solid = { positions: [], normals: [], indices: [], color: [0.8, 0.8, 0.8, 1] };
  const [cx, cz] = box.centre, extent = box.half;
  const centre = [cx, extent[1], cz];
  const faces = [
    { n: [1, 0, 0], u: [0, 0, -1], v: [0, 1, 0] }, { n: [-1, 0, 0], u: [0, 0, 1], v: [0, 1, 0] },
    { n: [0, 1, 0], u: [1, 0, 0], v: [0, 0, -1] }, { n: [0, -1, 0], u: [1, 0, 0], v: [0, 0, 1] },
    { n: [0, 0, 1], u: [1, 0, 0], v: [0, 1, 0] }, { n: [0, 0, -1], u: [-1, 0, 0], v: [0, 1, 0] },
  ];
  const k = 4;
  for (const { n, u, v } of faces) {
    const base = solid.positions.length / 3;
    for (let j = 0; j <= k; j++) {
      for (let i = 0; i <= k; i++) {
        const s = -1 + (2 * i) / k, t = -1 + (2 * j) / k;
        solid.positions.push(...[0, 1, 2].map((a) => centre[a] + extent[a] * (n[a] + s * u[a] + t * v[a])));
        solid.normals.push(...n);
      }
    }
    for (let j = 0; j < k; j++) {
      for (let i = 0; i < k; i++) {
        const a = base + j * (k + 1) + i, b = a + 1, c = a + k + 1, d = c + 1;
        solid.indices.push(a, b, c, b, d, c);  // u x v = n: counter-clockwise seen from outside
      }
    }
  }
  return gltfText([floor, solid]);
}

// An 8-bit RGB PNG (width x height, rgb row-major from the top row) as a data URI.
export function rgbPngDataUri(width, height, rgb) {
  const chunk = (type, data) => {
    const length = Buffer.alloc(4), crc = Buffer.alloc(4);
    length.writeUInt32BE(data.length);
    const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    crc.writeUInt32BE(zlib.crc32(body));
    return Buffer.concat([length, body, crc]);
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header.set([8, 2, 0, 0, 0], 8);  // 8 bits, RGB, deflate, no filter method, no interlace
  const rows = Buffer.alloc(height * (1 + 3 * width));
  for (let y = 0; y < height; y++) {
    rows[y * (1 + 3 * width)] = 0;  // filter type None
    for (let i = 0; i < 3 * width; i++) rows[y * (1 + 3 * width) + 1 + i] = rgb[y * 3 * width + i];
  }
  const png = Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', header),
    chunk('IDAT', zlib.deflateSync(rows)), chunk('IEND', Buffer.alloc(0))]);
  return `data:image/png;base64,${png.toString('base64')}`;
}

// One node and mesh per part, all in one base64 buffer. A part is {positions, normals,
// indices, color} (flat arrays, counter-clockwise front faces, linear RGBA base colour) with
// optional `uv` (flat u, v per vertex: TEXCOORD_0, glTF's v down the image), `normalMap`
// (a PNG data URI used as the material's normalTexture over TEXCOORD_0) and `metallic`,
// `roughness` (glTF's defaults, 1 and 1, when absent).
export function gltfText(parts) {
  const chunks = [], bufferViews = [], accessors = [], meshes = [], materials = [], images = [], textures = [];
  let offset = 0;
  const view = (typed, target) => {
    chunks.push(Buffer.from(typed.buffer));
    bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: typed.byteLength, target });
    offset += typed.byteLength;
    return bufferViews.length - 1;
  };
  parts.forEach((part, m) => {
    const pos = new Float32Array(part.positions), nrm = new Float32Array(part.normals), idx = new Uint32Array(part.indices);
    const count = pos.length / 3;
    const min = [0, 1, 2].map((a) => Math.min(...part.positions.filter((_, i) => i % 3 === a)));
    const max = [0, 1, 2].map((a) => Math.max(...part.positions.filter((_, i) => i % 3 === a)));
    const attributes = { POSITION: accessors.length, NORMAL: accessors.length + 1 };
    accessors.push({ bufferView: view(pos, 34962), componentType: 5126, count, type: 'VEC3', min, max });
    accessors.push({ bufferView: view(nrm, 34962), componentType: 5126, count, type: 'VEC3' });
    const indices = accessors.length;
    accessors.push({ bufferView: view(idx, 34963), componentType: 5125, count: idx.length, type: 'SCALAR' });
    if (part.uv) {
      attributes.TEXCOORD_0 = accessors.length;
      accessors.push({ bufferView: view(new Float32Array(part.uv), 34962), componentType: 5126, count, type: 'VEC2' });
    }
    meshes.push({ primitives: [{ attributes, indices, material: m }] });
    const material = { pbrMetallicRoughness: { baseColorFactor: part.color } };
    if (part.metallic !== undefined) material.pbrMetallicRoughness.metallicFactor = part.metallic;
    if (part.roughness !== undefined) material.pbrMetallicRoughness.roughnessFactor = part.roughness;
    if (part.normalMap) {
      images.push({ uri: part.normalMap });
      textures.push({ source: images.length - 1 });
      material.normalTexture = { index: textures.length - 1 };
    }
    materials.push(material);
  });
  const bytes = Buffer.concat(chunks);
  return JSON.stringify({
    asset: { version: '2.0', generator: 'tests/web/floor_scene_gltf.mjs' },
    scene: 0,
    scenes: [{ nodes: parts.map((_, i) => i) }],
    nodes: parts.map((_, i) => ({ mesh: i })),
    meshes,
    materials,
    ...(images.length ? { images, textures } : {}),
    buffers: [{ byteLength: bytes.length, uri: `data:application/octet-stream;base64,${bytes.toString('base64')}` }],
    bufferViews,
    accessors,
  });
}

// The stripes' slope at u: the tangent-space normal of stripeQuadGltf's map is
// normalize(stripeSlope(u), 0, 1), up to 31 degrees from the surface normal.
export const stripeSlope = (u) => 0.6 * Math.sin(8 * Math.PI * u);

// The normal-map scene of the transfer-texture tests: the quad [-1, 1]^2 at y = 0 facing +y
// over the whole atlas (u along +x, v along +z, TEXCOORD_0), with (withMap) an atlas x atlas
// normal map of stripes leaning along x (stripeSlope; +x of tangent space along +u = world +x).
// `material`: {color, metallic, roughness} of the quad (default a grey matte 0.8).
export function stripeQuadGltf(atlas, withMap, material = { color: [0.8, 0.8, 0.8, 1] }) {
  const part = { positions: [], normals: [], uv: [], indices: [0, 1, 2, 0, 2, 3] };
  for (const [sa, sb] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {  // counter-clockwise seen from +y
    part.positions.push(sb, 0, sa);
    part.normals.push(0, 1, 0);
    part.uv.push((sb + 1) / 2, (sa + 1) / 2);
  }
  const rgb = new Uint8Array(3 * atlas * atlas);
  for (let y = 0; y < atlas; y++)
    for (let i = 0; i < atlas; i++) {
      const s = stripeSlope((i + 0.5) / atlas), length = Math.hypot(s, 1);
      rgb.set([s / length, 0, 1 / length].map((c) => Math.round((c + 1) * 127.5)), 3 * (y * atlas + i));
    }
  return gltfText([{ ...part, ...material, ...(withMap ? { normalMap: rgbPngDataUri(atlas, atlas, rgb) } : {}) }]);
}
