#version 300 es
// Glossy PRT, per vertex and every frame (docs/web-client.md, "Glossy rendering"): the
// transferred incident radiance T_c (glossy_transfer.vert's output for the current lighting),
// convolved with the Phong lobe (band scales g_l(s), prt/glossy_lobe.h) and evaluated at the
// mirror direction R of the live eye:
//   L_c = k_s,c sum_i (g_l(i) T_c,i) y_i(R),   k_s = Schlick(f0, f90, n.v)
// as prt::glossyExitRadiance (prt/glossy_radiance.h). One point per vertex, rasteriser off,
// captured by transform feedback; glossyRadianceCpu (web/src/glossy_texture.cpp) emulates it.
precision highp float;
precision highp int;
precision highp sampler2D;

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec3 aNormal;
layout(location = 5) in vec4 aSpecular;  // f0 r, g, b; Phong exponent s
layout(location = 6) in float aSpecularF90;  // Schlick's grazing reflectance (0: no specular part)

uniform sampler2D uTransfer;  // RGBA32F: T_vc rows 4t .. 4t+3 at texel (c * uVertices + v) * uRowTexels + t
uniform int uTextureMask;     // the textures' width - 1 (a power of two)
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uRowTexels;       // ceil(packed bands^2 / 4)
uniform int uVertices;
uniform int uBands;           // displayed bands (<= 8)
uniform int uFresnel;         // 0: k_s = f0
uniform vec3 uEye;            // world space
// Real SH by Lisle & Huang's recurrence, constants as prt/sh_basis.cpp (glossy_texture.h).
uniform float uShY00;
uniform float uShK1;
uniform vec4 uShA[16];
uniform vec4 uShB[16];

out vec3 vGlossy;

float y[64];

float shA(int i) { return uShA[i >> 2][i & 3]; }
float shB(int i) { return uShB[i >> 2][i & 3]; }

void shBasis(int order, vec3 d) {
  y[0] = uShY00;
  if (order == 1) return;
  y[1] = uShK1 * d.y;
  y[2] = uShK1 * d.z;
  y[3] = uShK1 * d.x;
  for (int l = 2; l < order; ++l) {
    int base = l * (l + 1), base1 = (l - 1) * l, base2 = (l - 2) * (l - 1);
    for (int m = -(l - 2); m <= l - 2; ++m) y[base + m] = shA(base + m) * d.z * y[base1 + m] - shB(base + m) * y[base2 + m];
    y[base - (l - 1)] = shA(base - (l - 1)) * d.z * y[base1 - (l - 1)];
    y[base + (l - 1)] = shA(base + (l - 1)) * d.z * y[base1 + (l - 1)];
    float sp = y[base1 + (l - 1)], sn = y[base1 - (l - 1)];
    float c = shA(base + l);
    y[base + l] = c * (d.x * sp - d.y * sn);
    y[base - l] = c * (d.y * sp + d.x * sn);
  }
}

// Phong band scales g_l(s) = (s+1) I_l (prt/glossy_lobe.cpp's recurrence, in float).
void phongBandScales(int bands, float s, out float g[8]) {
  float evenPrev = 1.0 / (s + 1.0), oddPrev = 1.0 / (s + 2.0);
  for (int l = 0; l < bands; ++l) {
    float value;
    if (l == 0) {
      value = evenPrev;
    } else if (l == 1) {
      value = oddPrev;
    } else if (l % 2 == 0) {
      evenPrev = evenPrev * (s - float(l) + 2.0) / (s + float(l) + 1.0);
      value = evenPrev;
    } else {
      oddPrev = oddPrev * (s - float(l) + 2.0) / (s + float(l) + 1.0);
      value = oddPrev;
    }
    g[l] = (s + 1.0) * value;
  }
}

// Schlick's k_s = f0 + (f90 - f0)(1 - max(0, n.v))^5 (prt::schlickFresnel); f0 alone when off.
vec3 schlick(vec3 f0, float f90, float cosNormalView, bool on) {
  if (!on) return f0;
  float k = 1.0 - clamp(cosNormalView, 0.0, 1.0);
  float k2 = k * k, k5 = k2 * k2 * k;
  return f0 + (f90 - f0) * k5;
}

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 transferTexel(int i) { return texelFetch(uTransfer, texelCoord(i), 0); }

void main() {
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  vGlossy = vec3(0.0);
  // A matte vertex (f0 = f90 = 0: k_s = 0 at every angle) has no glossy term: exactly the 0
  // that k_s times the sum below would give, without the basis and the fetches.
  if (aSpecularF90 == 0.0 && aSpecular.rgb == vec3(0.0)) return;
  vec3 d = uEye - aPosition;
  float distance = length(d);
  if (!(distance > 0.0)) return;
  vec3 toEye = d * (1.0 / distance);
  vec3 n = aNormal;
  vec3 r = n * (2.0 * dot(n, toEye)) - toEye;
  float rl = length(r);
  r = rl > 0.0 ? r * (1.0 / rl) : n;
  shBasis(uBands, r);
  float g[8];
  phongBandScales(uBands, aSpecular.w, g);
  vec3 ks = schlick(aSpecular.rgb, aSpecularF90, dot(n, toEye), uFresnel == 1);
  int rows = uBands * uBands, activeTexels = (rows + 3) / 4;
  // The lobe's band scales folded into the basis once: gy_i = g_l(i) y_i(R), zero from rows on.
  vec4 gy[16];
  for (int t = 0; t < activeTexels; ++t) {
    for (int q = 0; q < 4; ++q) {
      int i = 4 * t + q;
      gy[t][q] = i < rows ? g[int(sqrt(float(i) + 0.5))] * y[i] : 0.0;
    }
  }
  for (int c = 0; c < 3; ++c) {
    float sum = 0.0;
    int base = (c * uVertices + gl_VertexID) * uRowTexels;
    for (int t = 0; t < activeTexels; ++t) sum += dot(transferTexel(base + t), gy[t]);
    vGlossy[c] = ks[c] * sum;
  }
}
