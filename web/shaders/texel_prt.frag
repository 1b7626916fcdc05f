#version 300 es
// PRT per fragment from transfer textures (PRTT): exit radiance_c = sum_i T_ci(uv) L_ci, with
// T read bilinearly at the atlas UV from the atlas's RGBA16F texture array (texel_texture.h:
// per channel uLayersPerChannel layers, coefficients 4g .. 4g+3 in layer g, as prt.vert's
// texels). Scalar passes (1 channel) are multiplied by the interpolated vertex albedo, as
// prt.vert multiplies by the vertex albedo; the 3-channel pass has the albedo folded in.
// Output as shade.frag: exposure, the ACES fit and sRGB. uAtlasSpace (the atlas read-back into a
// float target, tests only; texel_prt.vert draws the triangles at their atlas UVs) writes the
// radiance itself, and samples at gl_FragCoord / uAtlasSize, which is exactly the atlas UV
// vAtlasUv approximates there: the rasteriser snaps vertices to a sub-pixel grid (1/16 of a
// texel in SwiftShader), which moves the interpolated UV by up to ~1/32 texel and would mix
// about 2 % of a neighbouring texel into texels beside a sharp shadow.
//
// Glossy by the triple product with fixed lighting (TPFL, PRTT §3; docs/web-client.md "Glossy
// transfer textures"), when uGlossy: the texel's visibility vector v (uVisibility, the same
// layer layout, one channel, read bilinearly), the per-frame product matrix P_c(L) (uProduct,
// texel_glossy.h: row i of channel c at row c n^2 + i, 4 columns a texel), T_c = P_c v, and
// L_c = k_s,c sum_i g_l(i)(s) y_i(R) T_c,i with R = reflect(-view, n) and Schlick's n.v of the
// shading normal n: the asset's texel normal (uNormals, bilinear, made unit) where normal maps
// turned it (uShadingNormals), else the interpolated vertex normal: prt::tpflGlossyExitRadiance,
// emulated by tpflGlossyCpu. The diffuse transfer needs no normal here: the baker folded the
// mapped normal's cosine into it. shBasis and phongBandScales are the loop form of the
// recurrences glossy.vert writes out per band count (both emulated by glossy_texture.cpp's
// glossyShBasis and prt/glossy_lobe.h, and tested against them); schlick is glossy.vert's text
// (texel_core_node_test checks it).
precision highp sampler2D;
precision highp float;
precision highp int;
precision highp sampler2DArray;

in vec2 vAtlasUv;
in vec3 vAlbedo;
in vec3 vPosition;
in vec3 vNormal;
in vec4 vSpecular;
in float vSpecularF90;

uniform sampler2DArray uTransfer;
uniform int uLayersPerChannel;  // ceil(order^2 / 4) at the order the texture holds
uniform int uChannels;          // 1 or 3
uniform int uActiveLayers;      // ceil(order'^2 / 4) at the displayed order (<= uLayersPerChannel)
uniform float uExposure;        // linear scale, 2^EV
uniform bool uAtlasSpace;
uniform vec2 uAtlasSize;        // texels, for uAtlasSpace
uniform bool uWritePosition;    // with uAtlasSpace (tests): the fragment's world position, not radiance
uniform bool uDiffuse;          // the diffuse texel term (the panel's diffuse / glossy switch)
uniform bool uGlossy;           // the TPFL glossy term
uniform sampler2DArray uVisibility;  // RGBA16F, ceil(m^2 / 4) layers of the visibility vector
uniform sampler2D uProduct;     // RGBA32F, P_c(L): ceil(transfer order^2 / 4) wide, 3 uBands^2 high
uniform int uVisibilityLayers;  // layers of v read: ceil(min(m, transfer order)^2 / 4) <= 57
uniform int uBands;             // the product's bands n (lighting and output), <= 8
uniform int uFresnel;           // 0: k_s = f0
uniform vec3 uEye;              // world space
uniform sampler2D uNormals;     // RGBA16F per atlas: unit shading normal, w = 1; all 0 at empty texels
uniform bool uShadingNormals;   // the asset has texel normals (format 1.6): reflect about them
// Real SH by Lisle & Huang's recurrence, constants as prt/sh_basis.cpp (glossy_texture.h).
uniform float uShY00;
uniform float uShK1;
uniform vec4 uShA[16];
uniform vec4 uShB[16];

