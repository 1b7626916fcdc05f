// Packs a radiance transfer texture (prt/rtt.h; docs/bi-scale.md) for per-fragment lookups
// in WebGL2, and emulates the lookup the fragment shader makes, on the CPU. GL-free, tested
// under Node against prt::rttLookup.
//
// Layout: a 2D texture array of RGBA16F layers, (S V) x (S V) texels each (S spatial, V view
// samples a side): texel (x V + a, y V + b) of layer c T + t holds coefficients 4t .. 4t+3
// (zero-padded) of channel c at spatial sample (x, y) and view sample (a, b), T = ceil(n^2/4).
// Each spatial sample is a V x V block of view samples, so the GPU's bilinear filter
// interpolates across views (the paper's "8 x 8 view blocks") when the lookup clamps its
// coordinate to the block's outermost sample centres; the spatial sample is chosen nearest.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/rtt.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::web {

struct RttTextures {
  int order = 0, channels = 0, spatial = 0, views = 0;
  int layersPerChannel = 0;  // T
  int size = 0;              // S V: width and height of a layer
  std::vector<std::uint16_t> halves;  // [layer][row][column][4], binary16, ready for texImage3D
};

// Packs `rtt` for a device whose textures hold `maxTextureSize` texels a side and
// `maxLayers` layers (WebGL2 guarantees 2048 and 256). kInvalidArgument names what does not
// fit; kNotFinite a coefficient beyond binary16's range. Safe on a decoded (checked) RTT.
Status packRtt(const Rtt& rtt, int maxTextureSize, int maxLayers, RttTextures* out);

// The fragment shader's lookup on the CPU: the spatial sample nearest (u, v) (modulo 1), the
// view coordinates of `view` (tangent frame) or the centre view when !viewDependent, clamped
// to the block's outer sample centres, filtered bilinearly from the half-float texels as the
// GPU's LINEAR filter does (exact weights). out: channels * order^2 floats.
void rttTextureLookupCpu(const RttTextures& t, float u, float v, Vec3 view, bool viewDependent, float* out);

}  // namespace prt::web
