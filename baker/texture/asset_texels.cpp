#include "baker/texture/asset_texels.h"

#include <string>

namespace prt::bake {

Status assetTexelSamples(const BakedAsset& asset, std::vector<AtlasTexel>* out) {
  out->clear();
  if (asset.atlases.empty()) return Status::error(StatusCode::kInvalidArgument, "the asset has no transfer-texture atlases");
  std::vector<Uv> uv(asset.atlasUv.size() / 2);
  for (std::size_t v = 0; v < uv.size(); ++v) uv[v] = {asset.atlasUv[2 * v], asset.atlasUv[2 * v + 1]};
  AtlasSamples samples;
  PRT_RETURN_IF_ERROR(rasteriseAtlases(asset.positions, asset.normals, asset.albedo, asset.indices, uv, asset.atlases, &samples));
  if (samples.sampled.size() != asset.texelCoverage.size()) {
    return Status::error(StatusCode::kCorrupt, "the asset's coverage does not match its atlases");
  }
  for (std::size_t a = 0; a < asset.atlases.size(); ++a) {
    const std::uint32_t width = asset.atlases[a].width;
    for (std::uint64_t t = samples.firstTexel[a]; t < samples.firstTexel[a + 1]; ++t) {
      const bool sampled = samples.sampled[t] != 0;
      if (sampled == (asset.texelCoverage[t] == static_cast<std::uint8_t>(TexelCoverage::kSampled))) continue;
      const std::uint64_t local = t - samples.firstTexel[a];
      return Status::error(StatusCode::kCorrupt, "atlas " + std::to_string(a) + " texel (" +
                                                     std::to_string(local % width) + ", " + std::to_string(local / width) +
                                                     ") is " + (sampled ? "" : "not ") +
                                                     "reached by its triangles but marked " +
                                                     (sampled ? "unsampled" : "sampled") + " in the asset's coverage");
    }
  }
  *out = std::move(samples.texels);
  return Status::ok();
}

}  // namespace prt::bake
