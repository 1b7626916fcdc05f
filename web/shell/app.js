// The PRT page: fetches the catalogue and a baked scene from prt-serve (with a progress
// bar), hands the bytes to the wasm client (shared C++ decoder + WebGL2 renderer), wires
// the panel (lil-gui), pointer and touch input, and installs window.prtApp for tests and
// benchmarks (test_hook.js; docs/web-client.md).
import GUI from './lil-gui.esm.min.js';
import createPrtModule from './prt_client.mjs';
import { LightSet } from './light_set.js';
import { LightDrag } from './light_drag.js';
import { LightsPanel } from './lights_panel.js';
import { fetchJson, downloadAsset } from './scene_download.js';
import { ScenePicker } from './scene_picker.js';
import { streamAsset, PASS_NAMES } from './stream_loader.js';
import { installTestHook } from './test_hook.js';
import { encodePermalink, decodePermalink } from './permalink.js';

const LIGHTING_MODELS = ['distant', 'local-sphere', 'local-sphere-paper'];  // prt::LightingModel
const PROJECTIONS = { analytic: 2, gpu: 0, cpu: 1 };
const params = new URLSearchParams(location.search);
const canvas = document.getElementById('view');
const loadingText = document.getElementById('loading-text');
const loadingBar = document.getElementById('loading-bar');
const statsLine = document.getElementById('stats');
const noticeBox = document.getElementById('notice');
const helpBox = document.getElementById('help');

const state = {
  scene: params.get('scene') || '',
  mode: params.get('mode') || 'interreflected',
  order: 1,  // client.maxOrder once the module is loaded; then each scene's baked order
  environment: params.get('env') || '',
  exposure: Number(params.get('exposure') || 0),
  envYaw: 0,
  envPitch: 0,
  intensity: 1,
  color: '#ffffff',
  // Behind the scene: 'image' (the map itself), 'blurred' (its SH, the light the scene gets),
  // 'colour' (backgroundColor) or 'none' (docs/web-client.md, "Background").
  background: 'image',
  backgroundColor: '#1a1a1a',
  // CPCA-compressed passes: rendered straight from the clusters, or expanded on load.
  cpca: ['expand', 'expanded'].includes(params.get('cpca')) ? 'expanded' : 'direct',
  // Per pass, which terms are drawn: 'diffuse' (vector pass), 'glossy' (matrix pass) or 'both'.
  glossyMix: { unshadowed: 'both', shadowed: 'both', interreflected: 'both' },
  // Which passes are drawn: 'vertex' or 'texel' (transfer textures). A wish: a scene without
  // texel passes is drawn per vertex, a texel-only one per texel (app.source() says which).
  source: params.get('source') === 'texel' ? 'texel' : 'vertex',
  // Bi-scale scenes (docs/bi-scale.md): the RTT's meso scale per fragment (a wish: scenes
  // without an RTT draw PRT), and its view dependence (the paper's Figure 6 switch).
  biScale: true,
  viewDependence: true,
};
const GLOSSY_MIXES = ['diffuse', 'glossy', 'both'];
const BACKGROUNDS = ['image', 'blurred', 'colour', 'none'];  // BackgroundMode's names
// The dynamic-light settings the Lights panel edits (docs/web-client.md).
const lightSettings = { projection: 'analytic', cubeSize: 64, environmentOn: true };
const stats = { frameMs: 0, bytesLoaded: 0, vertices: 0, order: 0 };
let app = null;
// What the wasm module gives besides ClientApp, filled in once it is loaded: maxOrder, the
// SH bands the client renders with (Module.kMaxClientOrder, client_limits.h); the embind
// enums (client_bindings.cpp) ShadingMode (unshadowed, shadowed, interreflected: also the
// pass kinds; lambert) and PassForm (absent, expanded, cpca); modeNames, ShadingMode's
// value names (the transfer choices); formName(form): 'expanded', 'cpca' or null (absent).
const client = { maxOrder: 1, ShadingMode: null, PassForm: null, GlossyMix: null, TransferDomain: null, BackgroundMode: null, modeNames: [],
  formName: () => null };
// The names of an embind enum's values, in value order (the enum object also holds `values`).
const enumNames = (e) => Object.keys(e).filter((k) => k !== 'values').sort((a, b) => e[a].value - e[b].value);
let scenes = [];
let environments = [];  // /api/lights: environment maps as radiance SH
let gui = null;
let lightSet = null;
let lightDrag = null;
let lightsPanel = null;

