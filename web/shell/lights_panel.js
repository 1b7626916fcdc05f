// The "Lights" folder of the lil-gui panel: projection path, cube size, environment on/off,
// buttons that add a sphere, disc, rect, torus or OBJ-file light, and one sub-folder per
// light (colour, intensity, size, position, facing for one-sided lights, remove).
import { parseObj, normaliseToUnitRadius } from './obj_loader.js';
import { randomLights } from './random_lights.js';

// Per-light sub-folders are built for the first this-many lights: hundreds of folders would
// make the panel, not the lighting, the slow part.
const MAX_LIGHT_FOLDERS = 16;

const FACINGS = { down: [0, -1, 0], up: [0, 1, 0], '+x': [1, 0, 0], '-x': [-1, 0, 0], '+z': [0, 0, 1], '-z': [0, 0, -1] };

function facingName(normal) {
  let best = 'down', bestDot = -Infinity;
  for (const [name, n] of Object.entries(FACINGS)) {
    const d = n[0] * normal[0] + n[1] * normal[1] + n[2] * normal[2];
    if (d > bestDot) [best, bestDot] = [name, d];
  }
  return best;
}

export class LightsPanel {
  // `page` supplies: lightSet, settings ({projection, cubeSize, environmentOn}),
  // applySettings(), scale() (scene radius for slider ranges), centre() (light centre c),
  // notify(message) (a non-fatal message), showHelp().
  constructor(gui, page) {
    this.page = page;
    this.folder = gui.addFolder('Lights');
    const s = page.settings;
    this.folder.add(s, 'projection', ['analytic', 'gpu', 'cpu']).name('projection').onChange(() => page.applySettings());
    this.folder.add(s, 'cubeSize', [32, 64, 128]).name('cube size (per face)').onChange(() => page.applySettings());
    this.folder.add(s, 'environmentOn').name('environment on').onChange(() => page.applySettings());
    const actions = {
      sphere: () => this.addLight('sphere'),
      disc: () => this.addLight('disc'),
      rect: () => this.addLight('rect'),
      torus: () => this.addLight('torus'),
      obj: () => this.pickObj(),
      random: () => this.addRandom(),
      randomCount: 64,
      help: () => page.showHelp(),
    };
    this.folder.add(actions, 'sphere').name('add sphere light');
    this.folder.add(actions, 'disc').name('add disc light');
    this.folder.add(actions, 'rect').name('add rect light');
    this.folder.add(actions, 'torus').name('add torus light');
    this.folder.add(actions, 'obj').name('add OBJ mesh light…');
    this.folder.add(actions, 'randomCount', 1, 256, 1).name('random lights: count');
    this.folder.add(actions, 'random').name('add random lights');
    this.actions = actions;
    this.folder.add(actions, 'help').name('? how lights work');
    this.fileInput = document.createElement('input');
    this.fileInput.type = 'file';
    this.fileInput.accept = '.obj,text/plain';
    this.fileInput.hidden = true;
    this.fileInput.id = 'obj-file';
    document.body.appendChild(this.fileInput);
    this.fileInput.addEventListener('change', () => this.loadObjFile());
    this.lightFolders = [];
    this.views = [];
    this.rebuild();
  }

  // A new light of `kind` in front of the light centre, sized to the scene.
  addLight(kind) {
    const R = this.page.scale(), c = this.page.centre();
    const position = [c[0] + 0.2 * R * (this.page.lightSet.lights.length % 3 - 1), c[1] + 0.3 * R, c[2] + 0.2 * R];
    const base = { position, color: [1, 1, 1], intensity: 20 };
    const spec = kind === 'sphere' ? { ...base, shape: 'sphere', radius: 0.06 * R }
      : kind === 'disc' ? { ...base, shape: 'disc', radius: 0.1 * R, normal: [0, -1, 0] }
      : kind === 'rect' ? { ...base, shape: 'rect', size: [0.25 * R, 0.12 * R], normal: [0, -1, 0] }
      : kind === 'torus' ? { ...base, shape: 'mesh', mesh: 'torus', scale: 0.1 * R }
      : { ...base, shape: 'mesh', mesh: kind, scale: 0.1 * R };
    try {
      this.page.lightSet.add(spec);
    } catch (e) {
      this.page.notify(e.message);
    }
  }

