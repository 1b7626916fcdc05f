#version 300 es
// Bi-scale shading, the corners (docs/bi-scale.md, "The client"): de-indexed triangles, each
// corner carrying its triangle's three vertex ids, so the fragment shader can fetch the three
// vertices' rotated transferred radiance and weight it by the barycentrics (WebGL2 guarantees
// 15 varying vec4s, fewer than 25 RGB coefficients: the 75 numbers are fetched, not
// interpolated).
precision highp float;
precision highp int;

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aTangent;
layout(location = 3) in vec2 aPatchUv;
layout(location = 4) in uvec3 aVertices;
layout(location = 5) in vec2 aAtlasUv;  // the synthesised id map's atlas (0 when parametric)
layout(location = 6) in uint aPlacement;  // a per-triangle id map's entry (65535: none)

uniform mat4 uViewProjection;

out vec3 vPosition;
out vec3 vNormal;
out vec3 vTangent;
out vec2 vPatchUv;
out vec2 vAtlasUv;
out vec3 vBarycentric;
flat out uvec3 vVertices;
flat out uint vPlacement;

void main() {
  int corner = gl_VertexID % 3;
  vBarycentric = vec3(corner == 0 ? 1.0 : 0.0, corner == 1 ? 1.0 : 0.0, corner == 2 ? 1.0 : 0.0);
  vVertices = aVertices;
  vPlacement = aPlacement;
  vPosition = aPosition;
  vNormal = aNormal;
  vTangent = aTangent;
  vPatchUv = aPatchUv;
  vAtlasUv = aAtlasUv;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
