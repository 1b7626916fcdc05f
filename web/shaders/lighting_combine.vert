#version 300 es
// The frame's lighting block (docs/web-client.md): vec4 t of channel c is the light cube's
// SH (cut to the display order) plus the environment's (rotated, coloured and cut on the
// CPU; zero when it is off). One point per vec4, rasteriser off, captured by transform
// feedback straight into the uniform buffer the shading programs read: no CPU readback.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D uCubeSh;  // 16 x 3 RGBA32F, packLighting layout
uniform vec4 uEnvironment[48];
uniform int uCoeffCount;    // display order^2

out vec4 vLighting;

void main() {
  int c = gl_VertexID / 16;
  int t = gl_VertexID - 16 * c;
  vec4 index = vec4(float(4 * t)) + vec4(0.0, 1.0, 2.0, 3.0);
  vec4 keep = vec4(lessThan(index, vec4(float(uCoeffCount))));
  vLighting = texelFetch(uCubeSh, ivec2(t, c), 0) * keep + uEnvironment[gl_VertexID];
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
