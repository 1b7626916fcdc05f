// Transfer-codec decode throughput in wasm (the client's own decoder, compiled by
// Emscripten, run by Node's V8 as a browser would run it): every blob in a directory
// (prt-bake compress-report --save-blobs), decoded to floats and, for CPCA, to the form the
// renderer draws from (decodeCpcaTransfer + packCpca). Prints JSON rows.
// Usage: node --no-experimental-fetch codec_decode_bench.mjs PRT_CORE_NODE_JS BLOB_DIR
// (Node 18+ would otherwise fetch() the .wasm by path, which fails.)
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const [coreJs, blobDir] = process.argv.slice(2);
const core = await createRequire(import.meta.url)(path.resolve(coreJs))();
const rows = [];
for (const file of fs.readdirSync(blobDir).filter((f) => f.endsWith('.prtt')).sort()) {
  const bytes = fs.readFileSync(path.join(blobDir, file));
  const once = core.timeTransferDecode(bytes, 1);  // warm-up, and the size of a run
  if (typeof once === 'string') throw new Error(`${file}: ${once}`);
  const repeats = Math.max(3, Math.ceil(1.5 / Math.max(once.expand, once.cpca ?? 0, 1e-3)));
  // Best of three runs of `repeats` decodes each (the machine is shared).
  let best = null;
  for (let run = 0; run < 3; run++) {
    const r = core.timeTransferDecode(bytes, repeats);
    if (typeof r === 'string') throw new Error(`${file}: ${r}`);
    if (!best) best = r;
    best.expand = Math.min(best.expand, r.expand);
    if (r.cpca !== null) best.cpca = Math.min(best.cpca, r.cpca);
  }
  rows.push({ setting: file.replace(/\.prtt$/, ''), bytes: best.bytes, vertices: best.vertices, repeats,
              expand_seconds: best.expand, cpca_seconds: best.cpca });
  console.error(`${file}: ${(best.bytes / best.expand / 1e6).toFixed(1)} MB/s expanded` +
                (best.cpca !== null ? `, ${(best.bytes / best.cpca / 1e6).toFixed(1)} MB/s for direct CPCA` : ''));
}
console.log(JSON.stringify({ rows }, null, 2));