// ---- the test hook, window.prtApp (test_hook.js; docs/web-client.md) --------------------
const hook = installTestHook({
  get app() { return app; },
  get lightSet() { return lightSet; },
  client,
  canvas,
  state,
  lightSettings,
  stats,
  lightingModels: LIGHTING_MODELS,
  projections: PROJECTIONS,
  loadScene,
  environmentNames,
  selectEnvironment,
  applyState,
  applyLightSettings,
  currentView,
  permalink,
  scale: () => sceneRadius,
  refreshGui: () => { if (gui) gui.controllersRecursive().forEach((c) => c.updateDisplay()); },
});

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

// Streams the asset into wasm memory (scene_download.js), updating the progress bar.
async function downloadScene(entry) {
  await downloadAsset(app, entry, (received, declared) => {
    stats.bytesLoaded = received;
    progress(`Loading ${entry.name}: ${(received / 1e6).toFixed(1)} of ${(declared / 1e6).toFixed(1)} MB`, declared ? received / declared : 0);
  }, () => progress(`Decoding ${entry.name}…`, 1));
}

// 'white furnace' and the usable environment maps, the names set({environment}) takes.
function environmentNames() {
  return ['white furnace', ...environments.filter((l) => l.usable).map((l) => l.name)];
}

function selectEnvironment(name) {
  state.environment = name;
  hook.backgroundImage = null;  // the client drops the previous map's image; applyState asks for this one's
  const light = environments.find((l) => l.name === name && l.usable);
  if (!light) {
    state.environment = 'white furnace';
    app.setWhiteFurnace(1);
    return;
  }
  const order = Math.round(Math.sqrt(light.coefficients.length));
  const error = app.setEnvironment(light.coefficients.flat(), order);
  if (error) fail(`Environment '${name}' is unusable: ${error}`);
}

// ---- the image background (docs/web-client.md, "Background") ---------------------------
// Each map's RGB9E5 texture (/api/lights: background {url, width, height}), fetched once,
// only after the scene has streamed completely: the first lit frame and the sharpening
// bands never wait for the sky.
const backgroundImages = new Map();  // environment name -> {width, height, texels: Uint32Array}
let sceneStreamed = Promise.resolve();
let sceneStreamedResolve = null;
let backgroundFetches = 0;

// A new promise for the scene now loading; the previous one resolves, so nothing waits on
// a stream that a newer one replaced.
function startSceneStream() {
  const previous = sceneStreamedResolve;
  sceneStreamed = new Promise((resolve) => { sceneStreamedResolve = resolve; });
  if (previous) previous();
}

async function fetchBackground({ url, width, height }) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`HTTP ${r.status} for ${url}`);
  const bytes = await r.arrayBuffer();
  if (bytes.byteLength !== width * height * 4) throw new Error(`${bytes.byteLength} bytes for ${width}x${height} RGB9E5 texels`);
  return { width, height, texels: new Uint32Array(bytes) };  // little-endian, as every WebGL platform
}

// Gives the client the current map's image when the image background is on: at once from
// the cache, else after the scene has streamed and the fetch is done (prtApp.backgroundLoading
// meanwhile, with the blurred background standing in). Maps without an image (the white
// furnace, angular and cross layouts) keep the blurred one.
async function ensureBackground() {
  const name = state.environment;
  const light = environments.find((l) => l.name === name && l.usable);
  if (!app || !light || !light.background || (hook.backgroundImage && hook.backgroundImage.environment === name)) return;
  let image = backgroundImages.get(name);
  if (!image) {
    if (ensureBackground.pending === name) return;  // already on its way
    ensureBackground.pending = name;
    hook.backgroundLoading = ++backgroundFetches > 0;
    try {
      await sceneStreamed;
      image = await fetchBackground(light.background);
      backgroundImages.set(name, image);
    } catch (e) {
      notify(`The background image of '${name}' could not be loaded (${e.message}); showing the blurred environment.`);
      return;
    } finally {
      ensureBackground.pending = null;
      hook.backgroundLoading = --backgroundFetches > 0;
    }
    if (state.environment !== name || state.background !== 'image') return;  // changed meanwhile
  }
  const error = app.setBackgroundImage(image.width, image.height, image.texels);
  if (error) {
    notify(`The background image of '${name}' was refused (${error}); showing the blurred environment.`);
    return;
  }
  hook.backgroundImage = { environment: name, width: image.width, height: image.height };
}

