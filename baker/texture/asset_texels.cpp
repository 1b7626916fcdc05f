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

Status assetTexelSpecular(const BakedAsset& asset, std::span<const AtlasTexel> texels, std::vector<SpecularMaterial>* out) {
  out->clear();
  if (asset.specular.empty() || asset.specular.size() != asset.positions.size()) {
    return Status::error(StatusCode::kInvalidArgument, "the asset has no specular materials (one per vertex) to shade glossy texels with");
  }
  std::vector<SpecularMaterial> materials(texels.size());
  for (std::size_t t = 0; t < texels.size(); ++t) {
    const AtlasTexel& s = texels[t];
    if (std::size_t{s.triangle} >= asset.indices.size() / 3) {
      return Status::error(StatusCode::kCorrupt, "texel " + std::to_string(s.index) + "'s triangle " +
                                                     std::to_string(s.triangle) + " is not one of the asset's");
    }
    SpecularMaterial m{{0, 0, 0}, 0.0f, 0.0f};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = asset.indices[3 * std::size_t{s.triangle} + static_cast<std::size_t>(k)];
      if (v >= asset.specular.size()) return Status::error(StatusCode::kCorrupt, "index " + std::to_string(v) + " out of range");
      const SpecularMaterial& c = asset.specular[v];
      const float w = s.bary[static_cast<std::size_t>(k)];
      m.f0 = m.f0 + c.f0 * w;
      m.f90 += w * c.f90;
      m.exponent += w * c.exponent;
    }
    materials[t] = m;
  }
  *out = std::move(materials);
  return Status::ok();
}

}  // namespace prt::bake
