// The PRT page: fetches the catalogue and a baked scene from prt-serve (with a progress
// bar), hands the bytes to the wasm client (shared C++ decoder + WebGL2 renderer), wires
// the panel (lil-gui), pointer and touch input, and exposes window.prtApp for tests
// (docs/web-client.md).
import GUI from './lil-gui.esm.min.js';
import createPrtModule from './prt_client.mjs';

const MODES = { unshadowed: 0, shadowed: 1, interreflected: 2, lambert: 3 };
const params = new URLSearchParams(location.search);
const canvas = document.getElementById('view');
const loadingText = document.getElementById('loading-text');
const loadingBar = document.getElementById('loading-bar');
const statsLine = document.getElementById('stats');

const state = {
  scene: params.get('scene') || '',
  mode: params.get('mode') || 'interreflected',
  order: 8,
  environment: params.get('env') || '',
  exposure: Number(params.get('exposure') || 0),
  envYaw: 0,
  envPitch: 0,
  intensity: 1,
  color: '#ffffff',
  background: true,
};
const stats = { frameMs: 0, bytesLoaded: 0, vertices: 0, order: 0 };
let app = null;
let scenes = [];
let lights = [];
let gui = null;

// ---- the test hook (docs/web-client.md) -------------------------------------------------
const hook = {
  ready: false,
  frames: 0,
  error: null,
  stats,
  lightSH() {
    if (!app) return [];
    const flat = app.lightSH();
    const rows = [];
    for (let i = 0; i < flat.length; i += 3) rows.push([flat[i], flat[i + 1], flat[i + 2]]);
    return rows;
  },
  // Canvas pixel (CSS pixels, origin top-left) where world point p appeared in the last frame.
  project(p) {
    if (!app) return null;
    const [x, y] = app.project(p[0], p[1], p[2]);
    return [(x * 0.5 + 0.5) * canvas.clientWidth, (0.5 - y * 0.5) * canvas.clientHeight];
  },
  // Benchmark: draws n frames back to back, each finished with a 1-pixel readPixels (so the
  // GPU work is inside the measurement), and returns the mean milliseconds per frame.
  timeFrames(n) {
    if (!app || !hook.ready) return NaN;
    const gl = canvas.getContext('webgl2');
    const pixel = new Uint8Array(4);
    const t0 = performance.now();
    for (let i = 0; i < n; i++) {
      app.render(canvas.width, canvas.height);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    }
    return (performance.now() - t0) / n;
  },
  set(options) {
    if ('mode' in options) state.mode = options.mode;
    if ('order' in options) state.order = options.order;
    if ('exposure' in options) state.exposure = options.exposure;
    if ('envRotation' in options) {
      const r = options.envRotation;
      [state.envYaw, state.envPitch] = Array.isArray(r) ? r : [r, 0];
    }
    if ('intensity' in options) state.intensity = options.intensity;
    if ('background' in options) state.background = options.background;
    if ('environment' in options) selectEnvironment(options.environment ?? 'white furnace');
    applyState();
    if (gui) gui.controllersRecursive().forEach((c) => c.updateDisplay());
    return hook.frames;
  },
};
window.prtApp = hook;

function fail(message) {
  hook.error = message;
  document.getElementById('loading').hidden = true;
  const box = document.getElementById('error');
  box.textContent = message;
  box.hidden = false;
  console.warn(`prt: ${message}`);  // warn, not error: tests tell expected failures from console errors
}

function progress(text, fraction) {
  loadingText.textContent = text;
  loadingBar.style.width = `${Math.round(100 * Math.max(0, Math.min(1, fraction)))}%`;
}

async function fetchJson(url, what) {
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

// Streams the asset straight into wasm memory, updating the progress bar.
async function downloadScene(entry) {
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
    stats.bytesLoaded = received;
    progress(`Loading ${entry.name}: ${(received / 1e6).toFixed(1)} of ${(declared / 1e6).toFixed(1)} MB`, declared ? received / declared : 0);
  }
  const memory = app.reserveAsset(received);
  if (!memory) throw new Error(`Out of memory: cannot hold scene '${entry.name}' (${(received / 1e6).toFixed(1)} MB).`);
  let offset = 0;
  for (const c of chunks) {
    memory.set(c, offset);
    offset += c.length;
  }
  chunks = null;
  progress(`Decoding ${entry.name}…`, 1);
  const error = app.loadAsset();
  if (error) throw new Error(`Scene '${entry.name}' could not be loaded: ${error}`);
}

function selectEnvironment(name) {
  state.environment = name;
  const light = lights.find((l) => l.name === name && l.usable);
  if (!light) {
    state.environment = 'white furnace';
    app.setWhiteFurnace(1);
    return;
  }
  const order = Math.round(Math.sqrt(light.coefficients.length));
  const error = app.setEnvironment(light.coefficients.flat(), order);
  if (error) fail(`Environment '${name}' is unusable: ${error}`);
}

function applyState() {
  if (!app) return;
  app.setMode(MODES[state.mode] ?? 2);
  app.setDisplayOrder(state.order);
  app.setExposure(state.exposure);
  app.setEnvRotation(state.envYaw, state.envPitch);
  const c = parseInt(state.color.slice(1), 16);
  const k = state.intensity;
  app.setLightColor(k * ((c >> 16) & 255) / 255, k * ((c >> 8) & 255) / 255, k * (c & 255) / 255);
  app.setBackground(state.background);
}

async function loadScene(name) {
  const entry = scenes.find((s) => s.name === name);
  if (!entry) throw new Error(`No scene named '${name}' in the catalogue.`);
  document.getElementById('loading').hidden = false;
  hook.ready = false;
  await downloadScene(entry);
  document.getElementById('loading').hidden = true;
  state.scene = name;
  stats.vertices = app.vertexCount();
  state.order = app.bakedOrder();
  applyState();
  hook.ready = true;
}

