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
precision highp float;
precision highp int;
precision highp sampler2DArray;

in vec2 vAtlasUv;
in vec3 vAlbedo;

uniform sampler2DArray uTransfer;
uniform int uLayersPerChannel;  // ceil(order^2 / 4) at the order the texture holds
uniform int uChannels;          // 1 or 3
uniform int uActiveLayers;      // ceil(order'^2 / 4) at the displayed order (<= uLayersPerChannel)
uniform float uExposure;        // linear scale, 2^EV
uniform bool uAtlasSpace;
uniform vec2 uAtlasSize;        // texels, for uAtlasSpace
layout(std140) uniform Lighting {  // built on the GPU by lighting_combine.vert
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec4 fragColor;

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
  if (uChannels == 1) {
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
  if (uAtlasSpace) {
    fragColor = vec4(radiance, 1.0);
    return;
  }
  vec3 mapped = acesFit(max(radiance, vec3(0.0)) * uExposure);
  fragColor = vec4(linearToSrgb(mapped), 1.0);
}
