// The built-in mesh light: a torus generated here, so the page needs no mesh file.

// A torus about the y axis with major radius R and tube radius rt scaled so its outer
// radius R + rt is 1 (the built-in mesh light). `rings` around the axis, `sides` around the tube.
export function torusMesh(rings = 32, sides = 12, tubeFraction = 0.3) {
  const rt = tubeFraction, R = 1 - tubeFraction;
  const positions = new Float32Array(rings * sides * 3);
  const indices = new Uint32Array(rings * sides * 6);
  for (let i = 0; i < rings; i++) {
    const u = (2 * Math.PI * i) / rings;
    for (let j = 0; j < sides; j++) {
      const v = (2 * Math.PI * j) / sides;
      const k = 3 * (i * sides + j);
      positions[k] = (R + rt * Math.cos(v)) * Math.cos(u);
      positions[k + 1] = rt * Math.sin(v);
      positions[k + 2] = (R + rt * Math.cos(v)) * Math.sin(u);
    }
  }
  let t = 0;
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < sides; j++) {
      const a = i * sides + j, b = ((i + 1) % rings) * sides + j;
      const c = ((i + 1) % rings) * sides + ((j + 1) % sides), d = i * sides + ((j + 1) % sides);
      indices.set([a, b, c, a, c, d], t);
      t += 6;
    }
  }
  return { positions, indices };
}
