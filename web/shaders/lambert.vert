#version 300 es
// Plain Lambert reference for benchmarks: irradiance from the first 9 lighting coefficients
// (Ramamoorthi & Hanrahan) at the vertex normal, no transfer, no shadows.
precision highp float;

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;
layout(location = 2) in vec3 aNormal;

uniform mat4 uViewProjection;
layout(std140) uniform Lighting {  // built on the GPU by lighting_combine.vert
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec3 vRadiance;

void main() {
  vec3 n = normalize(aNormal);
  // (1/pi) * pi H_l y_lm(n): H_0 = 1, H_1 = 2/3, H_2 = 1/4, times the basis.
  vec4 b0 = vec4(0.282095, 0.488603 * 2.0 / 3.0 * n.y, 0.488603 * 2.0 / 3.0 * n.z, 0.488603 * 2.0 / 3.0 * n.x);
  vec4 b1 = 0.25 * vec4(1.092548 * n.x * n.y, 1.092548 * n.y * n.z, 0.315392 * (3.0 * n.z * n.z - 1.0),
                        1.092548 * n.x * n.z);
  float b2 = 0.25 * 0.546274 * (n.x * n.x - n.y * n.y);
  vec3 e = vec3(dot(b0, uLightR[0]) + dot(b1, uLightR[1]) + b2 * uLightR[2].x,
                dot(b0, uLightG[0]) + dot(b1, uLightG[1]) + b2 * uLightG[2].x,
                dot(b0, uLightB[0]) + dot(b1, uLightB[1]) + b2 * uLightB[2].x);
  vRadiance = aAlbedo * max(e, vec3(0.0));
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