function applyState() {
  if (!app) return;
  const { ShadingMode, modeNames } = client;
  app.setSource(client.TransferDomain[state.source]);  // first: setMode asks whether the drawn domain has the pass
  app.setMode(modeNames.includes(state.mode) ? ShadingMode[state.mode] : ShadingMode.interreflected);
  app.setDisplayOrder(state.order);
  app.setExposure(state.exposure);
  app.setEnvRotation(state.envYaw, state.envPitch);
  const c = parseInt(state.color.slice(1), 16);
  const k = state.intensity;
  app.setLightColor(k * ((c >> 16) & 255) / 255, k * ((c >> 8) & 255) / 255, k * (c & 255) / 255);
  app.setBackgroundMode(client.BackgroundMode[state.background]);
  const b = parseInt(state.backgroundColor.slice(1), 16);
  app.setBackgroundColour(((b >> 16) & 255) / 255, ((b >> 8) & 255) / 255, (b & 255) / 255);
  if (state.background === 'image') ensureBackground();
  for (const name of PASS_NAMES) app.setGlossyMix(ShadingMode[name], client.GlossyMix[state.glossyMix[name]]);
  app.setBiScale(state.biScale);
  app.setViewDependence(state.viewDependence);
  updateGlossyControl();
  updateBiScaleControls();
  updateSourceControl();
}

// The panel's bi-scale switches (meso scale on/off, view dependence): shown only for a scene
// with an RTT.
let biScaleControls = [];
function updateBiScaleControls() {
  if (!app) return;
  for (const c of biScaleControls) {
    c.show(app.biScaleOrder() > 0);
    c.updateDisplay();
  }
}

// The panel's "transfer source" switch (vertex / texel passes): shown only when the scene has both.
let sourceControl = null;
function updateSourceControl() {
  if (!sourceControl || !app) return;
  const { TransferDomain } = client;
  sourceControl.show(app.hasSource(TransferDomain.vertex) && app.hasSource(TransferDomain.texel));
  sourceControl.updateDisplay();
}

// The panel's "glossy" switch edits the displayed pass's mix; shown only when that pass has
// a glossy matrix pass (the asset's matrix passes: shadowed, interreflected).
let glossyControl = null;
const glossyView = {
  get mix() { return state.glossyMix[state.mode] || 'both'; },
  set mix(v) { if (PASS_NAMES.includes(state.mode)) state.glossyMix[state.mode] = v; },
};
function updateGlossyControl() {
  if (!glossyControl || !app) return;
  // Per vertex: the pass's glossy matrix pass; per texel: the TPFL visibility pass, whose
  // glossy term every texel pass adds.
  const texel = app.source() === client.TransferDomain.texel;
  const has = PASS_NAMES.includes(state.mode) && (texel ? app.hasTexelGlossy() : app.hasGlossy(client.ShadingMode[state.mode]));
  glossyControl.show(has);
  glossyControl.updateDisplay();
}

// Pushes the Lights panel's settings to the client; returns "" or why the GPU projection
// is unavailable (the client then projects on the CPU, and the panel says so).
function applyLightSettings() {
  if (!app) return '';
  let error = app.setProjection(PROJECTIONS[lightSettings.projection]);
  if (error) {
    lightSettings.projection = 'cpu';
    notify(`GPU projection unavailable (${error}); projecting on the CPU.`);
  }
  const sizeError = app.setCubeSize(lightSettings.cubeSize);
  if (sizeError) error = error || sizeError;
  app.setEnvironmentEnabled(lightSettings.environmentOn);
  return error;
}

// Scene radius in world units, for default light placement and the panel's slider ranges:
// the local lighting sphere's radius, or for distant scenes the radius of the bounding
// sphere the camera frames (ClientApp::sceneRadius).
let sceneRadius = 1;
function measureSceneRadius() {
  const r = app.lightingRadius();
  return r > 0 ? r : app.sceneRadius();
}

