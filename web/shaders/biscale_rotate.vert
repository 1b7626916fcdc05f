#version 300 es
// Bi-scale, when the lighting changes (docs/bi-scale.md, "The client"): a vertex's transferred
// incident radiance T_c (glossy_transfer.vert's output, world frame) rotated into the vertex's
// tangent frame, D_v T_c: the radiance incident on the meso scale, in the RTT's frame (the
// paper's M_p L). One point per vertex, rasteriser off, drawn once per channel (uChannel),
// captured by transform feedback as ROW_TEXELS vec4 in T's layout. Its main() is written out
// per (bands, ROW_TEXELS) by biScaleRotateMain (web/src/bi_scale_texture.cpp), which
// biScaleRotateCpu emulates.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D uTransfer;   // RGBA32F: T_vc, texel (c * uVertices + v) * ROW_TEXELS + t
uniform sampler2D uRotations;  // RGBA32F: D_v's blocks of bands 1.., texel v * ROTATION_TEXELS + k
uniform int uTextureMask;      // both textures' width - 1 (a power of two)
uniform int uTextureShift;     // log2 of their width: texel i is at (i & mask, i >> shift)
uniform int uVertices;
uniform int uChannel;          // 0 r, 1 g, 2 b

out vec4 vR0, vR1, vR2, vR3, vR4, vR5, vR6, vR7, vR8, vR9, vR10, vR11, vR12, vR13, vR14, vR15;

ivec2 texelCoord(int i) { return ivec2(i & uTextureMask, i >> uTextureShift); }
vec4 transferTexel(int i) { return texelFetch(uTransfer, texelCoord(i), 0); }
vec4 rotationTexel(int i) { return texelFetch(uRotations, texelCoord(i), 0); }
