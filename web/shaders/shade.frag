#version 300 es
// Exposure, tone mapping (ACES fit, Narkowicz 2015) and sRGB encoding of linear radiance.
precision highp float;

in vec3 vRadiance;
uniform float uExposure;  // linear scale, 2^EV
out vec4 fragColor;

vec3 acesFit(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  vec3 mapped = acesFit(max(vRadiance, vec3(0.0)) * uExposure);
  fragColor = vec4(linearToSrgb(mapped), 1.0);
}
