// The page's list of dynamic lights and the meshes mesh lights use, kept in step with the
// wasm client (ClientApp.setLights / addLightMesh). The panel, the pointer drag and
// prtApp.set({lights}) all change lights through here, so the client always sees one
// consistent, checked list.
import { normaliseLight, normaliseLights, packLights, boundingRadius, copyLight } from './lights.js';
import { meshRadius } from './obj_loader.js';
import { torusMesh } from './torus_mesh.js';

export class LightSet {
  // `app` is the ClientApp; `onChange()` runs after every successful change (panel refresh).
  constructor(app, onChange = () => {}) {
    this.app = app;
    this.onChange = onChange;
    this.lights = [];
    // Mesh key ('torus' or the id addMesh returned) -> {id: client mesh id, radius: bound at scale 1, name}.
    this.meshes = new Map();
  }

  // Registers a triangle mesh (xyz positions in the light's local units, triangle indices)
  // with the client and returns its id for {shape: 'mesh', mesh: id}. Throws with the
  // client's reason when it refuses the mesh.
  addMesh(positions, indices, name = 'mesh') {
    const p = Array.from(positions, Number), ix = Array.from(indices, Number);
    if (!p.length || p.length % 3) throw new Error(`addMesh: positions must be a non-empty list of x, y, z triples (got ${p.length} numbers)`);
    if (!ix.length || ix.length % 3) throw new Error(`addMesh: indices must be a non-empty list of triangles (got ${ix.length} indices)`);
    if (!ix.every((i) => Number.isInteger(i) && i >= 0 && i < p.length / 3)) throw new Error(`addMesh: every index must be an integer in 0..${p.length / 3 - 1}`);
    if (!p.every(Number.isFinite)) throw new Error('addMesh: positions must be finite numbers');
    const id = this.app.addLightMesh(p, ix);
    if (id < 0) throw new Error('addMesh: the client refused the mesh (empty, index out of range, non-finite or over 1M triangles)');
    this.meshes.set(id, { id, radius: meshRadius(p, ix), name });
    return id;
  }

  // The built-in torus mesh, registered on first use.
  ensureTorus() {
    if (!this.meshes.has('torus')) {
      const { positions, indices } = torusMesh();
      const id = this.addMesh(positions, indices, 'torus');
      this.meshes.set('torus', this.meshes.get(id));
      this.meshes.delete(id);
    }
  }

  // Replaces every light (descriptions as in docs/web-client.md). Throws, changing
  // nothing, when any light is invalid.
  set(list) {
    if (Array.isArray(list) && list.some((l) => l && l.shape === 'mesh' && l.mesh === 'torus')) this.ensureTorus();
    const checked = normaliseLights(list, this.meshes);
    this.push(checked);
  }

  add(spec) {
    if (spec.shape === 'mesh' && spec.mesh === 'torus') this.ensureTorus();
    const light = normaliseLight(spec, this.lights.length, this.meshes);
    this.push([...this.lights, light]);
    return this.lights.length - 1;
  }

  remove(index) {
    this.push(this.lights.filter((_, i) => i !== index));
  }

  // Changes some fields of light `index` (e.g. {position}); throws on invalid values.
  update(index, fields) {
    const merged = { ...this.lights[index], ...fields };
    const light = normaliseLight(merged, index, this.meshes);
    const next = this.lights.slice();
    next[index] = light;
    this.push(next);
  }

  push(list) {
    const error = this.app.setLights(packLights(list, this.meshes));
    if (error) throw new Error(`the client refused the lights: ${error}`);
    this.lights = list;
    this.onChange();
  }

  boundingRadius(index) {
    return boundingRadius(this.lights[index], this.meshes);
  }

  snapshot() {
    return this.lights.map(copyLight);
  }
}