// A scene baked for local lighting opens with one sphere light above the light centre c
// and to the viewer's left (the panel covers the right), inside the lighting sphere, so
// the first view shows the light, its soft shadows and the floor's gradient; distant
// scenes open with the environment alone.
function defaultLights() {
  if (app.lightingModel() === 0) return [];
  const c = Array.from(app.lightCenter()), r = sceneRadius;
  const ray = Array.from(app.rayFromScreen(0, 0));
  const f = ray.length === 6 && ray.every(Number.isFinite) ? ray.slice(3) : [0, 0, -1];
  let right = [-f[2], 0, f[0]];  // forward x up
  const length = Math.hypot(...right);
  right = length > 1e-3 ? right.map((x) => x / length) : [1, 0, 0];
  const offset = [0, 1, 2].map((k) => r * (-0.3 * right[k] + (k === 1 ? 0.3 : 0) - 0.1 * f[k]));
  return [{ shape: 'sphere', position: c.map((x, k) => x + offset[k]), radius: 0.07 * r, color: [1, 0.92, 0.8], intensity: 40 }];
}

// Shows a non-fatal message for 8 s, or with `sticky` until it is clicked (a link's bad
// values: the page may take longer than 8 s to show the scene they are about).
function notify(message, { sticky = false } = {}) {
  hook.notice = message;
  noticeBox.textContent = message;
  noticeBox.hidden = false;
  console.warn(`prt: ${message}`);
  clearTimeout(notify.timer);
  if (!sticky) notify.timer = setTimeout(() => { noticeBox.hidden = true; }, 8000);
}

function toggleHelp(show = helpBox.hidden) {
  helpBox.hidden = !show;
  if (!show || !hook.ready) return;
  const c = Array.from(app.lightCenter()).map((x) => x.toFixed(2)).join(', ');
  const model = LIGHTING_MODELS[app.lightingModel()];
  document.getElementById('help-scene').textContent = app.lightingModel() === 0
    ? `This scene was baked for distant lighting: lights act only through their direction from c = (${c}).`
    : `This scene was baked for local lighting (${model}): c = (${c}), r = ${app.lightingRadius().toFixed(2)}.`;
}

async function loadScene(name) {
  const entry = scenes.find((s) => s.name === name);
  if (!entry) throw new Error(`No scene named '${name}' in the catalogue.`);
  document.getElementById('loading').hidden = false;
  hook.ready = false;
  app.setCpcaDirect(state.cpca === 'direct');
  app.setSource(client.TransferDomain[state.source]);  // so the displayed domain's pass streams first
  startSceneStream();
  const streamed = sceneStreamedResolve;
  if (entry.parts) {
    // Progressive: resolves at the first picture (band 0 of the displayed pass); the other
    // bands and passes keep arriving (stream_loader.js). prtApp gets the byte counters.
    await streamAsset(app, entry, {
      kinds: client.ShadingMode,
      domains: client.TransferDomain,
      progress: hook,
      onProgress: () => {
        stats.bytesLoaded = hook.bytesReceived;
        progress(`Loading ${entry.name}: ${(hook.bytesReceived / 1e6).toFixed(1)} of ${(hook.bytesTotal / 1e6).toFixed(1)} MB`, hook.bytesReceived / hook.bytesTotal);
      },
      onError: (e) => {
        streamed();  // the background need not wait for parts that will not come
        fail(e.message);
      },
      onComplete: streamed,
    });
  } else {
    await downloadScene(entry);
    streamed();
  }
  document.getElementById('loading').hidden = true;
  state.scene = name;
  stats.vertices = app.vertexCount();
  state.order = app.bakedOrder();
  applyState();
  // Render once so rayFromScreen has a camera to place the default light with.
  app.render(Math.max(1, canvas.width), Math.max(1, canvas.height));
  sceneRadius = measureSceneRadius();
  lightSettings.environmentOn = app.lightingModel() === 0 || params.has('env');
  applyLightSettings();
  lightSet.set(defaultLights());
  hook.ready = true;
}

// ---- permalinks (permalink.js; docs/web-client.md, "Permalinks") ------------------------
// What a link holds: the page's view now (the camera from the client).
function currentView() {
  // Mesh lights from OBJ files name a mesh only this page has (its file is not on the
  // server), so links leave them out; the torus is built in and stays.
  const lights = lightSet.snapshot().filter((l) => l.shape !== 'mesh' || l.mesh === 'torus');
  return {
    scene: state.scene,
    camera: Array.from(app.cameraPose()),
    environment: state.environment,
    environmentOn: lightSettings.environmentOn,
    envYaw: state.envYaw,
    envPitch: state.envPitch,
    intensity: state.intensity,
    color: state.color,
    exposure: state.exposure,
    background: state.background,
    backgroundColor: state.backgroundColor,
    mode: state.mode,
    order: state.order,
    source: state.source,
    glossyMix: { ...state.glossyMix },
    biScale: state.biScale,
    viewDependence: state.viewDependence,
    projection: lightSettings.projection,
    cubeSize: lightSettings.cubeSize,
    lights,
  };
}

