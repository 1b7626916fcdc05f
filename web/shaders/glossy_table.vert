#version 300 es
// Glossy PRT, when the lighting changes (docs/web-client.md, "Glossy rendering"): every
// cluster's mean and basis matrices times the lighting, A_km,c L_c, from the CPCA matrix pass
// without expanding it per vertex (Sloan et al. 2003 §4.1). One point per table texel,
// rasteriser off, captured by transform feedback: point ((k * (1 + N') + m) * 3 + c) *
// ROW_TEXELS + t writes rows 4t .. 4t+3 of the product for cluster k, matrix m (0 the mean,
// else a basis matrix with its weight step folded in) and lighting channel c. The matrices are
// stored as full rows of ROW_TEXELS texels, so a row times the lighting is ACTIVE_TEXELS vec4
// dot products. web/src/glossy_texture.cpp (glossyTableCpu) emulates it.
//
// The renderer links it per (ROW_TEXELS = ceil(packed bands^2 / 4), ROWS = displayed bands^2)
// and defines both after the version line, so the loops below are written out with constant
// indices (see glossy_transfer.vert for why).
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D uMatrices;  // RGBA32F: matrix ((k * (1 + N') + m) * uChannels + c), uMatrixTexels texels each
uniform int uTextureMask;     // the textures' width - 1 (a power of two)
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uMatrixTexels;    // packed bands^2 * ROW_TEXELS
uniform int uChannels;        // 1: one matrix for r, g, b; 3: one per channel
layout(std140) uniform Lighting {  // the frame's lighting (lighting_combine.vert)
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec4 vTable;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 texelAt(int texel) { return texelFetch(uMatrices, texelCoord(texel), 0); }

#define ACTIVE_TEXELS ((ROWS + 3) / 4)
// The lighting's texel u, zero from ROWS on (compile-time tests).
#define LIGHT(u) if ((u) < ACTIVE_TEXELS) light[u] = (c == 0 ? uLightR[u] : (c == 1 ? uLightG[u] : uLightB[u])) * vec4(4 * (u) < ROWS, 4 * (u) + 1 < ROWS, 4 * (u) + 2 < ROWS, 4 * (u) + 3 < ROWS);
#define TERM(r, u) if ((u) < ACTIVE_TEXELS) acc += dot(texelAt(r + (u)), light[u]);

// Matrix row `i` (its first texel at `r`) times the lighting; 0 from ROWS on.
float rowTimesLight(int i, int r, vec4 light[16]) {
  if (i >= ROWS) return 0.0;
  float acc = 0.0;
  TERM(r, 0) TERM(r, 1) TERM(r, 2) TERM(r, 3) TERM(r, 4) TERM(r, 5) TERM(r, 6) TERM(r, 7)
  TERM(r, 8) TERM(r, 9) TERM(r, 10) TERM(r, 11) TERM(r, 12) TERM(r, 13) TERM(r, 14) TERM(r, 15)
  return acc;
}

void main() {
  int t = gl_VertexID % ROW_TEXELS;
  int c = (gl_VertexID / ROW_TEXELS) % 3;
  int km = gl_VertexID / (ROW_TEXELS * 3);
  int base = (km * uChannels + (uChannels == 3 ? c : 0)) * uMatrixTexels;
  vec4 light[16];
  LIGHT(0) LIGHT(1) LIGHT(2) LIGHT(3) LIGHT(4) LIGHT(5) LIGHT(6) LIGHT(7)
  LIGHT(8) LIGHT(9) LIGHT(10) LIGHT(11) LIGHT(12) LIGHT(13) LIGHT(14) LIGHT(15)
  int i = 4 * t;
  int r = base + i * ROW_TEXELS;
  vTable = vec4(rowTimesLight(i, r, light), rowTimesLight(i + 1, r + ROW_TEXELS, light),
                rowTimesLight(i + 2, r + 2 * ROW_TEXELS, light), rowTimesLight(i + 3, r + 3 * ROW_TEXELS, light));
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
