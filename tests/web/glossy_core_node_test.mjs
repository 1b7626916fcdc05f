// The glossy renderer's arithmetic in the client's wasm core under Node (web/src/glossy_texture.h):
// glossy_table.vert and glossy.vert emulated on the CPU from the packed textures (per-cluster
// matrices times the lighting, then per vertex the weighted sum, the lobe's band scales, Schlick
// and y_i(R)) must equal prt::glossyExitRadiance on the matrices prt::cpcaMatrixReconstruct expands, for synthetic CPCA
// matrix passes (both packings, 1 and 3 channels, 8- and 16-bit weights, every order the
// shaders take, cut to fewer bands), and the shaders' SH evaluation must equal the shared one.
// Needs no codec and no baker. Usage: node glossy_core_node_test.mjs PRT_CORE_NODE_JS
import { createRequire } from 'node:module';
import path from 'node:path';

const [coreJs] = process.argv.slice(2);
const failures = [];
let checks = 0;
const check = (ok, message) => {
  checks++;
  if (!ok) failures.push(message);
  return ok;
};
const core = await createRequire(import.meta.url)(path.resolve(coreJs))();

const perChannel = core.kMaxClientOrder * core.kMaxClientOrder;
const lightingFor = (bands, seed) => {
  const lighting = new Array(core.kPackedLightingFloats).fill(0);
  for (let c = 0; c < 3; c++)
    for (let i = 0; i < bands * bands; i++) lighting[perChannel * c + i] = (i === 0 ? 3 : Math.sin(1.7 * i + c + seed)) * (1 + 0.2 * c);
  return lighting;
};

// Float tolerance: the emulation takes the matrix-vector products before the CPCA weighted sum
// (linearity), the reference after expanding, so they differ by rounding only. Both are
// compared with the double-accumulated reference relative to the scale of the terms summed:
// |x - ref| <= 1e-4 * (sum of |terms|), bounded here by 1e-4 * max(1, max |ref|) per case.
const worstError = (values, reference) => {
  let scale = 1;
  for (const r of reference) scale = Math.max(scale, Math.abs(r));
  let worst = 0;
  for (let i = 0; i < values.length; i++) worst = Math.max(worst, Math.abs(values[i] - reference[i]) / scale);
  return worst;
};

check(core.kMaxGlossyOrder === 8, `kMaxGlossyOrder ${core.kMaxGlossyOrder}`);
const cases = [];
for (const bands of [1, 2, 3, 4, 5, 6, 8])
  for (const channels of [1, 3])
    for (const packing of ['full', 'symmetric'])
      cases.push({ bands, channels, packing, clusters: 5, vectors: bands === 8 ? 3 : 4, weightBits: (bands % 2) ? 8 : 16, seed: 11 * bands + channels });
cases.push({ bands: 5, channels: 3, packing: 'full', clusters: 1, vectors: 0, weightBits: 8, seed: 3 });  // no basis: the mean alone
cases.push({ bands: 6, channels: 1, packing: 'symmetric', clusters: 40, vectors: 9, weightBits: 16, seed: 4 });

for (const spec of cases) {
  for (const active of [...new Set([spec.bands, Math.max(1, spec.bands - 2)])]) {
    for (const eye of [[0, 0, 4], [3.5, -1.2, 0.4]]) {
      const name = `${JSON.stringify(spec)} active ${active} eye ${eye}`;
      const r = core.glossySyntheticCheck(spec, 200, eye, lightingFor(active, spec.seed), active, true);
      if (!check(r && typeof r === 'object', `${name}: ${r}`)) continue;
      check(r.emulated.length === 600 && r.reference.length === 600, `${name}: ${r.emulated.length} emulated values`);
      check(r.basisExact, `${name}: the shaders' SH basis differs from prt::evalShBasisUnchecked`);
      check(r.expansionsAgree, `${name}: glossy_synthetic's expansion differs from prt::cpcaMatrixReconstruct`);
      const eEm = worstError(r.emulated, r.referenceDouble), eRef = worstError(r.reference, r.referenceDouble);
      check(eEm < 1e-4, `${name}: emulated shaders differ from the double reference by ${eEm} (float reference: ${eRef})`);
      check(eRef < 1e-4, `${name}: float reference differs from double by ${eRef}`);
      // The fused step (straight from the table, a group of vertices at a time) gives the same.
      for (const size of ['1', '3', '8']) {
        const f = r.fused[size];
        check(f.length === 600 && worstError(f, r.referenceDouble) < 1e-4, `${name}: fused step, groups of ${size}, differs from the double reference by ${worstError(f, r.referenceDouble)}`);
      }
      // The check has teeth: the glossy term is not zero everywhere, and varies between vertices.
      let energy = 0, spread = 0;
      for (let i = 0; i < r.referenceDouble.length; i++) {
        energy += Math.abs(r.referenceDouble[i]);
        spread = Math.max(spread, Math.abs(r.referenceDouble[i] - r.referenceDouble[0]));
      }
      check(energy > 1e-3 && spread > 1e-4, `${name}: reference radiance is degenerate (sum |L| ${energy}, spread ${spread})`);
    }
  }
}