// The page's URL with the current view in its fragment (the query kept: ?cpca still applies).
function permalink() {
  const view = currentView();
  const href = `${location.origin}${location.pathname}${location.search}#${encodePermalink(view)}`;
  return { href, droppedLights: lightSet.lights.length - view.lights.length };
}

// The panel's "copy link": the link goes to the clipboard and the address bar. The clipboard
// needs a secure context (HTTPS or localhost); elsewhere the address bar is the way.
async function copyLink() {
  const { href, droppedLights } = permalink();
  history.replaceState(null, '', href);
  hook.link = href;
  const dropped = droppedLights ? ` (without ${droppedLights} OBJ mesh light${droppedLights === 1 ? '' : 's'}: their files are not on the server)` : '';
  try {
    await navigator.clipboard.writeText(href);
    notify(`Link copied${dropped}.`);
  } catch {
    notify(`The browser refused the clipboard: copy the link from the address bar${dropped}.`);
  }
}

// The fragment's view, read against what this server and module offer; fields needed before
// the scene loads (scene, source, mode: the displayed pass streams first) go to state now,
// `before` keeps the source they replaced in case the scene turns out to lack it.
function readLinkView() {
  const { view, problems } = decodePermalink(location.hash, {
    scenes: scenes.filter((s) => s.usable).map((s) => s.name),
    environments: environmentNames(),
    modes: client.modeNames,
    maxOrder: client.maxOrder,
    projections: Object.keys(PROJECTIONS),
  });
  const before = { source: state.source };
  for (const key of ['scene', 'source', 'mode']) if (key in view) state[key] = view[key];
  return { view, problems, before };
}

// Applies the rest of a link's view once its scene is loaded; a value the scene cannot
// take joins `problems`, keeps the default, and the notice lists them all.
function applyLinkView({ view, problems, before }) {
  const { TransferDomain } = client;
  for (const key of ['envYaw', 'envPitch', 'intensity', 'color', 'exposure', 'background', 'backgroundColor', 'biScale', 'viewDependence']) {
    if (key in view) state[key] = view[key];
  }
  if ('glossyMix' in view) Object.assign(state.glossyMix, view.glossyMix);
  if ('environment' in view) selectEnvironment(view.environment);
  if ('environmentOn' in view) lightSettings.environmentOn = view.environmentOn;
  if ('projection' in view) lightSettings.projection = view.projection;
  if ('cubeSize' in view) lightSettings.cubeSize = view.cubeSize;
  if ('source' in view && !app.hasSource(TransferDomain[view.source])) {
    problems.push(`source=${view.source}: scene '${state.scene}' has no ${view.source} passes`);
    state.source = before.source;
  }
  if ('order' in view) {
    if (view.order <= app.bakedOrder()) state.order = view.order;
    else problems.push(`order=${view.order} is above scene '${state.scene}''s baked order ${app.bakedOrder()}`);
  }
  if ('camera' in view && !app.setCameraPose(view.camera)) problems.push(`camera=${view.camera.join(',')} was refused`);
  if ('lights' in view) {
    try {
      lightSet.set(view.lights);
    } catch (e) {
      problems.push(`lights: ${e.message}`);
    }
  }
  applyState();
  const projectionError = applyLightSettings();
  if (projectionError && 'projection' in view) problems.push(`projection=${view.projection}: ${projectionError}`);
  if (problems.length) {
    hook.linkProblems = problems.slice();
    notify(`This link has values the page cannot use; defaults shown instead: ${problems.join('; ')}. (Click to close.)`, { sticky: true });
  }
}

