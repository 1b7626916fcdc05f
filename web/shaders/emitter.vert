#version 300 es
// Emitters (dynamic area lights) in the main view and in the light cube map: local geometry
// (impostor cube, unit square or light mesh) placed by uModel (web/src/emitters.h).
precision highp float;

layout(location = 0) in vec3 aPosition;

uniform mat4 uModel;
uniform mat4 uViewProjection;

out vec3 vWorld;
out vec2 vLocal;  // square coordinates in [-1, 1]^2 (disc mask)

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vLocal = aPosition.xy;
  gl_Position = uViewProjection * world;
}
