#version 300 es
// Glossy PRT, after the fused step (glossy.vert with GROUP, web/src/glossy_fused.h): each
// vertex's exit radiance read back from its group slot into vertex order, where the shading
// pass takes it as an attribute. One point per vertex, rasteriser off, captured by transform
// feedback.
precision highp float;
precision highp int;
precision highp sampler2D;

layout(location = 9) in uint aSlot;  // the vertex's slot in the fused step's output

uniform sampler2D uFused;      // RGBA32F: slot i at texel i, rgb the exit radiance
uniform int uTextureMask;      // the textures' width - 1 (a power of two)
uniform int uTextureShift;     // log2 of their width: texel i is at (i & mask, i >> shift)

out vec3 vGlossy;

void main() {
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  int i = int(aSlot);
  vGlossy = texelFetch(uFused, ivec2(i & uTextureMask, i >> uTextureShift), 0).rgb;
}
