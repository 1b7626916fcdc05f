#version 300 es
// Glossy PRT, when the lighting changes (docs/web-client.md, "Glossy rendering"): a vertex's
// transferred incident radiance for one lighting channel c,
//   T_vc = table[k][0][c] + sum_j level_vj table[k][j][c]
// (k its cluster, the table glossy_table.vert made from this lighting), independent of the
// view. One point per vertex, rasteriser off, drawn once per channel (uChannel), captured by
// transform feedback as ROW_TEXELS vec4 (vT0 .. vT{ROW_TEXELS-1}). glossyTransferCpu
// (web/src/glossy_texture.cpp) emulates it.
//
// The renderer links this program per (ROW_TEXELS, ACTIVE_TEXELS, VECTORS) and defines them
// after the version line: ROW_TEXELS = ceil(packed bands^2 / 4), the table's stride;
// ACTIVE_TEXELS = ceil(displayed bands^2 / 4) <= ROW_TEXELS, the texels summed (the rest of
// T stays 0); VECTORS = N'. With all three known at compile time the sum is written out below
// (macros over constant indices) and the accumulators are 16 named vectors: a software
// rasteriser that does not unroll loops (SwiftShader) turns a loop-indexed local array and a
// loop-indexed vector component into per-lane memory gathers and scatters, and keeps loop
// state in memory; in SwiftShader the written-out sum takes about half the time of the loops.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp isampler2D;

layout(location = 4) in uint aCluster;
layout(location = 5) in vec4 aSpecular;      // f0 r, g, b; Phong exponent s
layout(location = 6) in float aSpecularF90;  // Schlick's grazing reflectance

uniform sampler2D uTable;     // RGBA32F, glossy_table.vert's output
uniform isampler2D uWeights;  // RGBA8I / RGBA16I levels: texel v * uWeightTexels + j / 4
uniform int uTextureMask;     // the textures' width - 1 (a power of two)
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uWeightTexels;
uniform int uChannel;         // 0 r, 1 g, 2 b
uniform int uAllVertices;     // 1: every vertex's T (bi-scale reads them all), 0: the glossy ones

out vec4 vT0, vT1, vT2, vT3, vT4, vT5, vT6, vT7, vT8, vT9, vT10, vT11, vT12, vT13, vT14, vT15;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 tableTexel(int i) { return texelFetch(uTable, texelCoord(i), 0); }

// One basis vector's (or the mean's) row, times `level`, into the accumulators: texel t of
// the row at `row + t`, for t < ACTIVE_TEXELS (a compile-time test).
#define ADD(a, t, level) if ((t) < ACTIVE_TEXELS) a += (level) * tableTexel(row + (t));
#define ADD_ROW(level) ADD(a0, 0, level) ADD(a1, 1, level) ADD(a2, 2, level) ADD(a3, 3, level) ADD(a4, 4, level) ADD(a5, 5, level) ADD(a6, 6, level) ADD(a7, 7, level) ADD(a8, 8, level) ADD(a9, 9, level) ADD(a10, 10, level) ADD(a11, 11, level) ADD(a12, 12, level) ADD(a13, 13, level) ADD(a14, 14, level) ADD(a15, 15, level)
// Basis vector j (0-based) with its level, for j < VECTORS (compile-time).
#define BASIS(j, level) if ((j) < VECTORS) { row += stride; ADD_ROW(level) }
// Weight texel w: the levels of basis vectors 4w .. 4w + 3.
#define WEIGHTS(i) if (4 * (i) < VECTORS) { q = vec4(texelFetch(uWeights, texelCoord(weightTexel + (i)), 0)); BASIS(4 * (i), q.x) BASIS(4 * (i) + 1, q.y) BASIS(4 * (i) + 2, q.z) BASIS(4 * (i) + 3, q.w) }
#define MEAN(a, t) if ((t) < ACTIVE_TEXELS) a = tableTexel(row + (t));

void main() {
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  vec4 a0 = vec4(0.0), a1 = vec4(0.0), a2 = vec4(0.0), a3 = vec4(0.0), a4 = vec4(0.0), a5 = vec4(0.0), a6 = vec4(0.0), a7 = vec4(0.0);
  vec4 a8 = vec4(0.0), a9 = vec4(0.0), a10 = vec4(0.0), a11 = vec4(0.0), a12 = vec4(0.0), a13 = vec4(0.0), a14 = vec4(0.0), a15 = vec4(0.0);
  // A matte vertex (f0 = f90 = 0) has no glossy term (glossy.vert returns 0 for it): its T is
  // left 0, unread, unless bi-scale asks for every vertex.
  if (uAllVertices == 1 || !(aSpecularF90 == 0.0 && aSpecular.rgb == vec3(0.0))) {
    // The sum's order per entry is glossyTransferCpu's: the mean, then j = 1 .. N', each
    // level read once.
    int stride = 3 * ROW_TEXELS;  // texels from basis vector j's row for channel c to j + 1's
    int row = (int(aCluster) * (1 + VECTORS) * 3 + uChannel) * ROW_TEXELS;
    MEAN(a0, 0) MEAN(a1, 1) MEAN(a2, 2) MEAN(a3, 3) MEAN(a4, 4) MEAN(a5, 5) MEAN(a6, 6) MEAN(a7, 7)
    MEAN(a8, 8) MEAN(a9, 9) MEAN(a10, 10) MEAN(a11, 11) MEAN(a12, 12) MEAN(a13, 13) MEAN(a14, 14) MEAN(a15, 15)
    int weightTexel = gl_VertexID * uWeightTexels;
    vec4 q;
    WEIGHTS(0) WEIGHTS(1) WEIGHTS(2) WEIGHTS(3) WEIGHTS(4) WEIGHTS(5) WEIGHTS(6) WEIGHTS(7)
    WEIGHTS(8) WEIGHTS(9) WEIGHTS(10) WEIGHTS(11) WEIGHTS(12) WEIGHTS(13) WEIGHTS(14) WEIGHTS(15)
  }
  vT0 = a0; vT1 = a1; vT2 = a2; vT3 = a3; vT4 = a4; vT5 = a5; vT6 = a6; vT7 = a7;
  vT8 = a8; vT9 = a9; vT10 = a10; vT11 = a11; vT12 = a12; vT13 = a13; vT14 = a14; vT15 = a15;
}
