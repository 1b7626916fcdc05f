// Unwraps a PRTM mesh (mesh_raw.md) with xatlasjs's Node build (npm xatlasjs 0.2.0, the
// Emscripten port of xatlas) and writes the result as a PRTM mesh with UVs in [0, 1].
// Usage: node xatlas_unwrap.mjs XATLASJS_DIR IN.mesh OUT.mesh SIZE PADDING
// Prints one JSON line: seconds, charts, atlas count. Part of uv-atlas-eval.sh.
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [dir, input, output, sizeArg, paddingArg] = process.argv.slice(2);
if (!output) {
  console.error('usage: xatlas_unwrap.mjs XATLASJS_DIR IN.mesh OUT.mesh SIZE PADDING');
  process.exit(2);
}
const size = Number(sizeArg);
const padding = Number(paddingArg);

function readMesh(path) {
  const b = readFileSync(path);
  if (b.toString('latin1', 0, 4) !== 'PRTM') throw new Error(`${path}: not a PRTM mesh`);
  const [n, t] = [b.readUInt32LE(4), b.readUInt32LE(8)];
  const copy = (offset, count, Type) => new Type(b.buffer.slice(b.byteOffset + offset, b.byteOffset + offset + count * 4));
  return { positions: copy(16, 3 * n, Float32Array), indices: copy(16 + 12 * n, 3 * t, Uint32Array) };
}

function writeMesh(path, positions, uvs, indices) {
  const n = positions.length / 3;
  const head = Buffer.alloc(16);
  head.write('PRTM', 0, 'latin1');
  head.writeUInt32LE(n, 4);
  head.writeUInt32LE(indices.length / 3, 8);
  head.writeUInt32LE(1, 12);
  writeFileSync(path, Buffer.concat([head, Buffer.from(positions.buffer), Buffer.from(uvs.buffer), Buffer.from(indices.buffer)]));
}

const require = createRequire(import.meta.url);
const createXAtlasModule = require(join(dir, 'dist/node/xatlas.js'));
const { Api } = await import(pathToFileURL(join(dir, 'dist/node/api.mjs')).href);
const XatlasApi = Api(createXAtlasModule);
const api = await new Promise((resolve) => {
  const a = new XatlasApi(() => resolve(a), (file) => (file === 'xatlas.wasm' ? join(dir, 'dist/node/xatlas.wasm') : null));
});

const mesh = readMesh(input);
// The wrapper passes indices as Uint16Array: more than 65536 vertices cannot be one mesh.
if (mesh.positions.length / 3 > 65536) {
  console.log(JSON.stringify({ error: `${mesh.positions.length / 3} vertices: xatlasjs takes 16-bit indices only` }));
  process.exit(3);
}
const start = process.hrtime.bigint();
api.createAtlas();
if (api.addMesh(new Uint16Array(mesh.indices), mesh.positions) === null) {
  console.log(JSON.stringify({ error: 'addMesh failed' }));
  process.exit(3);
}
const atlas = api.generateAtlas({}, { resolution: size, padding, bilinear: true }, true);
const seconds = Number(process.hrtime.bigint() - start) / 1e9;
const m = atlas.meshes[0];
// The wrapper already divides xatlas's texel coordinates by the atlas size: [0, 1].
const uvs = m.vertex.coords1;
writeMesh(output, m.vertex.vertices, uvs, new Uint32Array(m.index));
api.destroyAtlas();
console.log(JSON.stringify({ seconds, width: atlas.width, height: atlas.height, atlasCount: atlas.atlasCount,
  vertices: m.vertexCount }));
