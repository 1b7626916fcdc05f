#version 300 es
// Glossy PRT, when the lighting changes (docs/web-client.md, "Glossy rendering"): every
// cluster's mean and basis matrices times the lighting, A_km,c L_c, from the CPCA matrix pass
// without expanding it per vertex (Sloan et al. 2003 §4.1). One point per table texel,
// rasteriser off, captured by transform feedback: point ((k * (1 + N') + m) * 3 + c) *
// uRowTexels + t writes rows 4t .. 4t+3 of the product for cluster k, matrix m (0 the mean,
// else a basis matrix with its weight step folded in) and lighting channel c. The matrices are
// stored as full rows of uRowTexels texels, so a row times the lighting is uRowTexels vec4
// dot products. web/src/glossy_texture.cpp (glossyTableCpu) emulates it.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D uMatrices;  // RGBA32F: matrix ((k * (1 + N') + m) * uChannels + c), uMatrixTexels texels each
uniform int uTextureMask;     // the textures' width - 1 (a power of two)
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uRowTexels;       // ceil(packed bands^2 / 4): texels of one row and of one table vector
uniform int uMatrixTexels;    // packed bands^2 * uRowTexels
uniform int uChannels;        // 1: one matrix for r, g, b; 3: one per channel
uniform int uRows;            // displayed bands^2 (<= packed bands^2)
layout(std140) uniform Lighting {  // the frame's lighting (lighting_combine.vert)
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec4 vTable;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 texelAt(int texel) { return texelFetch(uMatrices, texelCoord(texel), 0); }

void main() {
  int t = gl_VertexID % uRowTexels;
  int c = (gl_VertexID / uRowTexels) % 3;
  int km = gl_VertexID / (uRowTexels * 3);
  int base = (km * uChannels + (uChannels == 3 ? c : 0)) * uMatrixTexels;
  int activeTexels = (uRows + 3) / 4;
  // The lighting's displayed coefficients, 4 to a vec4, zero from uRows on.
  vec4 light[16];
  for (int u = 0; u < activeTexels; ++u) {
    vec4 l = c == 0 ? uLightR[u] : (c == 1 ? uLightG[u] : uLightB[u]);
    light[u] = l * vec4(lessThan(ivec4(4 * u) + ivec4(0, 1, 2, 3), ivec4(uRows)));
  }
  vec4 rows = vec4(0.0);
  for (int q = 0; q < 4; ++q) {
    int i = 4 * t + q;
    if (i >= uRows) break;
    float acc = 0.0;
    for (int u = 0; u < activeTexels; ++u) acc += dot(texelAt(base + i * uRowTexels + u), light[u]);
    rows[q] = acc;
  }
  vTable = rows;
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
