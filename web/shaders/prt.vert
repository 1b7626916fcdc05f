#version 300 es
// PRT shading in the vertex shader: exit radiance_c = sum_i T_ci L_ci (docs/web-client.md).
// Transfer is read from a float texture by gl_VertexID: each vertex owns
// uTexelsPerChannel * uChannels RGBA32F texels, laid out [channel][coefficient] with each
// channel padded to whole texels.
// Scalar passes (1 channel) are multiplied by the vertex albedo; RGB passes carry it.
precision highp float;
precision highp int;
precision highp sampler2D;

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;

uniform mat4 uViewProjection;
uniform sampler2D uTransfer;
uniform int uTextureMask;     // the textures' width - 1 (a power of two)
uniform int uTextureShift;    // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uTexelsPerChannel;  // ceil(order^2 / 4) at the baked order
uniform int uChannels;          // 1 or 3
uniform int uActiveTexels;      // ceil(order'^2 / 4) at the displayed order (<= uTexelsPerChannel)
// Lighting packed like the transfer: 4 coefficients per vec4, 16 vec4 = order 8.
layout(std140) uniform Lighting {  // built on the GPU by lighting_combine.vert
  vec4 uLightR[16];
  vec4 uLightG[16];
  vec4 uLightB[16];
};

out vec3 vRadiance;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }

vec4 transferTexel(int index) {
  return texelFetch(uTransfer, texelCoord(index), 0);
}

void main() {
  int texelsPerVertex = uTexelsPerChannel * uChannels;
  int base = gl_VertexID * texelsPerVertex;
  vec3 radiance = vec3(0.0);
  if (uChannels == 1) {
    for (int t = 0; t < uActiveTexels; ++t) {
      vec4 transfer = transferTexel(base + t);
      radiance += vec3(dot(transfer, uLightR[t]), dot(transfer, uLightG[t]), dot(transfer, uLightB[t]));
    }
    radiance *= aAlbedo;
  } else {
    for (int t = 0; t < uActiveTexels; ++t) {
      radiance.r += dot(transferTexel(base + t), uLightR[t]);
      radiance.g += dot(transferTexel(base + uTexelsPerChannel + t), uLightG[t]);
      radiance.b += dot(transferTexel(base + 2 * uTexelsPerChannel + t), uLightB[t]);
    }
  }
  vRadiance = radiance;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
