// A vertex bake split over machines (docs/scale-out.md): `bakeShard` runs one vertex range
// of one pass, `mergePass` is the barrier between passes (bounce b's shards read merged
// pass b-1 and, for b >= 2, the shards of pass b-1), `mergeShards` verifies every shard and gives the BakeResult bakeTransfer would
// have given on one machine, byte for byte. Every file is written atomically (native/file_io.h)
// and every file read is checked: present, of this plan, pass and range, checksums intact;
// a failure names the file.
#pragma once

#include <cstdint>
#include <string>

#include "baker/scene/scene.h"
#include "baker/shard/bake_plan.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/status.h"

namespace prt::bake {

struct TexelShardContext;  // sharded_texels.h

struct ShardContext {
  const BakePlan* plan = nullptr;
  std::string planPath;
  const Scene* scene = nullptr;            // prepared as bakeAsset prepares it (glossy split, prepareVertexBake): the plan's prepared scene
  const BakeOptions* transfer = nullptr;   // as prepareVertexBake returns them
  const TexelShardContext* texels = nullptr;  // a texel plan's texel series (sharded_texels.h); else null
};

// The number of passes a bake with `transfer` runs at most: 1 + the bounce limit with interreflection, else 1.
std::uint32_t plannedPasses(const BakeOptions& transfer);

// Bakes shard `shard` of pass `pass` and writes it to shardPath(). Pass b >= 1 reads merged
// pass b-1 (its energies, whether the series ended; B^0 for b = 1), every shard of pass b-1
// for B^{b-1} when b >= 2, and the shard's direct-pass hit records. *skipped: the bounce series ended before
// `pass` (nothing to do, nothing written). kInvalidArgument for a pass or shard outside the plan.
Status bakeShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard, bool* skipped, PassStats* stats);

// Verifies every shard of pass `pass`, merges them and writes mergedPassPath(); *final says
// whether the bounce series ends with this pass. *skipped as for bakeShard.
Status mergePass(const ShardContext& ctx, std::uint32_t pass, bool* skipped, bool* final);

// Verifies the merged passes up to the final one and every shard of those passes, and
// assembles the whole bake's result (no pass timings: those are in each shard's log).
Status mergeShards(const ShardContext& ctx, BakeResult* out);

}  // namespace prt::bake
