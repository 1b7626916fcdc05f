// Seam stitching for transfer textures (docs/transfer-textures.md, "Seams"): where one
// surface is cut into two charts, the gutter texels along each side of the cut take the
// transfer of the surface across the cut, read from the other chart, so that the client's
// bilinear filter reaches the same value from both sides and the cut shows no line. Gutter
// dilation alone (texel_dilate.h) repeats each chart's edge instead, and the two sides then
// differ by about two texels' worth of the transfer's gradient.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/texture/atlas_samples.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

// 1 - cos of the largest angle between the two sides' vertex normals at a shared endpoint for
// which the cut still counts as smooth: 1e-4 is 0.8 degrees, wide enough for normals stored
// quantised (KHR_mesh_quantization's 8-bit normals round to about 0.45 degrees) and far below
// any modelled crease.
inline constexpr double kSeamCreaseTolerance = 1e-4;

struct SeamTexel {
  std::uint64_t texel = 0;  // an unsampled texel beside a chart edge that continues in another chart
  std::uint32_t atlas = 0;  // the atlas holding the triangle across the cut
  Uv uv;                    // where the texel's centre lands on that triangle, in its atlas
};

// The seam texels of `samples` (rasteriseAtlases of the same mesh and atlases): every unsampled
// texel with a sampled 4-neighbour whose centre, carried across the owner triangle's edge (the
// edge's 3D endpoints shared by a triangle with other UVs there), lands on the neighbour: the
// distance past the edge is kept and turned about the edge into the neighbour's plane.
// Texels past a corner or a boundary edge (no neighbour) are not seam texels, nor are texels
// beside a crease: where the vertex normals (one per position, unit) of the two sides differ
// at either shared endpoint by more than kSeamCreaseTolerance (1 - cos), the shading is
// discontinuous across the edge by construction (a cube's edge), and carrying the other
// side's transfer over would bleed it into this side. Deterministic.
// Errors: kResourceExhausted (out of memory).
Status findSeamTexels(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const std::uint32_t> indices,
                      std::span<const Uv> uvs, std::span<const TextureAtlas> atlases, const AtlasSamples& samples,
                      std::vector<SeamTexel>* out);

// Overwrites each seam texel of `texture` (`stride` floats per texel, every atlas, numbered as
// AtlasSamples) with the bilinear read at its uv (bilinearTaps over `filled`); every read is
// taken before any write, so the result does not depend on the order of `seams`.
void stitchSeams(std::span<const SeamTexel> seams, std::span<const TextureAtlas> atlases,
                 std::span<const std::uint64_t> firstTexel, std::span<const std::uint8_t> filled,
                 std::span<float> texture, std::size_t stride);

}  // namespace prt::bake
