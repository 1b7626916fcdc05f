// The texel series of a sharded texel bake (--texels; docs/scale-out.md, "Texels"): the
// one-machine texel bake's pieces (baker/transfer/texel_range.h) over the plan's receiver
// ranges, in files of their own beside the vertex series' (texelShardPath, texelMergedPassPath),
// since the two series stop independently (each has its own energies and threshold test).
// The merged asset's texel passes are the one-machine bake's, byte for byte: every process
// rasterises the same atlases to the same receivers, each receiver's rays and hits are its
// own, block energies are summed in block order, every bounce texture is the whole previous
// bounce scattered, dilated and stitched by the same code, and the stored textures are made
// once, by `merge -o`, from the per-receiver sums.
#pragma once

#include <cstdint>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/shard/sharded_bake.h"
#include "baker/transfer/texel_range.h"
#include "prt/status.h"

namespace prt::bake {

// What a command needs of the receivers (why: rasterising and finding seams is about 60% of a
// merge's CPU time at a 512² atlas, and most commands need less than all of it).
enum class TexelNeeds : std::uint8_t {
  kNothing,    // merge --pass K >= 1: the plan's ranges and the files only
  kReceivers,  // the direct pass, merge --pass 0: the receivers, no seams
  kSeams,      // a bounce, merge -o: the receivers and the seams (every scatter stitches them)
};

struct TexelShardContext {
  std::vector<Uv> atlasUv;      // the prepared scene's atlas UVs
  TexelBakeOptions options;     // texelBakeOptions of the plan's bake options
  TexelReceivers receivers;     // the plan's atlases rasterised (prepareTexelShards), as `needs` says
  TexelNeeds needs = TexelNeeds::kNothing;
};

// Rasterises the plan's atlases over `atlasUv` on the prepared `scene` into *out, as far as
// `needs` asks. kCorrupt when the receivers are not the plan's count (the plan or its prepared
// scene damaged or made by another prt-bake); the texel bake's errors otherwise.
Status prepareTexelShards(const BakePlan& plan, const Scene& scene, std::vector<Uv> atlasUv, const TexelBakeOptions& options,
                          TexelNeeds needs, TexelShardContext* out);

// Texel shard `shard` of pass `pass` (ctx.texels set): the direct pass over its receivers, or
// bounce `pass` over them, which reads texel merged pass pass-1, B^{pass-1} of every receiver
// (merged pass 0 for bounce 1, else the texel shards of pass-1) and its direct texel shard's
// hit records. *skipped: the texel series ended before `pass` (nothing written).
Status bakeTexelShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard, bool* skipped, PassStats* stats);

// Verifies every texel shard of `pass` and writes the texel merged pass (its energies, whether
// the texel series ends; after pass 0, B^0 of every receiver). *skipped as for bakeTexelShard.
Status mergeTexelPass(const ShardContext& ctx, std::uint32_t pass, bool* skipped, bool* final);

// Verifies the texel merged passes up to the last one and every texel shard of those passes
// and gives the TexelBakeResult bakeTexelTransfer would have given (no pass timings, no
// unmapped-hit count: those are in each shard's log).
Status mergeTexelShards(const ShardContext& ctx, TexelBakeResult* out);

}  // namespace prt::bake