layout(std140) uniform Lighting {  // built on the GPU by lighting_combine.vert
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec4 fragColor;

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

// The TPFL glossy exit radiance at this fragment (see the top of the file).
vec3 glossyTerm(vec2 uv) {
  vec3 d = uEye - vPosition;
  float distance = length(d);
  if (!(distance > 0.0)) return vec3(0.0);
  vec3 toEye = d * (1.0 / distance);
  vec3 n = normalize(vNormal);
  if (uShadingNormals) {
    // w is the share of the bilinear taps that hold a normal: at a chart's outer gutter edge
    // the taps may reach empty texels (all 0), which only shorten the sum.
    vec4 mapped = textureLod(uNormals, uv, 0.0);
    if (mapped.w > 0.0 && dot(mapped.xyz, mapped.xyz) > 1e-12) n = normalize(mapped.xyz);
  }
  vec3 ks = schlick(vSpecular.rgb, vSpecularF90, dot(n, toEye), uFresnel == 1);
  // A matte surface (f0 = f90 = 0: the room's walls) has k_s = 0 at every angle: its glossy
  // term is exactly 0, so skip the n^2 x m^2 product (the bulk of a texel frame's cost).
  if (ks == vec3(0.0)) return vec3(0.0);
  vec3 r = n * (2.0 * dot(n, toEye)) - toEye;
  float rl = length(r);
  r = rl > 0.0 ? r * (1.0 / rl) : n;
  shBasis(uBands, r);
  float g[8];
  phongBandScales(uBands, vSpecular.w, g);
  vec4 v[57];
  for (int t = 0; t < uVisibilityLayers; ++t) v[t] = textureLod(uVisibility, vec3(uv, float(t)), 0.0);
  int rows = uBands * uBands;
  vec3 glossy = vec3(0.0);
  for (int c = 0; c < 3; ++c) {
    float sum = 0.0;
    for (int i = 0; i < rows; ++i) {
      float transferred = 0.0;
      for (int t = 0; t < uVisibilityLayers; ++t) transferred += dot(texelFetch(uProduct, ivec2(t, c * rows + i), 0), v[t]);
      sum += g[int(sqrt(float(i) + 0.5))] * y[i] * transferred;
    }
    glossy[c] = ks[c] * sum;
  }
  return glossy;
}


// Level 0 explicitly: the arrays have no mipmaps, and textureLod needs no derivatives.
vec4 coefficients(vec2 uv, int layer) {
  return textureLod(uTransfer, vec3(uv, float(layer)), 0.0);
}

// The same two functions as shade.frag (texel_core_node_test.mjs checks they stay identical).
vec3 acesFit(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  vec2 uv = uAtlasSpace ? gl_FragCoord.xy / uAtlasSize : vAtlasUv;
  vec3 radiance = vec3(0.0);
  if (!uDiffuse) {
    // glossy only
  } else if (uChannels == 1) {
    for (int t = 0; t < uActiveLayers; ++t) {
      vec4 transfer = coefficients(uv, t);
      radiance += vec3(dot(transfer, uLightR[t]), dot(transfer, uLightG[t]), dot(transfer, uLightB[t]));
    }
    radiance *= vAlbedo;
  } else {
    for (int t = 0; t < uActiveLayers; ++t) {
      radiance.r += dot(coefficients(uv, t), uLightR[t]);
      radiance.g += dot(coefficients(uv, uLayersPerChannel + t), uLightG[t]);
      radiance.b += dot(coefficients(uv, 2 * uLayersPerChannel + t), uLightB[t]);
    }
  }
  if (uGlossy) radiance += glossyTerm(uv);
  if (uAtlasSpace && uWritePosition) {
    fragColor = vec4(vPosition, 1.0);
    return;
  }
  if (uAtlasSpace) {
    fragColor = vec4(radiance, 1.0);
    return;
  }
  vec3 mapped = acesFit(max(radiance, vec3(0.0)) * uExposure);
  fragColor = vec4(linearToSrgb(mapped), 1.0);
}
