// Packs a transfer pass into RGBA32F texels for the vertex shader (shaders/prt.vert):
// per vertex, per channel, the order^2 coefficients padded to whole texels. GL-free, so
// the packing is tested under Node like the rest of the shared code.
#pragma once

#include <string>
#include <vector>

#include "client_limits.h"
#include "prt/asset.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::web {

// Guaranteed by every WebGL2 implementation (MAX_TEXTURE_SIZE >= 2048). A power of two: the
// shaders split a texel index into (x, y) with a mask and a shift (uTextureMask,
// uTextureShift), since an integer division per fetch is what a CPU rasteriser pays most for.
inline constexpr int kTransferTextureShift = 11;
inline constexpr int kTransferTextureWidth = 1 << kTransferTextureShift;

struct TransferTexture {
  int width = 0, height = 0;   // texels
  int channels = 0;            // 1 or 3
  int texelsPerChannel = 0;    // ceil(order^2 / 4)
  std::vector<float> texels;   // width * height * 4 floats
};

// Rows of a kTransferTextureWidth-wide texture holding `texels` (at least 1) into *rows; an
// error naming `what`, the texels needed and what one texture holds when over maxHeight
// (the device's MAX_TEXTURE_SIZE).
Status textureRowsFor(std::size_t texels, int maxHeight, const std::string& what, int* rows);

// Texels of one channel at `order`: ceil(order^2 / 4).
inline int texelsForOrder(int order) { return (order * order + 3) / 4; }

// Packs `pass` of an asset with `vertexCount` vertices at SH order `order` into a texture
// kTransferTextureWidth wide and at most `maxHeight` rows (the device's MAX_TEXTURE_SIZE).
// Errors, naming both numbers, when the scene does not fit in one texture.
Status packTransfer(const TransferPass& pass, int order, std::size_t vertexCount, int maxHeight, TransferTexture* out);

// Packs lighting (order^2 RGB coefficients) into kLightingTexelsPerChannel vec4 per channel
// in the same layout, keeping only the first `displayOrder`^2 coefficients (at most
// kMaxClientOrder bands; the rest zero): the uniforms uLightR/G/B. out must hold
// kPackedLightingFloats floats.
void packLighting(const std::vector<Rgb>& coeffs, int displayOrder, float* out);

}  // namespace prt::web
