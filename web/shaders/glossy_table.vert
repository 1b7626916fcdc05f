#version 300 es
// Glossy PRT, per frame (docs/web-client.md, "Glossy rendering"): every cluster's mean and
// basis matrices times the lighting, A_km,c L_c, from the CPCA matrix pass without expanding
// it (Sloan et al. 2003 §4.1). One point per table texel, rasteriser off, captured by transform
// feedback: point ((k * (1 + N') + m) * 3 + c) * uRowTexels + t writes rows 4t .. 4t+3 of the
// product for cluster k, matrix m (0 the mean, else a basis matrix with its weight step folded
// in) and lighting channel c. web/src/glossy_texture.cpp (glossyTableCpu) emulates it exactly.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D uMatrices;  // RGBA32F: matrix ((k * (1 + N') + m) * uChannels + c), uMatrixTexels texels each
uniform int uTextureWidth;
uniform int uRowTexels;       // ceil(bands^2 / 4) at the packed order
uniform int uMatrixTexels;    // ceil(packed entries / 4)
uniform int uChannels;        // 1: one matrix for r, g, b; 3: one per channel
uniform int uRows;            // displayed bands^2 (<= packed bands^2)
uniform int uSymmetric;       // 1: lower-triangle packing; 0: the shell packing (prt/transfer_matrix.h)
layout(std140) uniform Lighting {  // the frame's lighting (lighting_combine.vert)
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec4 vTable;

float lightAt(int c, int j) {
  vec4 t = c == 0 ? uLightR[j >> 2] : (c == 1 ? uLightG[j >> 2] : uLightB[j >> 2]);
  return t[j & 3];
}

// prt/transfer_matrix.h matrixEntryIndex.
int entryIndex(int i, int j) {
  int k = max(i, j);
  if (uSymmetric == 1) return k * (k + 1) / 2 + min(i, j);
  if (i == j) return k * k + 2 * k;
  return i == k ? k * k + j : k * k + k + i;
}

float entry(int base, int e) {
  int texel = base + (e >> 2);
  return texelFetch(uMatrices, ivec2(texel % uTextureWidth, texel / uTextureWidth), 0)[e & 3];
}

void main() {
  int t = gl_VertexID % uRowTexels;
  int c = (gl_VertexID / uRowTexels) % 3;
  int km = gl_VertexID / (uRowTexels * 3);
  int base = (km * uChannels + (uChannels == 3 ? c : 0)) * uMatrixTexels;
  vec4 rows = vec4(0.0);
  for (int q = 0; q < 4; ++q) {
    int i = 4 * t + q;
    float acc = 0.0;
    if (i < uRows) {
      for (int j = 0; j < uRows; ++j) acc += entry(base, entryIndex(i, j)) * lightAt(c, j);
    }
    rows[q] = acc;
  }
  vTable = rows;
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
