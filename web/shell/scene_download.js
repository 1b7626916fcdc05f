// Fetching from prt-serve with errors a person can act on: JSON documents (the catalogue,
// the environment list) and a baked asset streamed straight into the memory the wasm
// client reserved for it, then decoded there.

// GETs `url` and parses it as JSON; throws an Error naming `what`, the URL and the cause.
export async function fetchJson(url, what) {
  let response;
  try {
    response = await fetch(url);
  } catch (e) {
    throw new Error(`Cannot reach the server for the ${what} (${url}): ${e.message}. Is prt-serve running?`);
  }
  if (!response.ok) throw new Error(`The server answered ${response.status} ${response.statusText} for the ${what} (${url}).`);
  try {
    return await response.json();
  } catch (e) {
    throw new Error(`The ${what} (${url}) is not valid JSON: ${e.message}`);
  }
}

// Downloads catalogue entry `entry` ({name, url, bytes}) into `app` (ClientApp:
// reserveAsset, then loadAsset decodes it), calling onProgress(receivedBytes,
// declaredBytes) per chunk and onDecoding() before decoding; throws an Error naming the scene on any failure (network,
// HTTP status, out of memory, the decoder's own message).
export async function downloadAsset(app, entry, onProgress, onDecoding = () => {}) {
  let response;
  try {
    response = await fetch(entry.url);
  } catch (e) {
    throw new Error(`Cannot reach the server for scene '${entry.name}': ${e.message}. Is prt-serve running?`);
  }
  if (!response.ok) throw new Error(`The server answered ${response.status} ${response.statusText} for scene '${entry.name}' (${entry.url}).`);
  const declared = Number(response.headers.get('Content-Length') || entry.bytes || 0);
  let chunks = [];
  let received = 0;
  const reader = response.body.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    chunks.push(value);
    received += value.length;
    onProgress(received, declared);
  }
  const memory = app.reserveAsset(received);
  if (!memory) throw new Error(`Out of memory: cannot hold scene '${entry.name}' (${(received / 1e6).toFixed(1)} MB).`);
  let offset = 0;
  for (const c of chunks) {
    memory.set(c, offset);
    offset += c.length;
  }
  chunks = null;
  onDecoding();
  const error = app.loadAsset();
  if (error) throw new Error(`Scene '${entry.name}' could not be loaded: ${error}`);
}
