#version 300 es
// Bi-scale shading per fragment (Sloan et al. 2003, eq. 4; docs/bi-scale.md, "The client"):
//   L_c = B_c(q, w) . (D M L_c),
// B the RTT looked up at the patch position q = fract(patch uv) (nearest spatial sample) and
// the view w in the tangent frame (bilinear across the 8 x 8 view block, by the texture unit),
// dotted with the three vertices' rotated transferred radiance weighted by the barycentrics
// (the same as interpolating it: the dot product is linear). prt::biScaleExitRadiance is the
// reference; rttTextureLookupCpu emulates the lookup. BANDS and ROW_TEXELS are defined by the
// renderer: the sum runs over texels t < ceil(BANDS^2 / 4), and both vectors are 0 beyond
// BANDS^2 (the rotation step writes 0 there; the RTT's padding is 0). SYNTHESISED: q from the
// synthesised id map (docs/bi-scale.md): the placement of the id map texel under the fragment
// (nearest; SYNTHESISED 1) or of its triangle (SYNTHESISED 2), q = fract(((p - origin) . axisU, (p - origin) . axisV)) as prt::patchCoordinates.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;

in vec3 vPosition;
in vec3 vNormal;
in vec3 vTangent;
in vec2 vPatchUv;
in vec2 vAtlasUv;
in vec3 vBarycentric;
flat in uvec3 vVertices;
flat in uint vPlacement;

uniform sampler2D uRotated;       // RGBA32F: D_v T_vc, texel (c * uVertices + v) * ROW_TEXELS + t
uniform highp sampler2DArray uRtt;  // RGBA16F layers (web/src/rtt_texture.h), LINEAR
uniform int uTextureMask;
uniform int uTextureShift;
uniform int uVertices;
uniform int uRttSpatial;          // S
uniform int uRttViews;            // V
uniform int uRttLayersPerChannel; // ceil(n^2 / 4) of the RTT's order n
uniform int uRttChannels;         // 1 or 3
uniform int uViewDependent;       // 0: the centre view (the paper's Figure 6c)
uniform vec3 uEye;
#ifdef SYNTHESISED
uniform highp usampler2D uIdMap;  // R16UI: a placement index per atlas texel (65535: none)
uniform ivec2 uIdMapSize;
uniform sampler2D uPlacements;    // RGBA32F: 3 texels a placement, origin, axisU, axisV
#endif
uniform float uExposure;

out vec4 fragColor;

#define TEXELS ((BANDS * BANDS + 3) / 4)
const float kPi = 3.14159265358979;

vec3 acesFit(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 linearToSrgb(vec3 c) { return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c)); }

vec4 rotatedTexel(int i) { return texelFetch(uRotated, ivec2(i & uTextureMask, i >> uTextureShift), 0); }

// View-sample coordinates (a, b) in [0, V) of unit w (z >= 0): the inverse of the equal-area
// hemisphere map and Shirley & Chiu's concentric map, as prt::rttViewCoordinates.
vec2 viewCoordinates(vec3 w, float views) {
  float z = clamp(w.z, 0.0, 1.0);
  float k = sqrt(1.0 + z);
  vec2 d = k > 0.0 ? w.xy / k : vec2(0.0);
  float r = length(d);
  float phi = atan(d.y, d.x);
  if (phi < -kPi / 4.0) phi += 2.0 * kPi;
  vec2 s;
  if (phi < kPi / 4.0) {
    s = vec2(r, phi * r / (kPi / 4.0));
  } else if (phi < 3.0 * kPi / 4.0) {
    s = vec2(-(phi - kPi / 2.0) * r / (kPi / 4.0), r);
  } else if (phi < 5.0 * kPi / 4.0) {
    s = vec2(-r, -(phi - kPi) * r / (kPi / 4.0));
  } else {
    s = vec2((phi - 3.0 * kPi / 2.0) * r / (kPi / 4.0), -r);
  }
  return clamp((s + 1.0) * 0.5 * views, 0.0, views);
}

