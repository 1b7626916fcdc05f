#include "texel_texture.h"

#include <algorithm>
#include <string>

#include "prt/half_float.h"
#include "prt/octahedral_normal.h"
#include "transfer_texture.h"

namespace prt::web {
namespace {

// Every atlas non-empty and within the device's MAX_TEXTURE_SIZE; *texels gets their sum.
Status checkAtlasSizes(std::span<const TextureAtlas> atlases, int maxSize, std::size_t* texels) {
  *texels = 0;
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const TextureAtlas& atlas = atlases[a];
    if (atlas.width < 1 || atlas.height < 1) return Status::error(StatusCode::kInvalidArgument, "atlas " + std::to_string(a) + " is empty");
    if (atlas.width > static_cast<std::uint32_t>(maxSize) || atlas.height > static_cast<std::uint32_t>(maxSize)) {
      return Status::error(StatusCode::kInvalidArgument, "atlas " + std::to_string(a) + " is " + std::to_string(atlas.width) + "x" +
                                                             std::to_string(atlas.height) + " texels; this device's MAX_TEXTURE_SIZE is " +
                                                             std::to_string(maxSize));
    }
    *texels += static_cast<std::size_t>(atlas.width) * atlas.height;
  }
  return Status::ok();
}

}  // namespace

Status packTexelTransfer(const TransferPass& pass, int order, std::span<const TextureAtlas> atlases, int maxSize, int maxLayers,
                         TexelTextures* out) {
  if (pass.domain != TransferDomain::kTexel) {
    return Status::error(StatusCode::kInvalidArgument, "packTexelTransfer: the pass is not a texel pass");
  }
  if (pass.channels != 1 && pass.channels != 3) {
    return Status::error(StatusCode::kInvalidArgument, "texel pass has " + std::to_string(pass.channels) + " channels, not 1 or 3");
  }
  if (order < 1 || order > 16) return Status::error(StatusCode::kInvalidArgument, "texel pass order " + std::to_string(order) + " is not 1..16");
  if (atlases.empty()) return Status::error(StatusCode::kInvalidArgument, "texel pass without atlases");
  const int perChannel = texelsForOrder(order);
  const int layers = perChannel * pass.channels;
  if (layers > maxLayers) {
    return Status::error(StatusCode::kInvalidArgument,
                         "the texel pass needs " + std::to_string(layers) + " texture layers (" + std::to_string(pass.channels) +
                             " channels x " + std::to_string(perChannel) + " per channel at order " + std::to_string(order) +
                             "); this device's MAX_ARRAY_TEXTURE_LAYERS is " + std::to_string(maxLayers));
  }
  std::size_t texels = 0;
  if (Status s = checkAtlasSizes(atlases, maxSize, &texels); !s.isOk()) return s;
  const std::size_t n2 = static_cast<std::size_t>(order) * static_cast<std::size_t>(order);
  const std::size_t perTexel = n2 * static_cast<std::size_t>(pass.channels);
  if (pass.coeffs.size() != texels * perTexel) {
    return Status::error(StatusCode::kSizeMismatch, "texel pass holds " + std::to_string(pass.coeffs.size()) + " floats; " +
                                                        std::to_string(texels) + " texels at order " + std::to_string(order) +
                                                        " need " + std::to_string(texels * perTexel));
  }
  TexelTextures packed;
  packed.channels = pass.channels;
  packed.order = order;
  packed.layersPerChannel = perChannel;
  packed.atlases.resize(atlases.size());
  std::size_t first = 0;  // the atlas's first texel in the pass
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const std::size_t w = atlases[a].width, h = atlases[a].height, layerTexels = w * h;
    TexelAtlasTexture& t = packed.atlases[a];
    t.width = static_cast<int>(w);
    t.height = static_cast<int>(h);
    t.layers = layers;
    t.halves.assign(layerTexels * static_cast<std::size_t>(layers) * 4, 0);  // the padding lanes stay zero
    for (std::size_t texel = 0; texel < layerTexels; ++texel) {
      const float* src = &pass.coeffs[(first + texel) * perTexel];
      for (int c = 0; c < pass.channels; ++c) {
        for (std::size_t i = 0; i < n2; ++i) {
          const std::size_t layer = static_cast<std::size_t>(c * perChannel) + i / 4;
          t.halves[(layer * layerTexels + texel) * 4 + i % 4] = floatToHalf(src[static_cast<std::size_t>(c) * n2 + i]);
        }
      }
    }
    first += layerTexels;
  }
  *out = std::move(packed);
  return Status::ok();
}

Status packTexelNormals(std::span<const std::int16_t> codes, std::span<const std::uint8_t> coverage,
                        std::span<const TextureAtlas> atlases, int maxSize, std::vector<TexelAtlasTexture>* out) {
  std::size_t texels = 0;
  if (Status s = checkAtlasSizes(atlases, maxSize, &texels); !s.isOk()) return s;
  if (codes.size() != 2 * texels || coverage.size() != texels) {
    return Status::error(StatusCode::kSizeMismatch, "texel normals: " + std::to_string(codes.size()) + " codes and " +
                                                        std::to_string(coverage.size()) + " coverage values for " +
                                                        std::to_string(texels) + " texels (2 and 1 per texel expected)");
  }
  std::vector<TexelAtlasTexture> packed(atlases.size());
  std::size_t first = 0;
  const std::uint16_t one = floatToHalf(1.0f);
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    TexelAtlasTexture& t = packed[a];
    t.width = static_cast<int>(atlases[a].width);
    t.height = static_cast<int>(atlases[a].height);
    t.layers = 1;
    const std::size_t count = static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
    t.halves.assign(4 * count, 0);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t texel = first + i;
      if (coverage[texel] == static_cast<std::uint8_t>(TexelCoverage::kEmpty)) continue;
      const Vec3 n = decodeOctahedralNormal(codes[2 * texel], codes[2 * texel + 1]);
      const std::uint16_t h[4] = {floatToHalf(n.x), floatToHalf(n.y), floatToHalf(n.z), one};
      std::copy_n(h, 4, &t.halves[4 * i]);
    }
    first += count;
  }
  *out = std::move(packed);
  return Status::ok();
}

}  // namespace prt::web
