#version 300 es
// Transfer textures (PRTT; docs/web-client.md "Transfer textures"): the vertex stage only
// places the triangle and hands the atlas UV (one per vertex, the asset's atlas uv section) and
// the vertex albedo to texel_prt.frag, which does the shading. The atlas itself is chosen per
// draw call (an atlas's triangles are one contiguous run, and GLSL ES 3.00 cannot index an
// array of samplers with a varying), so no atlas index travels per vertex.
// uAtlasSpace draws the triangles where they lie in the atlas instead (clip = 2 uv - 1, so
// framebuffer row y is texel row y): the read-back the tests compare with the baker's texels.
// The glossy (TPFL) term needs the world position, the vertex normal and the specular material
// per fragment: interpolated here exactly as prt-bake interpolates a texel's owner triangle at
// the sample's barycentrics (assetTexelSpecular); unused (and attributes 5, 6 constant) without
// a visibility pass.
precision highp float;

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;
layout(location = 2) in vec3 aNormal;
layout(location = 5) in vec4 aSpecular;      // f0 r, g, b; Phong exponent s
layout(location = 6) in float aSpecularF90;  // Schlick's grazing reflectance
layout(location = 7) in vec2 aAtlasUv;

uniform mat4 uViewProjection;
uniform bool uAtlasSpace;

out vec2 vAtlasUv;
out vec3 vAlbedo;
out vec3 vPosition;
out vec3 vNormal;
out vec4 vSpecular;
out float vSpecularF90;
// The depth prepass and the shading pass link this same shader into two programs: invariance
// makes their depths bit-identical, which the shading pass's EQUAL depth test relies on.
invariant gl_Position;

void main() {
  vAtlasUv = aAtlasUv;
  vAlbedo = aAlbedo;
  vPosition = aPosition;
  vNormal = aNormal;
  vSpecular = aSpecular;
  vSpecularF90 = aSpecularF90;
  gl_Position = uAtlasSpace ? vec4(2.0 * aAtlasUv - 1.0, 0.0, 1.0) : uViewProjection * vec4(aPosition, 1.0);
}
