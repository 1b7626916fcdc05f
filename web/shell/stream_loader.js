// Progressive loading of a scene that prt-serve offers in parts (docs/server.md, "parts";
// docs/web-client.md, "Progressive loading"): the head and the mesh first, then per
// transfer pass (the displayed one first) its codec head, clusters and bands in order, each
// band re-uploaded as it arrives so the page shows an order-1 picture early and sharpens.
// The wasm client checks every byte (header, table, section and band checksums); this file
// only checks that the parts tile the file and arrive at their declared sizes. Parts marked
// "domain":"texel" (transfer textures: texel passes, and the atlas sections that come with
// the geometry) stream like the vertex ones; a pass is its kind, form and domain.

// The catalogue's names of the transfer passes, in the asset's kind order.
export const PASS_NAMES = ['unshadowed', 'shadowed', 'interreflected'];
const MAX_PARALLEL = 4;  // fetches in flight; bands are still applied strictly in order
let currentStream = 0;  // a newer streamAsset call abandons the older one (another scene picked)

class Superseded extends Error {}

// Checks the catalogue's part list against the file size: integers, in file order, tiling
// [0, bytes) exactly, the first one the head. Throws an Error naming the problem.
export function checkParts(parts, bytes) {
  if (!Array.isArray(parts) || parts.length === 0) throw new Error('the catalogue lists no parts');
  if (!Number.isSafeInteger(bytes) || bytes <= 0) throw new Error(`the catalogue's file size ${bytes} is not a positive integer`);
  let end = 0;
  parts.forEach((p, i) => {
    if (!p || !Number.isSafeInteger(p.offset) || !Number.isSafeInteger(p.size) || p.size <= 0 || typeof p.url !== 'string') {
      throw new Error(`part ${i} has no valid offset, size or url`);
    }
    if (p.offset !== end) throw new Error(`part ${i} starts at ${p.offset}, not where part ${i - 1} ends (${end})`);
    end = p.offset + p.size;
    if (p.kind === 'transfer-band' && !(Number.isInteger(p.band) && p.band >= 0)) throw new Error(`part ${i} has no valid band`);
    if (p.pass !== undefined && !PASS_NAMES.includes(p.pass)) throw new Error(`part ${i} names an unknown pass '${p.pass}'`);
    if (p.form !== undefined && !['vector', 'matrix', 'visibility'].includes(p.form)) throw new Error(`part ${i} names an unknown pass form '${p.form}'`);
    if (p.domain !== undefined && p.domain !== 'vertex' && p.domain !== 'texel') throw new Error(`part ${i} names an unknown domain '${p.domain}'`);
  });
  if (end !== bytes) throw new Error(`the parts cover ${end} bytes, the file has ${bytes}`);
  if (parts[0].kind !== 'head') throw new Error('the first part is not the head');
}

