// Transfer textures (PRTT; docs/transfer-textures.md): the diffuse passes of transfer_bake.h
// baked at texel samples of a UV atlas instead of at vertices.
//
// Every atlas's triangles are rasterised conservatively (baker/texture/texel_raster.h); each
// used texel's sample (position, interpolated normal, albedo interpolated from the owner
// triangle's vertices) receives the same direct pass as a vertex does, with the cosine about
// the normal map's normal where the material has one (PRTT §6.2): unshadowed U_i,
// shadowed S_i, bounce 0 = rho S. Bounce b gathers the previous bounce at each front-face hit
// point's own texel: the hit's atlas UV (the hit triangle's corner UVs at its barycentrics),
// read bilinearly from that triangle's atlas after the previous bounce was dilated into the
// gutters (PRTT §4.2's bounce textures), instead of interpolating the hit triangle's vertices.
// The result is dilated `dilation` texels into the gutters for the client's bilinear filter,
// and the gutter texels along cuts between charts are stitched to the surface across the cut.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

struct TexelBakeOptions {
  BakeOptions transfer;  // order, samples, sampling, seed, bounces, threads, lighting; glossy must be false
  int dilation = 3;      // gutter texels filled after each bounce and at the end (PRTT Alg. 1 uses 3)
  // Gutter texels along a cut between two charts read the surface across the cut
  // (baker/texture/texel_seams.h), so bilinear filtering shows no seam; needs dilation >= 1.
  bool stitchSeams = true;
  // > 0: also bake each texel's visibility vector at this order (2..kMaxShOrder; 2n - 1 for
  // lighting of order n makes TPFL glossy exact, docs/transfer-textures.md, "Glossy by the
  // triple product"). Distant lighting only.
  int visibilityOrder = 0;
};

struct TexelBakeResult {
  int order = 0;
  std::uint64_t texels = 0;              // all atlases' texels together (assetTexelCount)
  std::uint64_t sampledTexels = 0;       // texels holding a surface sample
  std::vector<std::uint8_t> coverage;    // per texel, TexelCoverage values, atlases in order
  std::vector<float> unshadowed;         // [texel][coefficient], dilated
  std::vector<float> shadowed;           // [texel][coefficient], dilated
  std::vector<float> interreflected;     // [texel][channel][coefficient], dilated; empty without interreflection
  int visibilityOrder = 0;
  std::vector<float> visibility;         // [texel][coefficient] at visibilityOrder, dilated; empty if not asked for
  // The shading normal per texel as 2 octahedral snorm16 codes (prt/octahedral_normal.h): the
  // normal-mapped one at sampled texels, dilated into the gutters, (0, 0) at empty texels. Empty
  // unless some sampled texel is normal-mapped (normalMappedTexels > 0): without a normal map
  // the interpolated vertex normal is the shading normal, and the client has it already.
  std::vector<std::int16_t> normals;
  int bounces = 0;
  std::vector<double> bounceEnergy;      // per bounce: sum over sampled texels of texel area x DC, all channels
  std::vector<PassStats> passes;
  std::size_t normalFallbacks = 0;       // texel_raster.h's count, summed over atlases
  // Bounce hits whose atlas UV found no filled texel to read (a triangle with no UV area,
  // which the rasteriser skips): they gather nothing. 0 on a valid atlas with dilation >= 1.
  std::uint64_t unmappedHits = 0;
  std::size_t texelsOutsideLight = 0;    // local lighting: sampled texels outside the sphere S
  std::size_t seamTexels = 0;            // gutter texels stitched across a chart cut
  std::size_t normalMappedTexels = 0;    // sampled texels whose shading normal came from a normal map
};

// Bakes the texel passes of `scene` over `atlasUv` (one per vertex, each atlas's triangles
// laid out inside [0, 1]) and `atlases` (in triangle order, covering every triangle once, as
// BakedAsset::atlases). Deterministic for a given input whatever transfer.threads. Progress
// reports texels as its `done`/`total`. Errors: the rasteriser's and the bake's (options,
// sizes), kInvalidArgument for glossy options or atlases not covering the triangles.
Status bakeTexelTransfer(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                         const TexelBakeOptions& options, TexelBakeResult* out);

}  // namespace prt::bake