function buildGui() {
  gui = new GUI({ title: 'PRT' });
  if (window.innerWidth < 600) gui.close();
  const usable = scenes.filter((s) => s.usable).map((s) => s.name);
  gui.add({ copyLink }, 'copyLink').name('copy link');  // first: what people look for when sharing
  const sceneControl = gui.add(state, 'scene', usable).name('scene').onChange((n) => pickScene(n));
  // The same choice as pictures (server-made thumbnails, placeholders where there are none).
  const sceneFolder = gui.addFolder('scenes');
  const pickScene = (n) => loadScene(n).then(() => { sceneControl.updateDisplay(); picker.select(state.scene); })
    .catch((e) => fail(e.message));
  const pickerBox = document.createElement('div');  // inside lil-gui's own children box, which it hides when closed
  sceneFolder.$children.append(pickerBox);
  const picker = new ScenePicker(pickerBox, scenes.filter((s) => s.usable), pickScene);
  picker.select(state.scene);
  if (usable.length < 2 || window.innerWidth < 600) sceneFolder.close();
  gui.add(state, 'mode', client.modeNames).name('transfer').onChange(applyState);
  glossyControl = gui.add(glossyView, 'mix', GLOSSY_MIXES).name('diffuse / glossy').onChange(applyState);
  updateGlossyControl();
  biScaleControls = [gui.add(state, 'biScale').name('bi-scale (RTT)').onChange(applyState),
    gui.add(state, 'viewDependence').name('RTT view dependence').onChange(applyState)];
  updateBiScaleControls();
  sourceControl = gui.add(state, 'source', ['vertex', 'texel']).name('transfer source').onChange(applyState);
  updateSourceControl();
  gui.add(state, 'cpca', ['direct', 'expanded']).name('CPCA rendering')
    .onChange(() => loadScene(state.scene).catch((e) => fail(e.message)));
  gui.add(state, 'order', 1, client.maxOrder, 1).name('SH order').onChange(applyState);
  const envNames = ['white furnace', ...environments.filter((l) => l.usable).map((l) => l.name)];
  gui.add(state, 'environment', envNames).name('environment').onChange((n) => {
    selectEnvironment(n);
    lightSettings.environmentOn = true;  // picking a map means wanting to see it
    applyState();
    applyLightSettings();
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  });
  gui.add(state, 'envYaw', -Math.PI, Math.PI, 0.01).name('env yaw').onChange(applyState);
  gui.add(state, 'envPitch', -1.5, 1.5, 0.01).name('env pitch').onChange(applyState);
  gui.add(state, 'intensity', 0, 10, 0.01).name('env intensity').onChange(applyState);
  gui.addColor(state, 'color').name('env colour').onChange(applyState);
  gui.add(state, 'exposure', -8, 8, 0.1).name('exposure (EV)').onChange(applyState);
  gui.add(state, 'background', BACKGROUNDS).name('background').onChange(applyState);
  gui.addColor(state, 'backgroundColor').name('background colour').onChange(applyState);
  lightsPanel = new LightsPanel(gui, {
    lightSet,
    settings: lightSettings,
    applySettings() {
      applyLightSettings();
      gui.controllersRecursive().forEach((c) => c.updateDisplay());
    },
    scale: () => sceneRadius,
    centre: () => Array.from(app.lightCenter()),
    notify,
    showHelp: () => toggleHelp(true),
  });
}

