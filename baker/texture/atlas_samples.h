// The surface samples of a set of texture atlases (a texture set, PRTT §4.3): every atlas's
// run of triangles rasterised into its own texture (texel_raster.h), with the samples'
// texels numbered across all atlases, atlas after atlas (BakedAsset::texelCoverage's order).
// Shared by the texel bake and by tools that re-derive an asset's samples.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/asset.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

struct AtlasTexel {
  std::uint32_t atlas = 0;      // index into the atlases
  int x = 0, y = 0;             // texel within the atlas
  std::uint64_t index = 0;      // across all atlases: the atlas's first texel + y × width + x
  std::uint32_t triangle = 0;   // the owner, a triangle index of the whole mesh
  std::array<float, 3> bary{};  // weights of the owner's corners in index order
  Vec3 position, normal;        // world space, on the owner; unit normal
  Rgb albedo;                   // the owner's vertex albedos at bary
};

struct AtlasSamples {
  std::vector<AtlasTexel> texels;       // one per sampled texel, in ascending index
  std::vector<std::uint64_t> firstTexel;  // per atlas, plus one: the total texel count
  std::vector<std::uint8_t> sampled;    // per texel of all atlases: 1 where a sample exists, else 0
  std::vector<std::uint32_t> triangleAtlas;  // per triangle, the atlas holding it
  std::size_t normalFallbacks = 0;      // texel_raster.h's count, summed over the atlases
};

// Ok when `atlases` can hold `triangleCount` triangles: 1..kMaxAssetAtlases atlases, sides
// 1..kMaxAtlasSize, at most kMaxAssetTexels texels together, triangle runs contiguous in
// order covering [0, triangleCount) exactly once, none empty. kInvalidArgument naming the atlas.
Status checkAtlases(std::span<const TextureAtlas> atlases, std::size_t triangleCount);

// Rasterises every atlas of `atlases` (checkAtlases) over the mesh (positions, normals,
// albedo and uvs one per vertex; indices 3 per triangle) into *out. Errors: checkAtlases's,
// kSizeMismatch (albedo or uvs of another length), the rasteriser's (texel_raster.h), each
// prefixed with the atlas; *out is then empty. Safe on untrusted input; deterministic.
Status rasteriseAtlases(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const Rgb> albedo,
                        std::span<const std::uint32_t> indices, std::span<const Uv> uvs,
                        std::span<const TextureAtlas> atlases, AtlasSamples* out);

}  // namespace prt::bake
