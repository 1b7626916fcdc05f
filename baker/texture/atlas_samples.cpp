#include "baker/texture/atlas_samples.h"

#include <string>

#include "baker/scene/uv_atlas_check.h"
#include "baker/texture/texel_raster.h"

namespace prt::bake {

Status checkAtlases(std::span<const TextureAtlas> atlases, std::size_t triangleCount) {
  if (atlases.empty() || atlases.size() > kMaxAssetAtlases) {
    return Status::error(StatusCode::kInvalidArgument, "the atlas count " + std::to_string(atlases.size()) +
                                                           " is outside 1 … " + std::to_string(kMaxAssetAtlases));
  }
  std::uint64_t next = 0, texels = 0;
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const TextureAtlas& atlas = atlases[a];
    const std::string name = "atlas " + std::to_string(a);
    if (atlas.width < 1 || atlas.width > kMaxAtlasSize || atlas.height < 1 || atlas.height > kMaxAtlasSize) {
      return Status::error(StatusCode::kInvalidArgument, name + " is " + std::to_string(atlas.width) + " × " +
                                                             std::to_string(atlas.height) + " texels, outside 1 … " +
                                                             std::to_string(kMaxAtlasSize));
    }
    if (atlas.firstTriangle != next) {
      return Status::error(StatusCode::kInvalidArgument, name + " starts at triangle " +
                                                             std::to_string(atlas.firstTriangle) + ", expected " +
                                                             std::to_string(next));
    }
    if (atlas.triangleCount == 0) return Status::error(StatusCode::kInvalidArgument, name + " holds no triangles");
    next += atlas.triangleCount;
    texels += std::uint64_t{atlas.width} * atlas.height;
  }
  if (next != triangleCount) {
    return Status::error(StatusCode::kInvalidArgument, "the atlases hold " + std::to_string(next) +
                                                           " triangles, the mesh has " + std::to_string(triangleCount));
  }
  if (texels > kMaxAssetTexels) {
    return Status::error(StatusCode::kInvalidArgument, "the atlases hold " + std::to_string(texels) +
                                                           " texels, more than " + std::to_string(kMaxAssetTexels));
  }
  return Status::ok();
}

Status rasteriseAtlases(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const Rgb> albedo,
                        std::span<const std::uint32_t> indices, std::span<const Uv> uvs,
                        std::span<const TextureAtlas> atlases, AtlasSamples* out) {
  *out = AtlasSamples{};
  if (indices.size() % 3 != 0) {
    return Status::error(StatusCode::kInvalidArgument, "the index count is not a multiple of 3");
  }
  PRT_RETURN_IF_ERROR(checkAtlases(atlases, indices.size() / 3));
  if (albedo.size() != positions.size() || uvs.size() != positions.size()) {
    return Status::error(StatusCode::kSizeMismatch, "the atlas UVs or albedos do not match the positions");
  }
  AtlasSamples r;
  r.firstTexel.push_back(0);
  for (const TextureAtlas& atlas : atlases) r.firstTexel.push_back(r.firstTexel.back() + std::uint64_t{atlas.width} * atlas.height);
  r.sampled.assign(r.firstTexel.back(), 0);
  r.triangleAtlas.resize(indices.size() / 3);
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const TextureAtlas& atlas = atlases[a];
    for (std::uint32_t t = 0; t < atlas.triangleCount; ++t) r.triangleAtlas[atlas.firstTriangle + t] = static_cast<std::uint32_t>(a);
    const auto run = indices.subspan(3 * std::size_t{atlas.firstTriangle}, 3 * std::size_t{atlas.triangleCount});
    TexelRaster raster;
    if (Status s = rasteriseTexels(positions, normals, run, uvs, static_cast<int>(atlas.width),
                                   static_cast<int>(atlas.height), &raster);
        !s.isOk()) {
      return Status::error(s.code(), "atlas " + std::to_string(a) + ": " + s.message());
    }
    r.normalFallbacks += raster.normalFallbacks;
    for (const TexelSample& s : raster.samples) {
      AtlasTexel t;
      t.atlas = static_cast<std::uint32_t>(a);
      t.x = static_cast<int>(s.texel % atlas.width);
      t.y = static_cast<int>(s.texel / atlas.width);
      t.index = r.firstTexel[a] + s.texel;
      t.triangle = atlas.firstTriangle + s.triangle;
      t.bary = s.bary;
      t.position = s.position;
      t.normal = s.normal;
      Rgb rho{0, 0, 0};
      for (int c = 0; c < 3; ++c) rho = rho + albedo[indices[3 * std::size_t{t.triangle} + c]] * s.bary[c];
      t.albedo = rho;
      r.sampled[t.index] = 1;
      r.texels.push_back(t);
    }
  }
  *out = std::move(r);
  return Status::ok();
}

}  // namespace prt::bake
