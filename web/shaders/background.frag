#version 300 es
// The environment as the background: the map itself (uImage, an RGB9E5 equirect texture,
// rotated and tinted as the lighting is), or the current (rotated) SH lighting evaluated per
// pixel up to order 4, i.e. the same low-frequency light the scene is lit with. Either way
// tone-mapped like the scene: exposure, ACES fit, sRGB.
precision highp float;

in vec2 vNdc;
uniform mat4 uInverseViewProjection;
uniform vec4 uLightR[16];
uniform vec4 uLightG[16];
uniform vec4 uLightB[16];
uniform float uExposure;
uniform bool uImage;
uniform sampler2D uEnvironmentImage;
// R^T: the lighting is the map rotated by R (f'(u) = f(R^T u), sh_rotation.h), so the pixel
// looking along d shows the map at R^T d.
uniform mat3 uEnvironmentRotation;
uniform vec3 uEnvironmentTint;
out vec4 fragColor;

const float kPi = 3.14159265358979;

// three.js / glTF-viewer equirect mapping (sh_project.h projectEquirect): longitude from +x
// toward +z at u = 1/2, latitude +pi/2 at the top row (v = 0; GL's t = 0 is the first row).
vec3 mapRadiance(vec3 d) {
  vec3 m = uEnvironmentRotation * d;
  float u = atan(m.z, m.x) / (2.0 * kPi) + 0.5;
  float v = acos(clamp(m.y, -1.0, 1.0)) / kPi;
  // No mipmaps, so the derivative jump where u wraps selects nothing: the seam is clean.
  return texture(uEnvironmentImage, vec2(u, v)).rgb * uEnvironmentTint;
}

vec3 acesFit(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 linearToSrgb(vec3 c) { return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c)); }

void main() {
  vec4 far = uInverseViewProjection * vec4(vNdc, 1.0, 1.0);
  vec4 near = uInverseViewProjection * vec4(vNdc, -1.0, 1.0);
  vec3 d = normalize(far.xyz / far.w - near.xyz / near.w);
  if (uImage) {
    fragColor = vec4(linearToSrgb(acesFit(mapRadiance(d) * uExposure)), 1.0);
    return;
  }
  float x = d.x, y = d.y, z = d.z;
  vec4 y0 = vec4(0.282095, 0.488603 * y, 0.488603 * z, 0.488603 * x);
  vec4 y1 = vec4(1.092548 * x * y, 1.092548 * y * z, 0.315392 * (3.0 * z * z - 1.0), 1.092548 * x * z);
  vec4 y2 = vec4(0.546274 * (x * x - y * y), 0.590044 * y * (3.0 * x * x - y * y), 2.890611 * x * y * z,
                 0.457046 * y * (5.0 * z * z - 1.0));
  vec4 y3 = vec4(0.373176 * z * (5.0 * z * z - 3.0), 0.457046 * x * (5.0 * z * z - 1.0),
                 1.445306 * z * (x * x - y * y), 0.590044 * x * (x * x - 3.0 * y * y));
  vec3 radiance = vec3(dot(y0, uLightR[0]) + dot(y1, uLightR[1]) + dot(y2, uLightR[2]) + dot(y3, uLightR[3]),
                       dot(y0, uLightG[0]) + dot(y1, uLightG[1]) + dot(y2, uLightG[2]) + dot(y3, uLightG[3]),
                       dot(y0, uLightB[0]) + dot(y1, uLightB[1]) + dot(y2, uLightB[2]) + dot(y3, uLightB[3]));
  fragColor = vec4(linearToSrgb(acesFit(max(radiance, vec3(0.0)) * uExposure)), 1.0);
}
