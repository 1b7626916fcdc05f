#version 300 es
// Draw pass after the transform-feedback PRT pass: exit radiance per vertex comes from the
// buffer prt.vert filled this frame, once per vertex (see docs/web-client.md), plus the
// glossy term glossy.vert captured (each a constant zero when its part is switched off).
precision highp float;

layout(location = 0) in vec3 aPosition;
layout(location = 3) in vec3 aRadiance;
layout(location = 5) in vec3 aGlossy;

uniform mat4 uViewProjection;
out vec3 vRadiance;

void main() {
  vRadiance = aRadiance + aGlossy;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
