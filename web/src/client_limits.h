// The client's fixed limits, GL-free (shared by the renderer, the lighting and the Node
// tests' core module). The lighting every shading program reads holds at most
// kMaxClientOrder bands: per channel kMaxClientOrder^2 coefficients, packed 4 to a vec4
// (the `Lighting` block and the uLightR/G/B arrays of shaders/*.vert, *.frag, which spell
// out its 16 vec4 per channel; the static_assert below keeps them in step). Exported to JS
// by embind (core_bindings.cpp) as Module.kMaxClientOrder.
#pragma once

namespace prt::web {

// Bands of SH the client renders with (assets may be baked higher; the first bands are used).
inline constexpr int kMaxClientOrder = 8;
// Coefficients per channel at kMaxClientOrder (64).
inline constexpr int kMaxClientCoeffs = kMaxClientOrder * kMaxClientOrder;
// The packLighting layout: RGB channels one after another, kMaxClientCoeffs each (192 floats).
inline constexpr int kPackedLightingFloats = 3 * kMaxClientCoeffs;
// vec4 texels per channel in that layout (16): the width of the cube-SH texture.
inline constexpr int kLightingTexelsPerChannel = kMaxClientCoeffs / 4;

static_assert(kMaxClientCoeffs % 4 == 0, "the lighting is packed 4 coefficients to a vec4");
static_assert(kLightingTexelsPerChannel == 16, "shaders/*.vert, *.frag declare uLightR/G/B[16] and uEnvironment[48]");

}  // namespace prt::web