// sum_j lambda_j (B_c . T_vj,c) for one channel: row0..row2 the three vertices' rows of the
// rotated T (texel indices), layer the channel's first RTT layer, uv the lookup. Written out
// with constant indices and compile-time tests (t < TEXELS) and no local arrays: SwiftShader
// does not unroll loops, and a loop-indexed array becomes per-lane memory traffic
// (glossy_transfer.vert measured it at about twice the time).
#define TERM(t) if ((t) < TEXELS) { b = texture(uRtt, vec3(uv, float(layer + (t)))); s0 += dot(rotatedTexel(row0 + (t)), b); s1 += dot(rotatedTexel(row1 + (t)), b); s2 += dot(rotatedTexel(row2 + (t)), b); }
float channelRadiance(int row0, int row1, int row2, int layer, vec2 uv) {
  vec4 b;
  float s0 = 0.0, s1 = 0.0, s2 = 0.0;
  TERM(0) TERM(1) TERM(2) TERM(3) TERM(4) TERM(5) TERM(6) TERM(7)
  TERM(8) TERM(9) TERM(10) TERM(11) TERM(12) TERM(13) TERM(14) TERM(15)
  return vBarycentric.x * s0 + vBarycentric.y * s1 + vBarycentric.z * s2;
}

void main() {
  vec3 n = normalize(vNormal);
  vec3 t = vTangent - n * dot(vTangent, n);
  t = length(t) > 0.0 ? normalize(t) : vec3(0.0);
  vec3 bitangent = cross(n, t);
  vec3 toEye = normalize(uEye - vPosition);
  vec3 w = vec3(dot(toEye, t), dot(toEye, bitangent), dot(toEye, n));
  float S = float(uRttSpatial), V = float(uRttViews);
#ifdef SYNTHESISED
#if SYNTHESISED == 2
  uint placement = vPlacement;  // per triangle
#else
  ivec2 idTexel = clamp(ivec2(floor(vAtlasUv * vec2(uIdMapSize))), ivec2(0), uIdMapSize - 1);
  uint placement = texelFetch(uIdMap, idTexel, 0).r;
#endif
  vec2 q = vec2(0.0);
  if (placement != 65535u) {
    int k = 3 * int(placement);
    vec3 origin = texelFetch(uPlacements, ivec2(k & uTextureMask, k >> uTextureShift), 0).xyz;
    vec3 axisU = texelFetch(uPlacements, ivec2((k + 1) & uTextureMask, (k + 1) >> uTextureShift), 0).xyz;
    vec3 axisV = texelFetch(uPlacements, ivec2((k + 2) & uTextureMask, (k + 2) >> uTextureShift), 0).xyz;
    vec3 d = vPosition - origin;
    q = fract(vec2(dot(d, axisU), dot(d, axisV)));
  }
#else
  vec2 q = fract(vPatchUv);
#endif
  vec2 cell = min(floor(q * S), vec2(S - 1.0));
  vec2 ab = uViewDependent == 1 ? viewCoordinates(w, V) : vec2(0.5 * V);
  // Inside the spatial sample's V x V block, clamped to its outer sample centres, so LINEAR
  // filtering blends views and never two spatial samples.
  vec2 texel = cell * V + clamp(ab, vec2(0.5), vec2(V - 0.5));
  vec2 uv = texel / (S * V);
  // Rows of channel c of vertex v: (c V + v) ROW_TEXELS; a grey RTT serves all three channels.
  ivec3 rows = ivec3(vVertices) * ROW_TEXELS;
  int channelRows = uVertices * ROW_TEXELS;
  int rgb = uRttChannels == 3 ? uRttLayersPerChannel : 0;
  vec3 radiance = vec3(channelRadiance(rows.x, rows.y, rows.z, 0, uv),
                       channelRadiance(rows.x + channelRows, rows.y + channelRows, rows.z + channelRows, rgb, uv),
                       channelRadiance(rows.x + 2 * channelRows, rows.y + 2 * channelRows, rows.z + 2 * channelRows, 2 * rgb, uv));
  fragColor = vec4(linearToSrgb(acesFit(max(radiance, vec3(0.0)) * uExposure)), 1.0);
}
