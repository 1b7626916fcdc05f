// The page's test and benchmark hook, window.prtApp (docs/web-client.md, "Test hook"): the
// state tests wait on (ready, frames, error, notice), read-outs of the client (lighting,
// camera, passes, per-vertex radiance), set() to change settings with every value checked
// first, and the benchmarks' timing loops. app.js owns the page and hands installTestHook
// what the hook reads and calls; app.js and stream_loader.js write the state fields.
import { normaliseLights } from './lights.js';
import { randomLights } from './random_lights.js';
import { PASS_NAMES } from './stream_loader.js';

export const SET_OPTIONS = ['mode', 'order', 'exposure', 'envRotation', 'intensity', 'color', 'background', 'backgroundColor', 'environment', 'lights', 'projection', 'cubeSize', 'glossy', 'source', 'biScale', 'viewDependence'];
const SOURCES = ['vertex', 'texel'];
const BACKGROUNDS = ['image', 'blurred', 'colour', 'none'];
const GLOSSY_MIXES = ['diffuse', 'glossy', 'both'];
// GlRenderer's GlossyWork (web/src/gl_renderer.h) by name, for timeGlossy.
const GLOSSY_WORK = { table: 1, relight: 2, view: 3, transfer: 4 };

const rows = (flat) => {
  const out = [];
  for (let i = 0; i < flat.length; i += 3) out.push([flat[i], flat[i + 1], flat[i + 2]]);
  return out;
};

