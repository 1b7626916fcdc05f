// Packs a texel transfer pass (transfer textures, PRTT; docs/web-client.md "Transfer
// textures") into half-float texture arrays, one per atlas, for shaders/texel_prt.frag: per
// channel ceil(order^2 / 4) RGBA layers, coefficients 4g .. 4g+3 in layer g of the channel,
// the same coefficient order and zero padding as the vertex packing (transfer_texture.h).
// GL-free, so the packing is tested under Node (tests/web/texel_core_node_test.mjs).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/asset.h"
#include "prt/status.h"

namespace prt::web {

// One atlas's RGBA16F TEXTURE_2D_ARRAY image: layer-major, then rows, then texels, 4 halves
// per texel: halves[((layer * height + y) * width + x) * 4 + lane]. Row y is the asset's texel
// row y (v in [y, y+1) / height, v down from the atlas's top-left in the glTF convention); GL
// puts the first row it is given at t = 0, so the shader samples at t = v, with no flip.
struct TexelAtlasTexture {
  int width = 0, height = 0, layers = 0;
  std::vector<std::uint16_t> halves;
};

struct TexelTextures {
  int channels = 0;          // 1 or 3
  int order = 0;             // bands held (order^2 coefficients per channel)
  int layersPerChannel = 0;  // ceil(order^2 / 4); layer of (channel c, group g) = c * layersPerChannel + g
  std::vector<TexelAtlasTexture> atlases;
};

// Packs `pass` (a texel pass holding `order` bands: texelCount x channels x order^2 floats,
// texels atlas after atlas, y * width + x within one) over `atlases` into *out. Errors, with
// *out untouched: a pass that is not per texel or whose size disagrees with the atlases, an
// order outside 1..16, an atlas side over `maxSize` (the device's MAX_TEXTURE_SIZE) or more
// layers than `maxLayers` (MAX_ARRAY_TEXTURE_LAYERS), each message naming both numbers.
Status packTexelTransfer(const TransferPass& pass, int order, std::span<const TextureAtlas> atlases, int maxSize, int maxLayers,
                         TexelTextures* out);

// Decodes the asset's texel normals (2 octahedral snorm16 codes per texel, texels atlas after
// atlas: BakedAsset::texelNormals) into one RGBA16F TEXTURE_2D image per atlas (layers 1, rows
// as above): unit x, y, z and w = 1 per covered texel, all four 0 where `coverage` says empty,
// so texel_prt.frag can tell a bilinear read that reached no normal. Decoded here rather than
// uploaded as codes: WebGL2 has no filterable 16-bit snorm format without EXT_texture_norm16,
// and bilinear filtering of octahedral codes is wrong across the fold. Errors, *out untouched:
// counts that disagree with the atlases or the coverage, an atlas side over `maxSize`.
Status packTexelNormals(std::span<const std::int16_t> codes, std::span<const std::uint8_t> coverage,
                        std::span<const TextureAtlas> atlases, int maxSize, std::vector<TexelAtlasTexture>* out);

}  // namespace prt::web