// ---- input: a press on a light drags it (light_drag.js); otherwise drag orbits, shift/right
// drag turns the environment, wheel/pinch zooms, two-finger drag pans
function setupInput() {
  const pointers = new Map();
  let lastPinch = 0;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    try {
      canvas.setPointerCapture(e.pointerId);
    } catch {
      // A pointer the browser no longer tracks (lifted already, or synthetic): nothing to capture.
    }
    if (hook.ready && lightDrag && !pointers.size && lightDrag.pointerDown(e)) return;
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button, shift: e.shiftKey });
  });
  const end = (e) => {
    if (lightDrag && lightDrag.pointerUp(e)) return;
    pointers.delete(e.pointerId);
    lastPinch = 0;
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('pointermove', (e) => {
    if (lightDrag && lightDrag.dragging) {
      try {
        lightDrag.pointerMove(e);
      } catch (err) {
        notify(err.message);
      }
      return;
    }
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

// " (CPCA: K clusters, N weights)" when the displayed pass is drawn from its clusters.
function formText() {
  if (!PASS_NAMES.includes(state.mode) || app.source() === client.TransferDomain.texel) return '';
  const kind = client.ShadingMode[state.mode];
  if (app.passForm(kind) !== client.PassForm.cpca) return '';
  const [clusters, weights] = app.cpcaShape(kind);
  return ` (CPCA: ${clusters} clusters, ${weights} weights)`;
}

// " per texel (W×H atlas)" when the displayed pass is a transfer texture.
function sourceText() {
  if (!PASS_NAMES.includes(state.mode) || app.source() !== client.TransferDomain.texel) return '';
  const sizes = Array.from(app.atlasSizes());
  const atlases = [];
  for (let i = 0; i < sizes.length; i += 2) atlases.push(`${sizes[i]}×${sizes[i + 1]}`);
  return ` per texel (${atlases.join(', ')} atlas${atlases.length === 1 ? '' : 'es'})`;
}

// " + glossy (order b, K clusters, N' matrices)" when the displayed pass draws a glossy term.
function glossyText() {
  if (!PASS_NAMES.includes(state.mode)) return '';
  if (app.source() === client.TransferDomain.texel) {
    const m = app.texelGlossyBands();
    return m ? ` · ${state.glossyMix[state.mode]}: TPFL glossy, visibility order ${m}` : '';
  }
  const kind = client.ShadingMode[state.mode];
  const bands = app.glossyBands(kind);
  if (!bands) return '';
  const [clusters, vectors] = app.glossyShape(kind);
  return ` · ${state.glossyMix[state.mode]}: glossy order ${Math.min(bands, stats.order)}/${bands} (${clusters} clusters, ${vectors} matrices)`;
}

function frame(now) {
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
  const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) {
    canvas.width = w;
    canvas.height = h;
  }
  if (hook.ready && !hook.paused) {
    const t0 = performance.now();
    app.render(w, h);
    hook.frames++;
    stats.frameMs = 0.9 * stats.frameMs + 0.1 * (performance.now() - t0 + (frame.last ? now - frame.last - (performance.now() - t0) : 0));
    stats.order = app.displayOrder();
    statsLine.textContent = `${stats.frameMs.toFixed(1)} ms/frame · ${stats.vertices.toLocaleString()} vertices · ` +
      `SH order ${stats.order} (${stats.order * stats.order} coeffs) · ${state.mode}${sourceText()}${formText()}${glossyText()} · ${(stats.bytesLoaded / 1e6).toFixed(2)} MB loaded · ` +
      `${LIGHTING_MODELS[app.lightingModel()]} lighting · ${lightSet.lights.length} light${lightSet.lights.length === 1 ? '' : 's'} ` +
      `(${lightSettings.projection} ${lightSettings.cubeSize}²)${lightSettings.environmentOn ? ' + environment' : ''}`;
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
  const { ShadingMode, PassForm, GlossyMix, TransferDomain, BackgroundMode } = Module;
  Object.assign(client, {
    maxOrder: Module.kMaxClientOrder,
    ShadingMode,
    PassForm,
    GlossyMix,
    TransferDomain,
    BackgroundMode,
    modeNames: enumNames(ShadingMode),
    formName: (form) => (form === PassForm.absent ? null : enumNames(PassForm).find((n) => PassForm[n] === form)),
  });
  state.order = client.maxOrder;
  app = new Module.ClientApp('#view');
  if (app.error()) {
    fail(app.error());
    return;
  }
  lightSet = new LightSet(app, () => lightsPanel && lightsPanel.refresh());
  lightDrag = new LightDrag(canvas, app, lightSet, () => 4 * sceneRadius);
  document.getElementById('help-button').addEventListener('click', () => toggleHelp());
  document.getElementById('help-close').addEventListener('click', () => toggleHelp(false));
  noticeBox.addEventListener('click', () => { noticeBox.hidden = true; });
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
    try {
      environments = (await fetchJson(`/api/lights?order=${client.maxOrder}`, 'environment list')).lights || [];
    } catch (e) {
      console.warn(`prt: ${e.message}; using the white furnace`);
      environments = [];
    }
    const link = readLinkView();
    if (!state.scene || !scenes.some((s) => s.name === state.scene)) state.scene = usable[0].name;
    await loadScene(state.scene);
    selectEnvironment(state.environment || (environments.find((l) => l.usable) || { name: 'white furnace' }).name);
    applyState();
    applyLightSettings();
    applyLinkView(link);
    buildGui();
  } catch (e) {
    fail(e.message);
  }
}

main();
