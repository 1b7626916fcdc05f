#version 300 es
// Glossy PRT, per vertex and every frame (docs/web-client.md, "Glossy rendering"): the
// transferred incident radiance T_c (glossy_transfer.vert's output for the current lighting),
// convolved with the Phong lobe (band scales g_l(s), prt/glossy_lobe.h) and evaluated at the
// mirror direction R of the live eye:
//   L_c = k_s,c sum_i (g_l(i) T_c,i) y_i(R),   k_s = Schlick(f0, f90, n.v)
// as prt::glossyExitRadiance (prt/glossy_radiance.h). One point per vertex, rasteriser off,
// captured by transform feedback; glossyRadianceCpu (web/src/glossy_texture.cpp) emulates it.
//
// The renderer links this program per displayed band count and defines BANDS (1 .. 8) after
// the version line, so the SH recurrence, the band scales and the sum are written out below
// with constant indices (see glossy_transfer.vert for why: no loop-indexed local arrays).
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp isampler2D;

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec3 aNormal;
layout(location = 5) in vec4 aSpecular;  // f0 r, g, b; Phong exponent s
layout(location = 6) in float aSpecularF90;  // Schlick's grazing reflectance (0: no specular part)

uniform sampler2D uTransfer;  // RGBA32F: T_vc rows 4t .. 4t+3 at texel (c * uVertices + v) * uRowTexels + t
uniform int uTextureMask;     // the textures' width - 1 (a power of two)
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uRowTexels;       // ceil(packed bands^2 / 4)
uniform int uVertices;
uniform int uFresnel;         // 0: k_s = f0
uniform vec3 uEye;            // world space
// Real SH by Lisle & Huang's recurrence, constants as prt/sh_basis.cpp (glossy_texture.h).
uniform float uShY00;
uniform float uShK1;
uniform vec4 uShA[16];
uniform vec4 uShB[16];

#ifdef GROUP
// The fused form (GROUP vertices of one cluster a point; its main() is generated and appended
// by glossyFusedMain, web/src/glossy_fused.cpp): the table straight times the lobe.
layout(location = 4) in uint aCluster;   // the group's cluster
layout(location = 7) in ivec4 aMembers0;  // vertex ids of members 0 .. 3 (-1: none)
layout(location = 8) in ivec4 aMembers1;  // members 4 .. 7
uniform sampler2D uTable;                 // RGBA32F, glossy_table.vert's output
uniform isampler2D uWeights;              // RGBA8I / RGBA16I levels: texel v * uWeightTexels + j / 4
uniform sampler2D uVertexData;            // RGBA32F, texels 3v .. 3v+2: (position, f90), (normal, s), (f0, 0)
uniform int uWeightTexels;
#else
out vec3 vGlossy;
#endif

#define ROWS (BANDS * BANDS)
#define TEXELS ((ROWS + 3) / 4)
// SH index of band l, order m; the recurrence's constants of an index.
#define IDX(l, m) ((l) * ((l) + 1) + (m))
#define SHA(i) uShA[(i) >> 2][(i) & 3]
#define SHB(i) uShB[(i) >> 2][(i) & 3]
// Band l's entry m with |m| <= l - 2, from bands l - 1 and l - 2.
#define MID(l, m) y[IDX(l, m)] = SHA(IDX(l, m)) * r.z * y[IDX((l) - 1, m)] - SHB(IDX(l, m)) * y[IDX((l) - 2, m)];
// Band l's entries m = +-(l - 1) and +-l, from band l - 1.
#define EDGES(l) y[IDX(l, 1 - (l))] = SHA(IDX(l, 1 - (l))) * r.z * y[IDX((l) - 1, 1 - (l))]; y[IDX(l, (l) - 1)] = SHA(IDX(l, (l) - 1)) * r.z * y[IDX((l) - 1, (l) - 1)]; y[IDX(l, l)] = SHA(IDX(l, l)) * (r.x * y[IDX((l) - 1, (l) - 1)] - r.y * y[IDX((l) - 1, 1 - (l))]); y[IDX(l, -(l))] = SHA(IDX(l, l)) * (r.y * y[IDX((l) - 1, (l) - 1)] + r.x * y[IDX((l) - 1, 1 - (l))]);
// Phong band scales g_l(s) = (s+1) I_l by prt/glossy_lobe.cpp's recurrence (even and odd l
// each from l - 2), in float.
#define SCALE(l, prev) prev = prev * (s - float(l) + 2.0) / (s + float(l) + 1.0); g[l] = (s + 1.0) * prev;
// Entry i of g_l(i) y_i(R), zero from ROWS on (kBand: the band of an index).
#define GY(i) ((i) < ROWS ? g[kBand[i]] * y[i] : 0.0)
#define GY_TEXEL(t) if ((t) < TEXELS) gy[t] = vec4(GY(4 * (t)), GY(4 * (t) + 1), GY(4 * (t) + 2), GY(4 * (t) + 3));
#define SUM(t) if ((t) < TEXELS) sum += dot(transferTexel(base + (t)), gy[t]);

const int kBand[64] = int[64](0, 1, 1, 1, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4,
                              5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6,
                              7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7);

// Schlick's k_s = f0 + (f90 - f0)(1 - max(0, n.v))^5 (prt::schlickFresnel); f0 alone when off.
vec3 schlick(vec3 f0, float f90, float cosNormalView, bool on) {
  if (!on) return f0;
  float k = 1.0 - clamp(cosNormalView, 0.0, 1.0);
  float k2 = k * k, k5 = k2 * k2 * k;
  return f0 + (f90 - f0) * k5;
}

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 transferTexel(int i) { return texelFetch(uTransfer, texelCoord(i), 0); }


