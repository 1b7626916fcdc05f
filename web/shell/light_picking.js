// Ray geometry for picking and dragging lights with the pointer. A ray is
// {origin: [x,y,z], dir: [x,y,z] unit}, world space (ClientApp.rayFromScreen). Pure:
// tests/web/shell_modules_test.mjs checks it under Node.

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const along = (ray, t) => [ray.origin[0] + t * ray.dir[0], ray.origin[1] + t * ray.dir[1], ray.origin[2] + t * ray.dir[2]];

// Distance along the ray to the first point in front of its origin on the sphere
// (centre, radius), or null when it misses. An origin inside the sphere hits at t = 0.
export function raySphere(ray, centre, radius) {
  const oc = sub(ray.origin, centre);
  const b = dot(oc, ray.dir);
  const c = dot(oc, oc) - radius * radius;
  if (c <= 0) return 0;
  const disc = b * b - c;
  if (disc < 0) return null;
  const t = -b - Math.sqrt(disc);
  return t > 0 ? t : null;
}

// Index of the light whose bounding sphere the ray hits first, or -1. Each sphere is
// grown to at least `minPixels` pixels on screen (`radiansPerPixel` = the angle between
// rays through neighbouring pixels) so small or distant lights stay easy to grab.
export function pickLight(ray, centres, radii, radiansPerPixel, minPixels = 8) {
  let best = -1, bestT = Infinity;
  centres.forEach((centre, i) => {
    const distance = Math.hypot(...sub(centre, ray.origin));
    const radius = Math.max(radii[i], distance * Math.tan(radiansPerPixel * minPixels));
    const t = raySphere(ray, centre, radius);
    if (t !== null && t < bestT) {
      best = i;
      bestT = t;
    }
  });
  return best;
}

// Where the ray meets the horizontal plane y = height, or null when it runs (nearly)
// parallel to it or meets it behind the origin: a drag there would fling the light away.
export function rayHorizontalPlane(ray, height) {
  if (Math.abs(ray.dir[1]) < 1e-4) return null;
  const t = (height - ray.origin[1]) / ray.dir[1];
  return t > 0 ? along(ray, t) : null;
}

// World distance per screen pixel at the depth of `point`, from the rays through two
// neighbouring pixels: how far a vertical drag of one pixel moves a light there.
export function worldPerPixel(ray, neighbourRay, point) {
  const t = Math.hypot(...sub(point, ray.origin));
  const angle = Math.acos(Math.max(-1, Math.min(1, dot(ray.dir, neighbourRay.dir))));
  return t * Math.tan(angle);
}
