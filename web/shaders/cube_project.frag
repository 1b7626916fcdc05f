#version 300 es
// Light-cube SH projection, pass 1 (docs/web-client.md): the fragment at (row, face *
// groups + group) sums one row of one face of the cube atlas times that row's SH weights
// (basis x exact texel solid angle, 4 coefficients of group `group` per weight texel). Each
// cube texel is fetched once per group; R, G and B go to three targets (layers of one
// array). Only the face's rectangle uRects[face] (texels any emitter can cover, from the
// CPU's bounding spheres) is read: the rest of the cube is black, and a loop that no lane
// of a 2x2 quad runs costs nothing, where a branch inside the loop would still cost the
// fetches on SIMD software rasterisers.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;

uniform sampler2D uCube;          // 3 size x 2 size atlas, face f at ((f % 3) size, (f / 3) size)
uniform sampler2DArray uWeights;  // same atlas layout, layer = coefficient group
uniform int uSize;
uniform int uGroups;
uniform ivec4 uRects[6];  // per face: first column, first row, last column, last row (inclusive)

layout(location = 0) out vec4 outR;
layout(location = 1) out vec4 outG;
layout(location = 2) out vec4 outB;

void main() {
  int row = int(gl_FragCoord.x);
  int slot = int(gl_FragCoord.y);
  int face = slot / uGroups;
  int group = slot - uGroups * face;
  ivec2 origin = ivec2((face % 3) * uSize, (face / 3) * uSize + row);
  ivec4 rect = uRects[face];
  int first = row >= rect.y && row <= rect.w ? rect.x : 0;
  int last = row >= rect.y && row <= rect.w ? rect.z : -1;
  vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
  for (int i = first; i <= last; ++i) {
    ivec2 p = ivec2(origin.x + i, origin.y);
    vec3 c = texelFetch(uCube, p, 0).rgb;
    vec4 w = texelFetch(uWeights, ivec3(p, group), 0);
    r += c.r * w;
    g += c.g * w;
    b += c.b * w;
  }
  outR = r;
  outG = g;
  outB = b;
}
