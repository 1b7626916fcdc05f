// N random sphere, disc and rect lights around the light centre, from a seeded generator so
// a test or benchmark gets the same lights every run (panel button "add random lights",
// prtApp.randomLights; docs/web-client.md, "Analytic lights").

// Mulberry32: a small 32-bit generator; returns floats in [0, 1).
export function seededRandom(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// `count` light specs (lights.js form) at 0.6..1.2 x `radius` from `centre`, in the upper
// hemisphere, one-sided ones facing the centre. Beyond 16 lights sizes shrink as
// 1/sqrt(count) and intensities as 1/count, so the lights cover about the solid angle of 16
// and shine about as much as 4 whatever their number: hundreds of full-size lights would
// tile the sky and mostly hide one another.
export function randomLights(count, centre, radius, seed = 1) {
  if (!Number.isInteger(count) || count < 0 || count > 1024) throw new Error(`randomLights: count must be an integer 0..1024, got ${JSON.stringify(count)}`);
  if (!(radius > 0)) throw new Error(`randomLights: radius must be > 0, got ${radius}`);
  const rnd = seededRandom(seed);
  const shapes = ['sphere', 'disc', 'rect'];
  const intensity = 20 * Math.min(1, 4 / Math.max(1, count));
  const out = [];
  for (let i = 0; i < count; i++) {
    const z = 0.1 + 0.9 * rnd(), phi = 2 * Math.PI * rnd(), r = Math.sqrt(1 - z * z);
    const d = radius * (0.6 + 0.6 * rnd());
    const dir = [r * Math.cos(phi), z, r * Math.sin(phi)];  // +y is up
    const position = dir.map((v, k) => centre[k] + d * v);
    const color = [0.5 + 0.5 * rnd(), 0.5 + 0.5 * rnd(), 0.5 + 0.5 * rnd()];
    const shape = shapes[i % 3];
    const size = radius * (0.03 + 0.05 * rnd()) * Math.min(1, Math.sqrt(16 / count));
    const normal = dir.map((v) => -v);
    if (shape === 'sphere') out.push({ shape, position, radius: size, color, intensity });
    else if (shape === 'disc') out.push({ shape, position, radius: size, normal, color, intensity });
    else out.push({ shape, position, size: [2 * size, size * (1 + rnd())], normal, color, intensity });
  }
  return out;
}
