#version 300 es
// PRT shading straight from CPCA-compressed transfer (Sloan et al. 2003; docs/web-client.md,
// "CPCA rendering"): the per-cluster constants were computed this frame (prt.vert on the
// cluster entries, captured into uTable); each vertex sums its cluster's constant term and
// its integer weight levels times the cluster's per-weight constants. Run once per vertex
// in a transform-feedback pass, like prt.vert.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp isampler2D;

layout(location = 1) in vec3 aAlbedo;
layout(location = 4) in uint aCluster;

uniform sampler2D uTable;     // RGB32F: entry k * uEntries + e
uniform isampler2D uWeights;  // RGBA8I / RGBA16I levels: texel v * uWeightTexels + t
uniform int uTextureMask;     // the textures' width - 1 (a power of two) — both textures
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uEntries;         // 1 + 4 * uWeightTexels
uniform int uWeightTexels;
uniform int uActiveTexels;    // texels holding the displayed bands' weights
uniform int uChannels;        // 1: scalar transfer, multiplied by the albedo

out vec3 vRadiance;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec3 entry(int i) {
  return texelFetch(uTable, texelCoord(i), 0).rgb;
}

void main() {
  int first = int(aCluster) * uEntries;
  vec3 radiance = entry(first);
  int base = gl_VertexID * uWeightTexels;
  for (int t = 0; t < uActiveTexels; ++t) {
    int i = base + t;
    vec4 q = vec4(texelFetch(uWeights, texelCoord(i), 0));
    int e = first + 1 + 4 * t;
    radiance += q.x * entry(e) + q.y * entry(e + 1) + q.z * entry(e + 2) + q.w * entry(e + 3);
  }
  vRadiance = uChannels == 1 ? radiance * aAlbedo : radiance;
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