// The glossy term follows the camera: moving the eye changes the emulated radiance, as it does
// the reference (the same vertices, materials and lighting).
{
  const spec = { bands: 4, channels: 3, packing: 'full', clusters: 3, vectors: 2, weightBits: 8, seed: 99 };
  const a = core.glossySyntheticCheck(spec, 50, [0, 0, 5], lightingFor(4, 1), 4, true);
  const b = core.glossySyntheticCheck(spec, 50, [5, 0, 0], lightingFor(4, 1), 4, true);
  let moved = 0;
  for (let i = 0; i < a.emulated.length; i++) moved = Math.max(moved, Math.abs(a.emulated[i] - b.emulated[i]));
  check(moved > 1e-3, `moving the eye changed the glossy radiance by only ${moved}`);
  // Without Fresnel k_s = f0: the two differ (Schlick raises every k_s toward 1 at grazing n.v).
  const c = core.glossySyntheticCheck(spec, 50, [0, 0, 5], lightingFor(4, 1), 4, false);
  check(worstError(c.emulated, c.referenceDouble) < 1e-4, 'no-Fresnel emulation differs from its reference');
  let differs = 0;
  for (let i = 0; i < a.emulated.length; i++) differs = Math.max(differs, Math.abs(a.emulated[i] - c.emulated[i]));
  check(differs > 1e-4, 'Fresnel made no difference');
}

// Grouping for the fused step: every vertex in exactly one slot of a group of its own cluster,
// clusters in order, a cluster's vertices in order, groups full but a cluster's last.
{
  const clusterOf = [];
  let seed = 5;
  for (let v = 0; v < 1000; v++) {
    seed = (seed * 1103515245 + 12345) % 2147483648;
    clusterOf.push(v % 97 === 0 ? 6 : seed % 6);  // cluster 6: 11 vertices; 7: none
  }
  for (const size of [1, 3, 8]) {
    const g = core.glossyGroups(clusterOf, 8, size, 4, 2);
    if (!check(typeof g === 'object', `groups of ${size}: ${g}`)) continue;
    const seen = new Array(clusterOf.length).fill(0);
    let ordered = true, sameCluster = true, packed = true, slotsAgree = true;
    const perCluster = new Array(8).fill(0);
    for (let k = 0; k < g.cluster.length; k++) {
      if (k > 0 && g.cluster[k] < g.cluster[k - 1]) ordered = false;
      let count = 0, last = -1;
      for (let i = 0; i < 8; i++) {
        const v = g.members[8 * k + i];
        if (v < 0) continue;
        if (i >= size || i !== count) packed = false;
        count++;
        seen[v]++;
        if (clusterOf[v] !== g.cluster[k]) sameCluster = false;
        if (v <= last) ordered = false;
        last = v;
        if (g.slot[v] !== k * size + i) slotsAgree = false;
      }
      perCluster[g.cluster[k]]++;
      const next = g.cluster[k + 1];
      if (count < size && next === g.cluster[k]) packed = false;  // only a cluster's last group is partly filled
    }
    check(seen.every((n) => n === 1), `groups of ${size}: a vertex is missing or repeated`);
    check(ordered && sameCluster && packed && slotsAgree, `groups of ${size}: order ${ordered}, one cluster a group ${sameCluster}, packed ${packed}, slots ${slotsAgree}`);
    const counts = new Array(8).fill(0);
    for (const k of clusterOf) counts[k]++;
    check(perCluster.every((n, k) => n === Math.ceil(counts[k] / size)), `groups of ${size}: ${perCluster} groups per cluster for ${counts} vertices`);
  }
  check(core.glossyGroups(clusterOf, 8, 1, 29, 7).groupSize === 8, 'mean cluster size 125, the dragon\'s shape: groups of 8');
  check(core.glossyGroups([0, 1, 2, 3], 4, 1, 29, 7).groupSize === 1, 'a cluster a vertex: groups of 1');
  check(core.glossyGroups([0, 0, 0, 1, 1, 1], 2, 1, 29, 7).groupSize === 2, 'three vertices a cluster: groups of 2');
  // 65 * 3 * 16 = 3120 dot products a member: groups of 2 stay within kMaxGlossyFusedDots (8192).
  check(core.glossyGroups(clusterOf, 8, 1, 64, 16).groupSize === 2, 'order 8, N\' = 64: groups of 2');
  for (const [ids, clusters, size, what] of [[[0, 1], 2, 0, 'size'], [[0, 1], 2, 9, 'size'], [[0, 5], 2, 4, 'cluster id']]) {
    const e = core.glossyGroups(ids, clusters, size, 4, 2);
    check(typeof e === 'string' && e.includes(what), `groups ${JSON.stringify([ids, clusters, size])}: ${e}`);
  }
}

// Bad input is a named error, not a crash.
{
  const bad = core.glossySyntheticCheck({ bands: 9, channels: 1, packing: 'full', clusters: 1, vectors: 1, weightBits: 8, seed: 1 },
    10, [0, 0, 1], lightingFor(1, 0), 1, true);
  check(typeof bad === 'string' && /bands/.test(bad), `order 9 accepted: ${bad}`);
  const badLight = core.glossySyntheticCheck({ bands: 2, channels: 1, packing: 'full', clusters: 1, vectors: 1, weightBits: 8, seed: 1 },
    10, [0, 0, 1], [1, 2, 3], 2, true);
  check(typeof badLight === 'string', 'short lighting accepted');
}

if (failures.length) {
  console.error(`${failures.length} of ${checks} checks failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
console.log(`glossy core: ${checks} checks passed`);
