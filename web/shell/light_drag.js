// Dragging lights with mouse and touch. A press over a light (its bounding sphere, hit by
// the camera ray through the pointer) grabs it: dragging moves it on the horizontal plane
// through it; shift-drag, or a second finger on touch (both fingers moving up and down),
// moves it vertically. A press that hits no light is left to the camera controls.
import { pickLight, rayHorizontalPlane, worldPerPixel } from './light_picking.js';

export class LightDrag {
  // `lightSet` is the page's LightSet; `maxDistance()` bounds how far from the light
  // centre c a drag may carry a light (a grazing ray would otherwise fling it away).
  constructor(canvas, app, lightSet, maxDistance) {
    this.canvas = canvas;
    this.app = app;
    this.lightSet = lightSet;
    this.maxDistance = maxDistance;
    this.active = null;  // {index, mode: 'horizontal'|'vertical', offset | lastY, pointers: Map}
  }

  get dragging() { return this.active !== null; }

  ray(clientX, clientY) {
    const r = this.canvas.getBoundingClientRect();
    const ndcX = ((clientX - r.left) / r.width) * 2 - 1;
    const ndcY = 1 - ((clientY - r.top) / r.height) * 2;
    const v = this.app.rayFromScreen(ndcX, ndcY);
    if (!v || v.length !== 6 || !Array.from(v).every(Number.isFinite)) return null;
    return { origin: [v[0], v[1], v[2]], dir: [v[3], v[4], v[5]] };
  }

  // Called on every pointerdown; returns true when the pointer now drags a light (the
  // caller must then not orbit or pan with it).
  pointerDown(e) {
    if (this.active) {
      // A second finger on a dragged light switches to vertical moves.
      if (e.pointerType === 'touch' && this.active.pointers.size === 1) {
        this.active.pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
        this.startVertical();
        return true;
      }
      return false;
    }
    if (e.button !== 0 || e.ctrlKey || !this.lightSet.lights.length) return false;
    const ray = this.ray(e.clientX, e.clientY);
    const neighbour = this.ray(e.clientX + 1, e.clientY);
    if (!ray || !neighbour) return false;
    const centres = this.lightSet.lights.map((l) => l.position);
    const radii = centres.map((_, i) => this.lightSet.boundingRadius(i));
    const angle = Math.acos(Math.max(-1, Math.min(1, ray.dir[0] * neighbour.dir[0] + ray.dir[1] * neighbour.dir[1] + ray.dir[2] * neighbour.dir[2])));
    const index = pickLight(ray, centres, radii, angle);
    if (index < 0) return false;
    this.active = { index, pointers: new Map([[e.pointerId, { x: e.clientX, y: e.clientY }]]) };
    if (e.shiftKey) this.startVertical();
    else this.startHorizontal();
    return true;
  }

  // The pointer position the drag follows: the one pointer, or the two fingers' midpoint.
  point() {
    const ps = [...this.active.pointers.values()];
    return { x: ps.reduce((s, p) => s + p.x, 0) / ps.length, y: ps.reduce((s, p) => s + p.y, 0) / ps.length };
  }

  startHorizontal() {
    const a = this.active;
    a.mode = 'horizontal';
    const position = this.lightSet.lights[a.index].position;
    const { x, y } = this.point();
    const ray = this.ray(x, y);
    const hit = ray && rayHorizontalPlane(ray, position[1]);
    // Keep the grab offset so the light does not jump to put its centre under the pointer.
    a.offset = hit ? [hit[0] - position[0], hit[2] - position[2]] : [0, 0];
  }

  startVertical() {
    this.active.mode = 'vertical';
    this.active.lastY = this.point().y;
  }

  // Returns true when the event belonged to a light drag (handled here).
  pointerMove(e) {
    const a = this.active;
    if (!a || !a.pointers.has(e.pointerId)) return false;
    a.pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
    if (a.mode === 'horizontal' && e.shiftKey && e.pointerType !== 'touch') this.startVertical();
    else if (a.mode === 'vertical' && !e.shiftKey && e.pointerType !== 'touch') this.startHorizontal();
    const light = this.lightSet.lights[a.index];
    const position = light.position.slice();
    const { x, y } = this.point();
    const ray = this.ray(x, y);
    if (!ray) return true;
    if (a.mode === 'horizontal') {
      const hit = rayHorizontalPlane(ray, position[1]);
      if (!hit) return true;
      position[0] = hit[0] - a.offset[0];
      position[2] = hit[2] - a.offset[1];
    } else {
      const neighbour = this.ray(x + 1, y);
      if (!neighbour) return true;
      position[1] -= (y - a.lastY) * worldPerPixel(ray, neighbour, position);
      a.lastY = y;
    }
    const c = this.app.lightCenter();
    const limit = this.maxDistance();
    const d = [position[0] - c[0], position[1] - c[1], position[2] - c[2]];
    const length = Math.hypot(...d);
    if (length > limit) for (let k = 0; k < 3; k++) position[k] = c[k] + (d[k] * limit) / length;
    this.lightSet.update(a.index, { position });
    return true;
  }

  // Returns true when the event ended (part of) a light drag.
  pointerUp(e) {
    const a = this.active;
    if (!a || !a.pointers.has(e.pointerId)) return false;
    a.pointers.delete(e.pointerId);
    if (!a.pointers.size) this.active = null;
    else this.startHorizontal();  // one finger left: back to horizontal moves from here
    return true;
  }
}