  // Adds `randomCount` seeded random sphere/disc/rect lights (random_lights.js).
  addRandom() {
    const set = this.page.lightSet;
    this.randomSeed = (this.randomSeed ?? 0) + 1;
    try {
      set.set(set.snapshot().concat(randomLights(Math.round(this.actions.randomCount), this.page.centre(), this.page.scale(), this.randomSeed)));
    } catch (e) {
      this.page.notify(e.message);
    }
  }

  pickObj() {
    this.fileInput.value = '';
    this.fileInput.click();
  }

  async loadObjFile() {
    const file = this.fileInput.files && this.fileInput.files[0];
    if (!file) return;
    try {
      if (file.size > 256 * 1024 * 1024) throw new Error(`OBJ: ${file.name} is ${(file.size / 1e6).toFixed(0)} MB; the limit is 256 MB`);
      const { positions, indices } = parseObj(await file.text());
      const id = this.page.lightSet.addMesh(normaliseToUnitRadius(positions, indices), indices, file.name);
      this.addLight(id);
      this.page.notify(`Added ${file.name}: ${positions.length / 3} vertices, ${indices.length / 3} triangles`);
    } catch (e) {
      this.page.notify(`${file.name}: ${e.message}`);
    }
  }

  // Recreates the per-light sub-folders (after lights were added or removed).
  rebuild() {
    for (const f of this.lightFolders) f.destroy();
    this.lightFolders = [];
    this.views = [];
    this.signature = this.page.lightSet.lights.map((l) => `${l.shape}:${l.mesh ?? ''}`).join();
    const R = this.page.scale(), c = this.page.centre();
    const set = this.page.lightSet;
    set.lights.slice(0, MAX_LIGHT_FOLDERS).forEach((light, i) => {
      const meshName = light.shape === 'mesh' ? set.meshes.get(light.mesh).name : '';
      const folder = this.folder.addFolder(`light ${i + 1}: ${light.shape === 'mesh' ? meshName : light.shape}`);
      const view = { color: light.color.slice(), intensity: light.intensity, x: 0, y: 0, z: 0, size: 0, width: 0, height: 0, facing: 'down',
        remove: () => set.remove(i) };
      this.views.push(view);
      const change = (fields) => {
        try {
          set.update(i, fields());
        } catch (e) {
          this.page.notify(e.message);
        }
      };
      folder.addColor(view, 'color').name('colour').onChange(() => change(() => ({ color: view.color.slice() })));
      folder.add(view, 'intensity', 0, 200, 0.1).name('intensity').onChange(() => change(() => ({ intensity: view.intensity })));
      if (light.shape === 'rect') {
        folder.add(view, 'width', 0.01 * R, R, 0.001 * R).name('width').onChange(() => change(() => ({ size: [view.width, view.height] })));
        folder.add(view, 'height', 0.01 * R, R, 0.001 * R).name('height').onChange(() => change(() => ({ size: [view.width, view.height] })));
      } else {
        const field = light.shape === 'mesh' ? 'scale' : 'radius';
        folder.add(view, 'size', 0.005 * R, 0.5 * R, 0.001 * R).name(field).onChange(() => change(() => ({ [field]: view.size })));
      }
      for (const [axis, k] of [['x', 0], ['y', 1], ['z', 2]]) {
        folder.add(view, axis, c[k] - 1.5 * R, c[k] + 1.5 * R, 0.001 * R).name(axis)
          .onChange(() => change(() => ({ position: [view.x, view.y, view.z] })));
      }
      if (light.shape === 'disc' || light.shape === 'rect') {
        folder.add(view, 'facing', Object.keys(FACINGS)).name('faces').onChange(() => change(() => ({ normal: FACINGS[view.facing] })));
      }
      folder.add(view, 'remove').name('remove this light');
      this.lightFolders.push(folder);
    });
    this.refresh();
  }

  // Shows the current values (after a drag or prtApp.set) without rebuilding.
  refresh() {
    const lights = this.page.lightSet.lights;
    if (lights.map((l) => `${l.shape}:${l.mesh ?? ''}`).join() !== this.signature) {
      this.rebuild();
      return;
    }
    lights.slice(0, MAX_LIGHT_FOLDERS).forEach((light, i) => {
      const v = this.views[i];
      v.color = light.color.slice();
      v.intensity = light.intensity;
      [v.x, v.y, v.z] = light.position;
      if (light.shape === 'rect') [v.width, v.height] = light.size;
      else v.size = light.shape === 'mesh' ? light.scale : light.radius;
      if (light.normal) v.facing = facingName(light.normal);
      this.lightFolders[i].controllersRecursive().forEach((ctl) => ctl.updateDisplay());
    });
  }
}
