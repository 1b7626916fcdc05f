#version 300 es
// Emitted radiance of one emitter. Spheres are ray-cast inside their impostor cube (exact
// silhouette from any viewpoint, depth written from the hit point); discs are the unit
// square masked to the unit circle. Disc, rect and sphere emit from their front side only;
// their back (a sphere's inside) is opaque black. Meshes emit from both sides.
// uOutput: 0 linear radiance (float light cube), 1 RGBE8 (light cube without float render
// targets: value = rgb / 255 * 2^(255 a - 128)), 2 display (exposure, ACES fit, sRGB).
precision highp float;

in vec3 vWorld;
in vec2 vLocal;

uniform mat4 uViewProjection;
uniform int uShape;     // 0 sphere, 1 disc, 2 rect, 3 mesh
uniform vec4 uSphere;   // centre, radius
uniform vec3 uEye;      // viewpoint: the camera, or the light cube's centre
uniform vec3 uRadiance;
uniform int uOutput;
uniform float uExposure;

out vec4 fragColor;

vec3 acesFit(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 linearToSrgb(vec3 c) { return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c)); }

vec4 encodeRgbe(vec3 c) {
  float m = max(c.r, max(c.g, c.b));
  if (m < 1e-30) return vec4(0.0);
  float e = clamp(ceil(log2(m)), -127.0, 127.0);
  float scale = exp2(-e);
  if (m * scale > 1.0) {  // log2 rounding
    e += 1.0;
    scale *= 0.5;
  }
  return vec4(c * scale, (e + 128.0) / 255.0);
}

void main() {
  vec3 radiance = uRadiance;
  if (uShape == 0) {
    vec3 dir = normalize(vWorld - uEye);
    vec3 oc = uEye - uSphere.xyz;
    float b = dot(oc, dir);
    vec3 perp = oc - b * dir;  // closest approach, without the cancellation of b^2 - c
    float h = uSphere.w * uSphere.w - dot(perp, perp);
    if (h < 0.0) discard;
    bool inside = dot(oc, oc) <= uSphere.w * uSphere.w;
    float t = inside ? -b + sqrt(h) : -b - sqrt(h);
    if (t < 0.0) discard;
    if (inside) radiance = vec3(0.0);
    vec4 clip = uViewProjection * vec4(uEye + t * dir, 1.0);
    gl_FragDepth = clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
  } else {
    if (uShape == 1 && dot(vLocal, vLocal) > 1.0) discard;
    if (uShape != 3 && !gl_FrontFacing) radiance = vec3(0.0);
    gl_FragDepth = gl_FragCoord.z;
  }
  if (uOutput == 1) {
    fragColor = encodeRgbe(radiance);
  } else if (uOutput == 2) {
    fragColor = vec4(linearToSrgb(acesFit(radiance * uExposure)), 1.0);
  } else {
    fragColor = vec4(radiance, 1.0);
  }
}