// The lobe toward the eye at a vertex: gy_i = g_l(i)(s) y_i(R) for i < ROWS (zero beyond and
// when false is returned) and Schlick's k_s. False when the vertex has no glossy term: matte
// (f0 = f90 = 0: k_s = 0 at every angle, exactly the 0 the sum would give) or at the eye.
bool lobeTowardEye(vec3 position, vec3 n, vec4 specular, float f90, out vec4 gy[16], out vec3 ks) {
  gy[0] = vec4(0.0); gy[1] = vec4(0.0); gy[2] = vec4(0.0); gy[3] = vec4(0.0); gy[4] = vec4(0.0); gy[5] = vec4(0.0); gy[6] = vec4(0.0); gy[7] = vec4(0.0);
  gy[8] = vec4(0.0); gy[9] = vec4(0.0); gy[10] = vec4(0.0); gy[11] = vec4(0.0); gy[12] = vec4(0.0); gy[13] = vec4(0.0); gy[14] = vec4(0.0); gy[15] = vec4(0.0);
  ks = vec3(0.0);
  if (f90 == 0.0 && specular.rgb == vec3(0.0)) return false;
  vec3 d = uEye - position;
  float distance = length(d);
  if (!(distance > 0.0)) return false;
  vec3 toEye = d * (1.0 / distance);
  vec3 r = n * (2.0 * dot(n, toEye)) - toEye;
  float rl = length(r);
  r = rl > 0.0 ? r * (1.0 / rl) : n;
  // y_i(R), bands 0 .. BANDS - 1 (Lisle & Huang, as prt/sh_basis.cpp).
  float y[64];
  y[0] = uShY00;
#if BANDS > 1
  y[1] = uShK1 * r.y;
  y[2] = uShK1 * r.z;
  y[3] = uShK1 * r.x;
#endif
#if BANDS > 2
  MID(2, 0) EDGES(2)
#endif
#if BANDS > 3
  MID(3, -1) MID(3, 0) MID(3, 1) EDGES(3)
#endif
#if BANDS > 4
  MID(4, -2) MID(4, -1) MID(4, 0) MID(4, 1) MID(4, 2) EDGES(4)
#endif
#if BANDS > 5
  MID(5, -3) MID(5, -2) MID(5, -1) MID(5, 0) MID(5, 1) MID(5, 2) MID(5, 3) EDGES(5)
#endif
#if BANDS > 6
  MID(6, -4) MID(6, -3) MID(6, -2) MID(6, -1) MID(6, 0) MID(6, 1) MID(6, 2) MID(6, 3) MID(6, 4) EDGES(6)
#endif
#if BANDS > 7
  MID(7, -5) MID(7, -4) MID(7, -3) MID(7, -2) MID(7, -1) MID(7, 0) MID(7, 1) MID(7, 2) MID(7, 3) MID(7, 4) MID(7, 5) EDGES(7)
#endif

  float g[8];
  float s = specular.w;
  float even = 1.0 / (s + 1.0), odd = 1.0 / (s + 2.0);
  g[0] = (s + 1.0) * even;
#if BANDS > 1
  g[1] = (s + 1.0) * odd;
#endif
#if BANDS > 2
  SCALE(2, even)
#endif
#if BANDS > 3
  SCALE(3, odd)
#endif
#if BANDS > 4
  SCALE(4, even)
#endif
#if BANDS > 5
  SCALE(5, odd)
#endif
#if BANDS > 6
  SCALE(6, even)
#endif
#if BANDS > 7
  SCALE(7, odd)
#endif

  // The lobe's band scales folded into the basis once: gy_i = g_l(i) y_i(R), zero from ROWS on.
  GY_TEXEL(0) GY_TEXEL(1) GY_TEXEL(2) GY_TEXEL(3) GY_TEXEL(4) GY_TEXEL(5) GY_TEXEL(6) GY_TEXEL(7)
  GY_TEXEL(8) GY_TEXEL(9) GY_TEXEL(10) GY_TEXEL(11) GY_TEXEL(12) GY_TEXEL(13) GY_TEXEL(14) GY_TEXEL(15)
  ks = schlick(specular.rgb, f90, dot(n, toEye), uFresnel == 1);
  return true;
}

#ifndef GROUP
// sum_i gy_i T_i over the transfer row at `row` (channel c of vertex v: row c * V + v).
float channelSum(int row, vec4 gy[16]) {
  float sum = 0.0;
  int base = row * uRowTexels;
  SUM(0) SUM(1) SUM(2) SUM(3) SUM(4) SUM(5) SUM(6) SUM(7) SUM(8) SUM(9) SUM(10) SUM(11) SUM(12) SUM(13) SUM(14) SUM(15)
  return sum;
}

void main() {
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  vGlossy = vec3(0.0);
  vec4 gy[16];
  vec3 ks;
  if (!lobeTowardEye(aPosition, aNormal, aSpecular, aSpecularF90, gy, ks)) return;
  vGlossy = vec3(ks.r * channelSum(gl_VertexID, gy), ks.g * channelSum(uVertices + gl_VertexID, gy),
                 ks.b * channelSum(2 * uVertices + gl_VertexID, gy));
}
#endif