// Builds the hook, sets window.prtApp to it and returns it. `page` gives:
//   app, lightSet           getters: the ClientApp and the LightSet (null until made)
//   client                  the module's limits and enums (maxOrder, ShadingMode, PassForm,
//                           modeNames, formName(form)): app.js's `client`
//   canvas, state, lightSettings, stats, lightingModels, projections
//   loadScene(name), environmentNames(), selectEnvironment(name), applyState(),
//   applyLightSettings() (returns "" or why the GPU projection is unavailable), refreshGui()
export function installTestHook(page) {
  const { canvas, state, lightSettings, client } = page;
  const ready = () => page.app && hook.ready;
  const hook = {
    ready: false,
    frames: 0,
    error: null,
    notice: null,  // the last non-fatal message shown (bad OBJ file, refused value)
    link: null,  // the last link "copy link" made
    // The image background: {environment, width, height} of the map image the client draws
    // (null: none, e.g. still loading, or a map without one), and whether a fetch is under way.
    backgroundImage: null,
    backgroundLoading: false,
    linkProblems: [],  // why values of the opening link were not used (permalink.js)
    paused: false,  // true stops the page's own frame loop (benchmarks with several pages open)
    stats: page.stats,
    // Radiance SH the last frame used: the light cube's projection plus the environment when on.
    lightSH() {
      return page.app ? rows(page.app.lightSH()) : [];
    },
    // The light cube's projection alone (no environment), at the baked order.
    cubeSH() {
      return page.app ? rows(page.app.cubeSH()) : [];
    },
    get scene() { return ready() ? state.scene : null; },  // the scene shown (its catalogue name)
    get lightCenter() { return ready() ? Array.from(page.app.lightCenter()) : null; },
    get lightingModel() { return ready() ? page.lightingModels[page.app.lightingModel()] ?? 'unknown' : null; },
    get lightingRadius() { return ready() ? page.app.lightingRadius() : null; },
    get lights() { return page.lightSet ? page.lightSet.snapshot() : []; },
    get projection() { return lightSettings.projection; },
    get cubeSize() { return lightSettings.cubeSize; },
    get environment() { return lightSettings.environmentOn ? state.environment : null; },
    // How each pass is drawn: 'cpca' (straight from the clusters, Sloan 2003), 'expanded' or
    // null (absent); and for CPCA passes [clusters, weights per vertex].
    get passForms() {
      return ready() ? Object.fromEntries(PASS_NAMES.map((n) => [n, client.formName(page.app.passForm(client.ShadingMode[n]))])) : null;
    },
    get cpcaShapes() {
      return ready() ? Object.fromEntries(PASS_NAMES.map((n) => [n, Array.from(page.app.cpcaShape(client.ShadingMode[n]))])) : null;
    },
    // Transfer textures (docs/web-client.md, "Transfer textures"): the domain drawn now
    // ('vertex' or 'texel'), the texel passes' bands on the GPU [unshadowed, shadowed,
    // interreflected] (0: absent or not arrived yet; like loadedBands), the atlases.
    get source() {
      return ready() ? (page.app.source() === client.TransferDomain.texel ? 'texel' : 'vertex') : null;
    },
    get texelBands() {
      return page.app ? PASS_NAMES.map((n) => page.app.texelBands(client.ShadingMode[n])) : null;
    },
    // Bands of the TPFL visibility pass on the GPU (0: none), and the last failure to remake
    // its product matrix ('' when none).
    get texelGlossyBands() { return page.app ? page.app.texelGlossyBands() : 0; },
    get texelGlossyError() { return page.app ? page.app.texelGlossyError() : ''; },
    get atlases() {
      if (!ready()) return null;
      const sizes = Array.from(page.app.atlasSizes());
      return sizes.filter((_, i) => i % 2 === 0).map((width, i) => ({ width, height: sizes[2 * i + 1] }));
    },
    // Atlas `atlas` of texel pass `pass` rendered in UV space by the shading fragment shader with
    // the current lighting and order, read back: {width, height, data: Float32Array of linear
    // RGBA, row y = texel row y, alpha 1 where a triangle covers the texel centre}. Throws on error.
    // With positions = true the fragments' world positions (xyz) instead of the radiance.
    texelAtlasRadiance(pass, atlas = 0, positions = false) {
      if (!ready()) throw new Error('texelAtlasRadiance: no scene is loaded yet');
      if (!PASS_NAMES.includes(pass)) throw new Error(`texelAtlasRadiance: pass must be one of ${PASS_NAMES.join(', ')}`);
      const data = page.app.texelAtlasRadiance(client.ShadingMode[pass], atlas, positions);
      if (typeof data === 'string') throw new Error(`texelAtlasRadiance: ${data}`);
      const sizes = Array.from(page.app.atlasSizes());
      return { width: sizes[2 * atlas], height: sizes[2 * atlas + 1], data };
    },
    // Exit radiance of every vertex in the last frame (flat RGB, before exposure): a GPU read-back.
    vertexRadiance() {
      return ready() ? Float32Array.from(page.app.vertexRadiance()) : null;
    },
    // Glossy rendering (docs/web-client.md, "Glossy rendering"): per pass the glossy pass's
    // bands on the GPU (0: none) and [clusters, basis matrices, channels].
    get glossyBands() {
      return ready() ? Object.fromEntries(PASS_NAMES.map((n) => [n, page.app.glossyBands(client.ShadingMode[n])])) : null;
    },
    get glossyShapes() {
      return ready() ? Object.fromEntries(PASS_NAMES.map((n) => [n, Array.from(page.app.glossyShape(client.ShadingMode[n]))])) : null;
    },
    // The glossy radiance of every vertex in the last frame (flat RGB, GPU read-back), and the
    // CPU reference of it (prt::glossyExitRadiance on the expanded matrices, the same lighting
    // and eye) for the displayed pass.
    vertexGlossy() {
      return ready() ? Float32Array.from(page.app.vertexGlossy()) : null;
    },
    // Which glossy step wrote vertexGlossy: 'fused' (the frame's lighting changed), 'view' (only
    // the camera moved: the cached transferred radiance) or '' (none yet).
    get glossyStep() { return ready() ? page.app.lastGlossyStep() : null; },
    // Bi-scale (docs/bi-scale.md, "The client"): the RTT's bands on the GPU (0: the scene has
    // none), whether the last frame was drawn bi-scale, and its rotated transferred radiance read
    // back from the GPU with the CPU reference of it (Float32Array, [channel][vertex][row texels x 4]).
    get biScaleOrder() { return ready() ? page.app.biScaleOrder() : 0; },
    get drewBiScale() { return ready() ? page.app.drewBiScale() : false; },
    biScaleRotated() { return ready() ? page.app.biScaleRotated() : null; },
    biScaleRotatedReference() { return ready() ? page.app.biScaleRotatedReference() : null; },
    glossyReference() {
      if (!ready() || !PASS_NAMES.includes(state.mode)) return null;
      return Float32Array.from(page.app.glossyReference(client.ShadingMode[state.mode]));
    },
    // Tests: a synthetic glossy pass (web/src/glossy_synthetic.h) on pass `mode` of the loaded
    // scene, material {f0, exponent} on the vertices whose albedo green >= minGreen (f0 = 0
    // elsewhere). Throws on error.
    useSyntheticGlossy({ mode, bands = 4, channels = 1, clusters = 8, vectors = 3, seed = 1, f0 = 1, exponent = 30, minGreen = 0 }) {
      if (!ready()) throw new Error('useSyntheticGlossy: no scene is loaded yet');
      if (!PASS_NAMES.includes(mode)) throw new Error(`useSyntheticGlossy: mode must be one of ${PASS_NAMES.join(', ')}`);
      const error = page.app.useSyntheticGlossy(client.ShadingMode[mode], bands, channels, clusters, vectors, seed, f0, exponent, minGreen);
      if (error) throw new Error(`useSyntheticGlossy: ${error}`);
      page.applyState();
      page.refreshGui();
    },
    // Benchmark: the glossy work of the displayed pass alone, n times back to back, ended by a
    // read-back: 'table' the per-cluster table alone; 'relight' the table and the fused step
    // (a frame whose lighting changed); 'transfer' the table, the transferred radiance and the
    // view step (the first camera move after the lighting stopped changing, plus the table);
    // 'view' the view step alone on the cached transferred radiance (a frame where only the
    // camera moved).
    timeGlossy(n, work = 'relight') {
      if (!ready()) return NaN;
      const code = GLOSSY_WORK[work];
      if (code === undefined) throw new Error(`timeGlossy: work must be one of ${Object.keys(GLOSSY_WORK).join(', ')}`);
      if (code === GLOSSY_WORK.view && !page.app.shadeGlossyVertices(GLOSSY_WORK.transfer)) return NaN;
      const t0 = performance.now();
      for (let i = 0; i < n; i++) if (!page.app.shadeGlossyVertices(code)) return NaN;
      page.app.finishGlossy(code);  // a read-back of what the last pass wrote
      return (performance.now() - t0) / n;
    },
    // Registers a mesh for mesh lights (xyz positions in the light's units, triangle
    // indices); returns the id to use as {shape: 'mesh', mesh: id}. Throws on bad input.
    addMesh(positions, indices) {
      if (!page.lightSet) throw new Error('addMesh: no scene is loaded yet');
      return page.lightSet.addMesh(positions, indices);
    },
    // The view a permalink holds now (app.js currentView: permalink.js's fields), and the link.
    get view() { return ready() ? page.currentView() : null; },
    permalink() { return ready() ? page.permalink().href : null; },
    // The last frame's eye position, world units ([x, y, z]; null before a scene is ready).
    get eye() { return ready() ? Array.from(page.app.rayFromScreen(0, 0)).slice(0, 3) : null; },
    // Orbits the camera about its target by (dx, dy) radians, as a drag does.
    orbit(dx, dy) {
      if (ready()) page.app.orbit(dx, dy);
    },
    // The last frame's view-projection matrix: 16 numbers, column-major, OpenGL clip space.
    viewProjection() {
      return ready() ? Array.from(page.app.viewProjection()) : null;
    },
    // The scene's bounding sphere the camera frames (world units).
    get sceneSphere() { return ready() ? { center: Array.from(page.app.sceneCenter()), radius: page.app.sceneRadius() } : null; },
    // Canvas pixel (CSS pixels, origin top-left) where world point p appeared in the last frame.
    project(p) {
      if (!page.app) return null;
      const [x, y] = page.app.project(p[0], p[1], p[2]);
      return [(x * 0.5 + 0.5) * canvas.clientWidth, (0.5 - y * 0.5) * canvas.clientHeight];
    },
    // Benchmark: draws n frames back to back, each finished with a 1-pixel readPixels (so the
    // GPU work is inside the measurement), and returns the mean milliseconds per frame. With
    // `relight` each frame treats the lighting as changed (as while a light moves), so the
    // glossy term redoes its view-independent work; otherwise only the camera could have moved.
    timeFrames(n, relight = false) {
      if (!ready()) return NaN;
      const gl = canvas.getContext('webgl2');
      const pixel = new Uint8Array(4);
      const t0 = performance.now();
      for (let i = 0; i < n; i++) {
        if (relight) page.app.touchLighting();
        page.app.render(canvas.width, canvas.height);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      }
      return (performance.now() - t0) / n;
    },
    // Benchmark: the per-vertex PRT pass alone (no drawing), n times back to back, ended by a
    // 1-vertex read-back of its output; mean milliseconds per pass. NaN in Lambert mode.
    timeShading(n) {
      if (!ready()) return NaN;
      const t0 = performance.now();
      for (let i = 0; i < n; i++) if (!page.app.shadeVertices()) return NaN;
      page.app.finishShading();
      return (performance.now() - t0) / n;
    },
    // Benchmark: n samples, each the mean milliseconds of `batch` light updates back to back
    // (light cube render + SH projection). Each update ends by reading its result back
    // (cubeSH: 48 floats from the GPU on the GPU path), so its GPU work is inside the sample:
    // finishGpu alone was seen not to block in headless Chromium, letting work pile up.
    // Batches > 1 measure updates shorter than the browser's timer resolution (100 us
    // without cross-origin isolation).
    // On the analytic path an update re-projects light `onlyLight` (every light when omitted
    // or < 0: a drag moves one) and rebuilds the lighting block; there is no cube render to
    // wait for, so each sample ends with one read-back of the block (lightSH) instead.
    timeLightUpdates(n, batch = 1, onlyLight = -1) {
      if (!ready()) return [];
      const analytic = lightSettings.projection === 'analytic';
      const samples = [];
      for (let i = 0; i < n; i++) {
        const t0 = performance.now();
        for (let k = 0; k < batch; k++) {
          page.app.projectLightsNow(onlyLight);
          if (!analytic) {
            page.app.finishGpu();
            page.app.cubeSH();
          }
        }
        if (analytic) page.app.lightSH();
        samples.push((performance.now() - t0) / batch);
      }
      return samples;
    },
    // `count` seeded random sphere/disc/rect lights around the light centre (random_lights.js),
    // as a list for set({lights}).
    randomLights(count, seed = 1) {
      if (!ready()) throw new Error('randomLights: no scene is loaded yet');
      return randomLights(count, Array.from(page.app.lightCenter()), page.scale(), seed);
    },
    // Reloads the current scene with CPCA passes drawn 'direct' (from their clusters) or
    // 'expanded' (to plain transfer on load), like the panel's "CPCA rendering"; resolves once
    // every pass has all its bands.
    async setCpca(form) {
      if (form !== 'direct' && form !== 'expanded') throw new Error(`setCpca: expected 'direct' or 'expanded', got ${JSON.stringify(form)}`);
      if (!ready()) throw new Error('setCpca: no scene is loaded yet');
      state.cpca = form;
      page.refreshGui();
      await page.loadScene(state.scene);
      while (!hook.error && page.app.streamBuffer() !== null) {  // freed once every part is applied
        await new Promise((r) => setTimeout(r, 50));
      }
      if (hook.error) throw new Error(hook.error);
    },
    // Changes settings (docs/web-client.md); returns the current frame count. Every value is
    // checked first: on a bad one it throws an Error naming it and changes nothing.
    set(options) {
      if (options === null || typeof options !== 'object') throw new Error('set: expected an object of settings');
      for (const key of Object.keys(options)) {
        if (!SET_OPTIONS.includes(key)) throw new Error(`set: unknown setting '${key}' (known: ${SET_OPTIONS.join(', ')})`);
      }
      const { modeNames, maxOrder } = client;
      if ('mode' in options && !modeNames.includes(options.mode)) throw new Error(`set: mode must be one of ${modeNames.join(', ')}; got ${JSON.stringify(options.mode)}`);
      if ('order' in options && !(Number.isInteger(options.order) && options.order >= 1 && options.order <= maxOrder)) {
        throw new Error(`set: order must be an integer 1..${maxOrder}, got ${JSON.stringify(options.order)}`);
      }
      if ('projection' in options && !Object.hasOwn(page.projections, options.projection)) {
        throw new Error(`set: projection must be 'analytic', 'gpu' or 'cpu', got ${JSON.stringify(options.projection)}`);
      }
      if ('cubeSize' in options && !(Number.isInteger(options.cubeSize) && options.cubeSize >= 8 && options.cubeSize <= 512)) {
        throw new Error(`set: cubeSize must be an integer 8..512 (texels per face side), got ${JSON.stringify(options.cubeSize)}`);
      }
      if ('glossy' in options) {
        const g = options.glossy;
        const bad = g === null || typeof g !== 'object' || Object.entries(g).some(([k, v]) => !PASS_NAMES.includes(k) || !GLOSSY_MIXES.includes(v));
        if (bad) throw new Error(`set: glossy must map pass names (${PASS_NAMES.join(', ')}) to one of ${GLOSSY_MIXES.join(', ')}; got ${JSON.stringify(g)}`);
      }
      if ('source' in options) {
        if (!SOURCES.includes(options.source)) throw new Error(`set: source must be one of ${SOURCES.join(', ')}; got ${JSON.stringify(options.source)}`);
        if (page.app && !page.app.hasSource(client.TransferDomain[options.source])) {
          throw new Error(`set: source '${options.source}': this scene has no ${options.source} passes`);
        }
      }
      for (const key of ['biScale', 'viewDependence']) {
        if (key in options && typeof options[key] !== 'boolean') throw new Error(`set: ${key} must be true or false, got ${JSON.stringify(options[key])}`);
      }
      if ('background' in options && !(typeof options.background === 'boolean' || BACKGROUNDS.includes(options.background))) {
        throw new Error(`set: background must be one of ${BACKGROUNDS.join(', ')} (or true: blurred, false: none), got ${JSON.stringify(options.background)}`);
      }
      if ('backgroundColor' in options && !(typeof options.backgroundColor === 'string' && /^#[0-9a-f]{6}$/i.test(options.backgroundColor))) {
        throw new Error(`set: backgroundColor must be '#rrggbb', got ${JSON.stringify(options.backgroundColor)}`);
      }
      if ('color' in options && !(typeof options.color === 'string' && /^#[0-9a-f]{6}$/i.test(options.color))) {
        throw new Error(`set: color must be '#rrggbb', got ${JSON.stringify(options.color)}`);
      }
      const environments = page.environmentNames();
      if ('environment' in options && options.environment !== null && !environments.includes(options.environment)) {
        throw new Error(`set: environment must be null (off) or one of ${environments.map((n) => `'${n}'`).join(', ')}; got ${JSON.stringify(options.environment)}`);
      }
      const { lightSet } = page;
      if ('lights' in options) {
        if (!lightSet) throw new Error('set: lights need a loaded scene');
        if (Array.isArray(options.lights) && options.lights.some((l) => l && l.mesh === 'torus')) lightSet.ensureTorus();
        normaliseLights(options.lights, lightSet.meshes);  // throws on the first bad light
      }
      for (const key of ['mode', 'order', 'exposure', 'intensity', 'color', 'backgroundColor', 'source', 'biScale', 'viewDependence']) if (key in options) state[key] = options[key];
      // true and false are what background took before it had four choices: the SH view, or nothing.
      if ('background' in options) state.background = options.background === true ? 'blurred' : options.background === false ? 'none' : options.background;
      if ('glossy' in options) Object.assign(state.glossyMix, options.glossy);
      if ('envRotation' in options) {
        const r = options.envRotation;
        [state.envYaw, state.envPitch] = Array.isArray(r) ? r : [r, 0];
      }
      if ('environment' in options) {
        lightSettings.environmentOn = options.environment !== null;
        if (options.environment !== null) page.selectEnvironment(options.environment);
      }
      if ('projection' in options) lightSettings.projection = options.projection;
      if ('cubeSize' in options) lightSettings.cubeSize = options.cubeSize;
      page.applyState();
      const projectionError = page.applyLightSettings();
      if ('lights' in options) lightSet.set(options.lights);
      page.refreshGui();
      if (projectionError && 'projection' in options) throw new Error(`set: ${projectionError}`);
      return hook.frames;
    },
  };
  window.prtApp = hook;
  return hook;
}
