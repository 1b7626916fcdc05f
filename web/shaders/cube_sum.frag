#version 300 es
// Light-cube SH projection, pass 2: texel (t, c) of the 16 x 3 cube-SH texture (the
// packLighting layout: channel c, coefficients 4t..4t+3) sums pass 1's 6 x size partial
// sums of group t in channel c (at (row, face * groups + t)). Groups past the order are zero.
precision highp float;
precision highp int;
precision highp sampler2DArray;

uniform sampler2DArray uPartial;  // size x (6 groups), layers R, G, B
uniform int uSize;
uniform int uGroups;

out vec4 fragColor;

void main() {
  int t = int(gl_FragCoord.x);
  int c = int(gl_FragCoord.y);
  vec4 sum = vec4(0.0);
  if (t < uGroups) {
    for (int face = 0; face < 6; ++face) {
      for (int row = 0; row < uSize; ++row) sum += texelFetch(uPartial, ivec3(row, face * uGroups + t, c), 0);
    }
  }
  fragColor = sum;
}
