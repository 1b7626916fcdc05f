// The vertex bake split into independent pieces for a sharded bake (baker/shard,
// docs/scale-out.md): the direct pass over one range of vertex blocks, and one bounce's
// gather over one range given the whole previous bounce. Each piece runs exactly the code
// of bakeTransfer on its vertices (same direction set, same rays, same gather), so the
// pieces put together are byte for byte the one-machine bake.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/status.h"

namespace prt::bake {

// The direct pass's outputs for vertices [begin, end).
struct DirectRange {
  std::vector<float> unshadowed, shadowed;  // (end - begin) x order^2
  // options.glossy: (end - begin) x matrixEntryCount(order, matrixPackingFor(kShadowed, model))
  std::vector<float> glossyShadowed;
  std::vector<HitBlock> blocks;             // with interreflection: the range's blocks' front-face hits
  std::size_t verticesOutsideLight = 0;     // local lighting
  PassStats stats;
};

// Direct pass (unshadowed, shadowed, the glossy shadowed matrices with options.glossy, hit
// records when options.interreflection) over vertices [begin, end) of `scene`, prepared as
// bakeAsset prepares it (the glossy material split included). kInvalidArgument when begin is
// not a multiple of kBlockVertices or the range is empty or past the vertices.
Status bakeDirectRange(const Scene& scene, const BakeOptions& options, std::size_t begin, std::size_t end,
                       DirectRange* out);

// The glossy part of a range's bounce b (options.glossy and b <= options.glossyBounces):
// bakeTransfer's glossy gather, which runs before the diffuse one and feeds it.
struct GlossyRangeBounce {
  // M^{b-1} at every glossy sender, in glossySenderIndex order: for b = 1 the shadowed
  // matrices (packing matrixPackingFor(kShadowed, model)), for b >= 2 [sender][channel][dense n2 x n2].
  std::span<const float> previous;
  std::vector<float>* bounce = nullptr;  // out: M^b of the range's vertices, [vertex][channel][dense n2 x n2]
};

// Bounce `bounce` (>= 1) over the blocks [firstBlock, firstBlock + blocks.size()) given
// B^{bounce-1} of every vertex (`previous`) and, when `glossy` is given, the glossy senders'
// M^{bounce-1}: writes B^bounce of the range's vertices into *current (with the light the
// glossy senders add, as bakeTransfer) and each block's energy into *blockEnergy (summed in
// block order they are bakeTransfer's bounce energy). kInvalidArgument or kCorrupt on sizes
// or hit records that do not fit the scene (a triangle out of range, a weight not finite, a
// glossy hit's sample index out of range): the one check of the records a sharded bake reads.
// *hitCrc (when given): one per block, the CRC-32C of its records' bytes, taken as they were
// checked, for a caller that verifies the checksum of the file they came from afterwards.
Status gatherBounceRange(const Scene& scene, const BakeOptions& options, int bounce, std::size_t firstBlock,
                         std::span<const HitBlockView> blocks, std::span<const float> previous,
                         const GlossyRangeBounce* glossy, std::vector<float>* current, std::vector<double>* blockEnergy,
                         std::vector<std::uint32_t>* hitCrc, PassStats* stats);

}  // namespace prt::bake
