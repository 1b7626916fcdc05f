// The texel bake (texel_bake.h) split into pieces for a sharded bake (baker/shard,
// docs/scale-out.md), as transfer_range.h splits the vertex bake: the receivers (the atlases'
// rasterised samples, deterministic), the direct pass over one range of receiver blocks, bounce
// 0, the bounce texture (the previous bounce scattered, dilated and seam-stitched), one
// bounce's gather over one range, and the stored textures. bakeTexelTransfer is these pieces
// run in order on one machine, so the pieces run on many machines give its bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/texture/atlas_samples.h"
#include "baker/texture/texel_seams.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/texel_bake.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

// What every piece reads: the receivers of a scene's atlases and what follows from them alone.
struct TexelReceivers {
  AtlasSamples samples;               // receivers = samples.texels, in texel order
  std::vector<SeamTexel> seams;       // options.stitchSeams: gutter texels read across chart cuts
  std::vector<Vec3> positions, normals;
  std::vector<Vec3> shading;          // normal-mapped scenes: the cosine's normal per receiver; else empty
  std::size_t normalMappedTexels = 0;
  std::vector<Vec3> faceNormal;       // faceNormals(scene)
  // A receiver's share of the surface: its owner triangle's area split evenly among that
  // triangle's samples, so bounce energies do not depend on the atlas resolution.
  std::vector<double> area;
  std::size_t count() const { return samples.texels.size(); }
};

// Checks the options, rasterises `atlases` over `atlasUv` and finds the seams. Errors: the
// texel bake's (options, sizes, rasteriser), kInvalidArgument when no texel is sampled.
Status prepareTexelReceivers(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                             const TexelBakeOptions& options, TexelReceivers* out);

// The direct pass's outputs for receivers [begin, end).
struct TexelDirectRange {
  std::vector<float> unshadowed, shadowed;  // (end - begin) x order^2
  std::vector<float> visibility;            // options.visibilityOrder > 0: (end - begin) x visibilityOrder^2
  std::vector<HitBlock> blocks;             // with interreflection: the range's blocks' front-face hits
  std::size_t outsideLight = 0;             // local lighting: receivers outside the sphere
  PassStats stats;
};

// Direct pass over receivers [begin, end): the one-machine texel bake's, on those receivers.
// kInvalidArgument when begin is not a multiple of kBlockVertices or the range is empty or past the receivers.
Status bakeTexelDirectRange(const Scene& scene, const TexelReceivers& receivers, const TexelBakeOptions& options,
                            std::size_t begin, std::size_t end, TexelDirectRange* out);

// Bounce 0 of every receiver, rho S ([receiver][channel][coefficient]), and its energy summed in
// receiver order. kSizeMismatch when `shadowed` is not receivers x order^2.
Status texelFirstBounce(const TexelReceivers& receivers, int order, std::span<const float> shadowed,
                        std::vector<float>* bounce, double* energy);

// A per-receiver array scattered to all atlases' texels (`stride` floats a texel), dilated
// `dilation` texels into the gutters and seam-stitched; *filled: 1 where sampled or filled.
struct TexelTexture {
  std::vector<float> values;
  std::size_t stride = 0;
  std::vector<std::uint8_t> filled;
};
Status scatterTexels(const TexelReceivers& receivers, std::span<const TextureAtlas> atlases, std::span<const float> perReceiver,
                     std::size_t stride, int dilation, TexelTexture* out);

// Bounce `bounce` over the receiver blocks [firstBlock, firstBlock + blocks.size()), reading
// `previous`, the previous bounce's texture (scatterTexels of it at 3 order^2 floats): writes
// the range's bounce into *current, each block's energy into *blockEnergy (summed in block
// order they are the one-machine energy) and adds the hits that found no texel to *unmapped.
// kCorrupt when a hit record names a triangle out of range or has a weight that is not finite
// (checked block by block before the block is gathered: records a sharded bake read from a file).
Status gatherTexelBounceRange(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                              const TexelReceivers& receivers, const TexelBakeOptions& options, int bounce,
                              std::size_t firstBlock, std::span<const HitBlockView> blocks, const TexelTexture& previous,
                              std::vector<float>* current, std::vector<double>* blockEnergy, std::uint64_t* unmapped,
                              PassStats* stats);

// Per-receiver passes of the whole bake, as the one-machine bake holds them at its end.
struct TexelPasses {
  std::vector<float> unshadowed, shadowed;  // receivers x order^2
  std::vector<float> interreflected;        // receivers x 3 order^2: B^0 + B^1 + ... in bounce order; empty without
  std::vector<float> visibility;            // receivers x visibilityOrder^2, or empty
  int bounces = 0;
  std::vector<double> bounceEnergy;
};

// The stored textures of `passes` (scattered, dilated, stitched), the coverage, the normals
// and the counts into *out (its passes, unmappedHits and texelsOutsideLight left to the caller).
Status finishTexelBake(const TexelReceivers& receivers, std::span<const TextureAtlas> atlases,
                       const TexelBakeOptions& options, TexelPasses&& passes, TexelBakeResult* out);

}  // namespace prt::bake