function buildGui() {
  gui = new GUI({ title: 'PRT' });
  if (window.innerWidth < 600) gui.close();
  const usable = scenes.filter((s) => s.usable).map((s) => s.name);
  gui.add(state, 'scene', usable).name('scene').onChange((n) => loadScene(n).catch((e) => fail(e.message)));
  gui.add(state, 'mode', Object.keys(MODES)).name('transfer').onChange(applyState);
  gui.add(state, 'order', 1, 8, 1).name('SH order').onChange(applyState);
  const envNames = ['white furnace', ...lights.filter((l) => l.usable).map((l) => l.name)];
  gui.add(state, 'environment', envNames).name('environment').onChange((n) => { selectEnvironment(n); applyState(); });
  gui.add(state, 'envYaw', -Math.PI, Math.PI, 0.01).name('light yaw').onChange(applyState);
  gui.add(state, 'envPitch', -1.5, 1.5, 0.01).name('light pitch').onChange(applyState);
  gui.add(state, 'intensity', 0, 10, 0.01).name('intensity').onChange(applyState);
  gui.addColor(state, 'color').name('light colour').onChange(applyState);
  gui.add(state, 'exposure', -8, 8, 0.1).name('exposure (EV)').onChange(applyState);
  gui.add(state, 'background').name('background').onChange(applyState);
}

// ---- input: drag orbits, shift/right drag turns the light, wheel/pinch zooms, two-finger drag pans
function setupInput() {
  const pointers = new Map();
  let lastPinch = 0;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button, shift: e.shiftKey });
  });
  const end = (e) => { pointers.delete(e.pointerId); lastPinch = 0; };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('pointermove', (e) => {
    const p = pointers.get(e.pointerId);
    if (!p || !app) return;
    const dx = e.clientX - p.x, dy = e.clientY - p.y;
    p.x = e.clientX;
    p.y = e.clientY;
    const scale = 4 / Math.max(canvas.clientWidth, canvas.clientHeight);
    if (pointers.size >= 2) {
      const [a, b] = [...pointers.values()];
      const dist = Math.hypot(a.x - b.x, a.y - b.y);
      if (lastPinch) app.zoom(lastPinch / Math.max(dist, 1));
      lastPinch = dist;
      app.pan(-dx * scale * 0.25, dy * scale * 0.25);
    } else if (p.button === 2 || p.shift || e.shiftKey) {
      state.envYaw = ((state.envYaw + dx * scale + Math.PI) % (2 * Math.PI) + 2 * Math.PI) % (2 * Math.PI) - Math.PI;
      state.envPitch = Math.max(-1.5, Math.min(1.5, state.envPitch + dy * scale));
      applyState();
      if (gui) gui.controllersRecursive().forEach((c) => c.updateDisplay());
    } else if (p.button === 1 || e.ctrlKey) {
      app.pan(-dx * scale * 0.5, dy * scale * 0.5);
    } else {
      app.orbit(-dx * scale, dy * scale);
    }
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    if (app) app.zoom(Math.exp(e.deltaY * 0.001));
  }, { passive: false });
  canvas.addEventListener('dblclick', () => app && app.frameScene());
}

function frame(now) {
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
  const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) {
    canvas.width = w;
    canvas.height = h;
  }
  if (hook.ready) {
    const t0 = performance.now();
    app.render(w, h);
    hook.frames++;
    stats.frameMs = 0.9 * stats.frameMs + 0.1 * (performance.now() - t0 + (frame.last ? now - frame.last - (performance.now() - t0) : 0));
    stats.order = app.displayOrder();
    statsLine.textContent = `${stats.frameMs.toFixed(1)} ms/frame · ${stats.vertices.toLocaleString()} vertices · ` +
      `SH order ${stats.order} (${stats.order * stats.order} coeffs) · ${state.mode} · ${(stats.bytesLoaded / 1e6).toFixed(2)} MB loaded`;
  }
  frame.last = now;
  requestAnimationFrame(frame);
}

async function main() {
  progress('Starting…', 0);
  if (!document.createElement('canvas').getContext('webgl2')) {
    fail('This page needs WebGL2, which this browser or device does not provide.');
    return;
  }
  let Module;
  try {
    Module = await createPrtModule();
  } catch (e) {
    fail(`The client's WebAssembly module could not be loaded: ${e.message || e}`);
    return;
  }
  app = new Module.ClientApp('#view');
  if (app.error()) {
    fail(app.error());
    return;
  }
  setupInput();
  requestAnimationFrame(frame);
  try {
    progress('Fetching the scene catalogue…', 0);
    const catalogue = await fetchJson('/api/scenes', 'scene catalogue');
    scenes = catalogue.scenes || [];
    const usable = scenes.filter((s) => s.usable);
    if (!usable.length) {
      const broken = scenes.filter((s) => !s.usable).map((s) => `${s.name}: ${s.error}`).join('\n');
      throw new Error(`The server has no usable scene.${broken ? `\n${broken}` : ''}`);
    }
    if (!state.scene || !scenes.some((s) => s.name === state.scene)) state.scene = usable[0].name;
    try {
      lights = (await fetchJson('/api/lights?order=8', 'environment list')).lights || [];
    } catch (e) {
      console.warn(`prt: ${e.message}; using the white furnace`);
      lights = [];
    }
    await loadScene(state.scene);
    selectEnvironment(state.environment || (lights.find((l) => l.usable) || { name: 'white furnace' }).name);
    applyState();
    buildGui();
  } catch (e) {
    fail(e.message);
  }
}

main();
