#version 300 es
// Glossy PRT, when the lighting changes (docs/web-client.md, "Glossy rendering"): a vertex's
// transferred incident radiance for one lighting channel c,
//   T_vc = table[k][0][c] + sum_j level_vj table[k][j][c]
// (k its cluster, the table glossy_table.vert made from this lighting), independent of the
// view. One point per vertex, rasteriser off, drawn once per channel (uChannel), captured by
// transform feedback as ROW_TEXELS vec4 (vT0 .. vT15, the first ROW_TEXELS of them captured:
// the program is linked per row width). glossyTransferCpu (web/src/glossy_texture.cpp)
// emulates it.
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
uniform int uRowTexels;       // ceil(packed bands^2 / 4): the table's stride (<= 16)
uniform int uActiveTexels;    // ceil(displayed bands^2 / 4) (<= uRowTexels)
uniform int uVectors;         // N' (<= 64)
uniform int uWeightTexels;
uniform int uChannel;         // 0 r, 1 g, 2 b

out vec4 vT0, vT1, vT2, vT3, vT4, vT5, vT6, vT7, vT8, vT9, vT10, vT11, vT12, vT13, vT14, vT15;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 tableTexel(int i) { return texelFetch(uTable, texelCoord(i), 0); }

void main() {
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  vec4 tr[16];
  for (int t = 0; t < 16; ++t) tr[t] = vec4(0.0);
  // A matte vertex (f0 = f90 = 0) has no glossy term (glossy.vert returns 0 for it): its T is
  // left 0, unread.
  bool matte = aSpecularF90 == 0.0 && aSpecular.rgb == vec3(0.0);
  // Basis vectors outer, row texels inner: each basis vector's level is read once and its row
  // is one run of texels from `row`; the loops have constant bounds (16 texels, 4 levels a
  // weight texel) so the accumulators stay in registers where the compiler unrolls them. The
  // sum's order per entry is glossyTransferCpu's: the mean, then j = 1 .. N'.
  int stride = 3 * uRowTexels;  // texels from basis vector j's row for channel c to j + 1's
  int row = (int(aCluster) * (1 + uVectors) * 3 + uChannel) * uRowTexels;
  for (int t = 0; t < 16; ++t) {
    if (matte || t >= uActiveTexels) break;
    tr[t] = tableTexel(row + t);
  }
  int weightTexel = gl_VertexID * uWeightTexels;
  for (int w = 0; w < (matte ? 0 : uWeightTexels); ++w) {
    vec4 q = vec4(texelFetch(uWeights, texelCoord(weightTexel + w), 0));
    for (int u = 0; u < 4; ++u) {
      if (4 * w + u >= uVectors) break;
      row += stride;
      for (int t = 0; t < 16; ++t) {
        if (t >= uActiveTexels) break;
        tr[t] += q[u] * tableTexel(row + t);
      }
    }
  }
  vT0 = tr[0]; vT1 = tr[1]; vT2 = tr[2]; vT3 = tr[3]; vT4 = tr[4]; vT5 = tr[5]; vT6 = tr[6]; vT7 = tr[7];
  vT8 = tr[8]; vT9 = tr[9]; vT10 = tr[10]; vT11 = tr[11]; vT12 = tr[12]; vT13 = tr[13]; vT14 = tr[14]; vT15 = tr[15];
}