// Streams catalogue entry `entry` ({name, bytes, parts}) into `app` (ClientApp); `kinds`
// maps each of PASS_NAMES to the client's pass kind (the embind enum Module.ShadingMode,
// whose values app.mode() returns and app.streamPass / loadedBands take), `domains` maps
// 'vertex' and 'texel' to Module.TransferDomain (what app.source() returns). Resolves
// once the first picture can be drawn (geometry and band 0 of the displayed pass in the
// displayed domain, or that whole pass when it is float32), and keeps loading the rest in the
// background. `progress` (an object) gets bytesReceived, bytesTotal, transferBytesReceived,
// transferBytesTotal, updated per part; onProgress() is called after each. A failure before
// the first picture rejects; one after it goes to onError(Error). Either way the message
// names the scene and the problem (network, HTTP status, size, the decoder's own words).
// onComplete() runs once every part has been applied (not after a failure or a newer stream).
export function streamAsset(app, entry, { kinds, domains, progress = {}, onProgress = () => {}, onError = () => {}, onComplete = () => {} } = {}) {
  if (!kinds || PASS_NAMES.some((n) => !kinds[n])) throw new Error('streamAsset: kinds must give the client\'s pass kind for every pass name');
  if (!domains || !domains.vertex || !domains.texel) throw new Error('streamAsset: domains must give the client\'s vertex and texel domains');
  const fail = (message) => new Error(`Scene '${entry.name}' could not be loaded: ${message}`);
  try {
    checkParts(entry.parts, entry.bytes);
  } catch (e) {
    throw fail(`the catalogue's part list is unusable: ${e.message}`);
  }
  // Every part, the TPFL visibility pass's too (asset format 1.5: the texel passes' glossy term).
  const wanted = entry.parts;
  const transferParts = wanted.filter((p) => p.pass !== undefined);
  Object.assign(progress, {
    bytesReceived: 0,
    bytesTotal: wanted.reduce((s, p) => s + p.size, 0),
    transferBytesReceived: 0,
    transferBytesTotal: transferParts.reduce((s, p) => s + p.size, 0),
  });
  // Bands on the GPU per pass [unshadowed, shadowed, interreflected], 0 = not (yet) there
  // (the glossy passes': prtApp.glossyBands; the texel passes': prtApp.texelBands).
  Object.defineProperty(progress, 'loadedBands', { get: () => PASS_NAMES.map((n) => app.loadedBands(kinds[n])), configurable: true, enumerable: true });
  const generation = ++currentStream;
  const superseded = () => generation !== currentStream;
  if (!app.reserveStream(entry.bytes)) throw new Error(`Out of memory: cannot hold scene '${entry.name}' (${(entry.bytes / 1e6).toFixed(1)} MB).`);

  let failed = false;
  const fetchPart = async (part) => {
    let response;
    try {
      response = await fetch(part.url);
    } catch (e) {
      throw new Error(`Cannot reach the server for scene '${entry.name}' (${part.url}): ${e.message}. Is prt-serve running?`);
    }
    if (!response.ok) throw new Error(`The server answered ${response.status} ${response.statusText} for a part of scene '${entry.name}' (${part.url}).`);
    const body = new Uint8Array(await response.arrayBuffer());
    if (superseded()) throw new Superseded();  // the buffer now belongs to another scene
    if (body.length !== part.size) {
      throw fail(`truncated: part ${part.url} (bytes ${part.offset}..${part.offset + part.size}) arrived with ${body.length} of its ${part.size} bytes`);
    }
    if (failed) return;
    const memory = app.streamBuffer();  // re-taken: wasm memory growth detaches old views
    // Gone or resized: a whole-asset load (which frees it) or another stream took over.
    if (!memory || memory.length !== entry.bytes) throw new Superseded();
    memory.set(body, part.offset);
    progress.bytesReceived += part.size;
    if (part.pass !== undefined) progress.transferBytesReceived += part.size;
    onProgress();
  };

  // Runs fetchPart over `parts` with at most MAX_PARALLEL in flight, in list order, calling
  // onDone(index) after each arrives (in arrival order).
  const fetchAll = (parts, onDone) => new Promise((resolve, reject) => {
    let next = 0, inFlight = 0, done = 0;
    const pump = () => {
      if (failed) return;
      if (done === parts.length) { resolve(); return; }
      while (inFlight < MAX_PARALLEL && next < parts.length) {
        const i = next++;
        inFlight++;
        fetchPart(parts[i]).then(() => {
          if (failed) return;
          inFlight--;
          done++;
          onDone(i);
          pump();
        }).catch((e) => { failed = true; reject(e); });
      }
    };
    pump();
  });

  const run = async (onFirstPicture) => {
    // The head, the mesh and (for transfer textures) the atlas sections.
    await fetchAll(wanted.filter((p) => p.pass === undefined), () => {});
    const geometryError = app.streamGeometry();
    if (geometryError) throw fail(geometryError);
    const displayed = app.mode();
    const displayedDomain = app.source() === domains.texel ? 'texel' : 'vertex';
    let shown = false;
    // Glossy matrix passes the server did not cut into parts (no `form: matrix` parts: their
    // sections came whole with the geometry's): uploaded whole now.
    for (const name of PASS_NAMES) {
      const k = kinds[name];
      if (app.hasGlossy(k) && !transferParts.some((p) => p.pass === name && p.form === 'matrix')) {
        const error = app.streamGlossyPass(k, 0);
        if (error) throw fail(error);
      }
    }
    // A visibility pass the server did not list as parts of its own came whole with the geometry.
    if (app.hasTexelGlossy() && !transferParts.some((p) => p.form === 'visibility')) {
      const error = app.streamVisibilityPass(0);
      if (error) throw fail(error);
    }
    const domainOf = (p) => (p.domain === 'texel' ? 'texel' : 'vertex');
    if (app.hasAnyPass(displayed) && !transferParts.some((p) => kinds[p.pass] === displayed && domainOf(p) === displayedDomain)) {
      shown = true;  // a glossy-only displayed pass, whole already
      onFirstPicture();
    }
    // The displayed pass first, then the others in file order; a pass is its kind, form and
    // domain ("shadowed/vector/vertex", the glossy "shadowed/matrix/vertex", the transfer
    // texture "shadowed/vector/texel", the TPFL "shadowed/visibility/texel"), each streamed band by band.
    const formOf = (p) => (p.form === 'matrix' || p.form === 'visibility' ? p.form : 'vector');
    const keyOf = (p) => `${p.pass}/${formOf(p)}/${domainOf(p)}`;
    const passKeys = [...new Set(transferParts.map(keyOf))];
    const isDisplayed = (key) => {
      const [name, form, domain] = key.split('/');
      return kinds[name] === displayed && domain === displayedDomain && form !== 'visibility';
    };
    passKeys.sort((a, b) => isDisplayed(b) - isDisplayed(a));
    const queue = passKeys.flatMap((key) => transferParts.filter((p) => keyOf(p) === key));
    const arrived = new Array(queue.length).fill(false);
    const applied = new Map();  // pass key -> bands uploaded
    // Applies, per pass, the longest run of arrived parts from its start: a pass's bands go
    // up strictly in order whatever order the fetches finish in.
    const apply = () => {
      for (const key of passKeys) {
        const [name, form, domain] = key.split('/');
        const k = kinds[name];
        const parts = queue.map((p, i) => [p, i]).filter(([p]) => keyOf(p) === key);
        let bands = 0, whole = false;
        for (const [p, i] of parts) {
          if (!arrived[i]) break;
          if (p.kind === 'transfer-band') bands = p.band + 1;
          else if (p.kind === 'section') whole = true;  // a float32 (or unsplittable) pass
        }
        if (!whole && bands === 0) continue;
        const request = whole ? 0 : bands;
        if (applied.get(key) === (whole ? 'all' : bands)) continue;
        const error = form === 'matrix' ? app.streamGlossyPass(k, request)
          : form === 'visibility' ? app.streamVisibilityPass(request)
            : domain === 'texel' ? app.streamTexelPass(k, request) : app.streamPass(k, request);
        if (error) throw fail(error);
        applied.set(key, whole ? 'all' : bands);
        if (isDisplayed(key) && !shown) {
          shown = true;
          onFirstPicture();
        }
      }
    };
    await fetchAll(queue, (i) => {
      arrived[i] = true;
      try {
        apply();
      } catch (e) {
        failed = true;
        throw e;
      }
    });
    if (!shown) throw fail(`the parts hold no transfer for the displayed pass`);
  };

  return new Promise((resolve, reject) => {
    let first = false;
    run(() => { first = true; resolve(); }).then(() => {
      app.endStream();
      onComplete();
    }, (e) => {
      failed = true;
      if (e instanceof Superseded) return;  // quietly: the newer stream owns the buffer and the page
      app.endStream();
      if (first) onError(e);
      else reject(e);
    });
  });
}
