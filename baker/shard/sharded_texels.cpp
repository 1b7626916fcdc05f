#include "baker/shard/sharded_texels.h"

#include <string>
#include <utility>

#include "baker/shard/plan_files.h"
#include "baker/shard/shard_payloads.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

std::string texelShardLabel(std::uint32_t pass, std::uint32_t shard) { return "texel " + shardLabel(pass, shard); }
std::string texelMergedLabel(std::uint32_t pass) { return "texel " + mergedLabel(pass); }

std::size_t coefficients(const ShardContext& ctx) { return static_cast<std::size_t>(shCoeffCount(ctx.transfer->order)); }

std::size_t visibilityEntries(const ShardContext& ctx) {
  const int m = ctx.texels->options.visibilityOrder;
  return m > 0 ? static_cast<std::size_t>(shCoeffCount(m)) : 0;
}

VertexRange allReceivers(const ShardContext& ctx) { return {0, ctx.plan->texelReceivers}; }

ShardHeader texelHeader(const ShardContext& ctx, ShardFileKind kind, std::uint32_t pass, std::uint32_t shard, VertexRange range) {
  ShardHeader h;
  h.kind = kind;
  h.planId = ctx.plan->id;
  h.pass = pass;
  h.shard = shard;
  h.vertexBegin = range.begin;  // a texel file's range: texel receivers
  h.vertexEnd = range.end;
  return h;
}

Status readTexelDirectShard(const ShardContext& ctx, std::uint32_t shard, DirectShardPart part, MappedFile* file, DirectShard* out) {
  const VertexRange range = ctx.plan->texelShards[shard];
  const std::string path = texelShardPath(ctx.planPath, 0, shard), label = texelShardLabel(0, shard);
  std::span<const std::uint8_t> payload;
  PRT_RETURN_IF_ERROR(readPlanFile(ctx, path, label, ShardFileKind::kTexelShard, 0, shard, range, file, &payload));
  if (Status s = decodeDirectShard(payload, range.end - range.begin, static_cast<int>(coefficients(ctx)), 0, part, out,
                                   visibilityEntries(ctx));
      !s.isOk()) {
    return Status::error(s.code(), label + " ('" + path + "') is corrupt: " + s.message());
  }
  if (out->hasHits != ctx.transfer->interreflection || out->glossy || out->hasVisibility != (visibilityEntries(ctx) > 0)) {
    return Status::error(StatusCode::kCorrupt,
                         label + " ('" + path + "') does not match the plan's interreflection or visibility setting");
  }
  return Status::ok();
}

// *out views *file.
Status readTexelBounceShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard, MappedFile* file, BounceShardView* out) {
  const VertexRange range = ctx.plan->texelShards[shard];
  const std::string path = texelShardPath(ctx.planPath, pass, shard), label = texelShardLabel(pass, shard);
  std::span<const std::uint8_t> payload;
  PRT_RETURN_IF_ERROR(readPlanFile(ctx, path, label, ShardFileKind::kTexelShard, pass, shard, range, file, &payload));
  if (Status s = decodeBounceShard(payload, range.end - range.begin, static_cast<int>(coefficients(ctx)), false, out); !s.isOk()) {
    return Status::error(s.code(), label + " ('" + path + "') is corrupt: " + s.message());
  }
  return Status::ok();
}

// *out views *file. Only texel merged pass 0 holds a bounce (B^0 of every receiver).
Status readTexelMergedPass(const ShardContext& ctx, std::uint32_t pass, MappedFile* file, MergedPassView* out) {
  const std::string path = texelMergedPassPath(ctx.planPath, pass), label = texelMergedLabel(pass);
  std::span<const std::uint8_t> payload;
  PRT_RETURN_IF_ERROR(
      readPlanFile(ctx, path, label, ShardFileKind::kTexelMergedPass, pass, kNoShard, allReceivers(ctx), file, &payload));
  const std::uint64_t bounceFloats = pass == 0 && ctx.transfer->interreflection ? ctx.plan->texelReceivers * 3 * coefficients(ctx) : 0;
  if (Status s = decodeMergedPass(payload, pass, bounceFloats, 0, out); !s.isOk()) {
    return Status::error(s.code(), label + " ('" + path + "') is corrupt: " + s.message());
  }
  return Status::ok();
}

ReadMergedPass readTexelMerged(const ShardContext& ctx) {
  return [&ctx](std::uint32_t j, MappedFile* file, MergedPassView* out) { return readTexelMergedPass(ctx, j, file, out); };
}

// B^{pass-1} of every receiver: texel merged pass 0's B^0 for bounce 1, else the texel
// shards of pass-1 checked and put together in range order (as the vertex series does).
Status previousTexelBounce(const ShardContext& ctx, std::uint32_t pass, const MergedPassView& merged, std::vector<float>* out) {
  if (pass == 1) {
    out->assign(merged.bounce.begin(), merged.bounce.end());
    return Status::ok();
  }
  out->clear();
  out->reserve(ctx.plan->texelReceivers * 3 * coefficients(ctx));
  for (std::uint32_t i = 0; i < ctx.plan->texelShards.size(); ++i) {
    MappedFile file;
    BounceShardView b;
    PRT_RETURN_IF_ERROR(readTexelBounceShard(ctx, pass - 1, i, &file, &b));
    out->insert(out->end(), b.bounce.begin(), b.bounce.end());
  }
  return Status::ok();
}

// A command that reached a piece its preparation left out (a bug in the caller, not in the files).
Status needs(const ShardContext& ctx, TexelNeeds need) {
  if (static_cast<int>(ctx.texels->needs) >= static_cast<int>(need)) return Status::ok();
  return Status::error(StatusCode::kInternal, "the texel receivers were prepared without what this step needs");
}

// The texel options as the stopping rule sees them (the vertex bake's interreflection and limits).
const BakeOptions& texelTransfer(const ShardContext& ctx) { return ctx.texels->options.transfer; }

}  // namespace

Status prepareTexelShards(const BakePlan& plan, const Scene& scene, std::vector<Uv> atlasUv, const TexelBakeOptions& options,
                          TexelNeeds needs, TexelShardContext* out) {
  out->atlasUv = std::move(atlasUv);
  out->options = options;
  out->needs = needs;
  if (needs == TexelNeeds::kNothing) return Status::ok();
  TexelBakeOptions prepare = options;
  prepare.stitchSeams = options.stitchSeams && needs == TexelNeeds::kSeams;
  PRT_RETURN_IF_ERROR(prepareTexelReceivers(scene, out->atlasUv, plan.atlases, prepare, &out->receivers));
  if (out->receivers.count() != plan.texelReceivers) {
    return Status::error(StatusCode::kCorrupt, "the plan's atlases give " + std::to_string(out->receivers.count()) +
                                                   " texel receivers, the plan has " + std::to_string(plan.texelReceivers) +
                                                   " (a damaged plan, or one made by another prt-bake)");
  }
  return Status::ok();
}

Status bakeTexelShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard, bool* skipped, PassStats* stats) {
  PRT_RETURN_IF_ERROR(checkPassShard(ctx, pass, shard));
  *skipped = false;
  const VertexRange range = ctx.plan->texelShards[shard];
  const TexelShardContext& t = *ctx.texels;
  const ShardHeader h = texelHeader(ctx, ShardFileKind::kTexelShard, pass, shard, range);
  if (pass == 0) {
    PRT_RETURN_IF_ERROR(needs(ctx, TexelNeeds::kReceivers));
    TexelDirectRange r;
    PRT_RETURN_IF_ERROR(bakeTexelDirectRange(*ctx.scene, t.receivers, t.options, range.begin, range.end, &r));
    DirectShard s;
    s.unshadowed = std::move(r.unshadowed);
    s.shadowed = std::move(r.shadowed);
    s.verticesOutsideLight = r.outsideLight;
    s.hasHits = ctx.transfer->interreflection;
    s.hasVisibility = !r.visibility.empty();
    s.visibility = std::move(r.visibility);
    s.blocks = std::move(r.blocks);
    *stats = r.stats;
    PayloadParts payload;
    directShardParts(s, &payload);
    return writePlanFile(texelShardPath(ctx.planPath, pass, shard), h, payload);
  }
  MappedFile previousFile;
  MergedPassView previous;
  PRT_RETURN_IF_ERROR(passBefore(pass, readTexelMerged(ctx), skipped, &previousFile, &previous));
  if (*skipped) return Status::ok();
  PRT_RETURN_IF_ERROR(needs(ctx, TexelNeeds::kSeams));
  std::vector<float> previousB;
  PRT_RETURN_IF_ERROR(previousTexelBounce(ctx, pass, previous, &previousB));
  // The bounce texture every shard of this pass makes alike: the whole previous bounce,
  // scattered, dilated and stitched as the one-machine bake makes it before its gather.
  TexelTexture texture;
  PRT_RETURN_IF_ERROR(scatterTexels(t.receivers, ctx.plan->atlases, previousB, 3 * coefficients(ctx), t.options.dilation, &texture));
  MappedFile directFile;
  DirectShard direct;
  PRT_RETURN_IF_ERROR(readTexelDirectShard(ctx, shard, DirectShardPart::kHits, &directFile, &direct));
  BounceShard out;
  std::uint64_t unmapped = 0;
  const std::string label = texelShardLabel(0, shard) + " ('" + texelShardPath(ctx.planPath, 0, shard) + "')";
  if (Status s = gatherTexelBounceRange(*ctx.scene, t.atlasUv, ctx.plan->atlases, t.receivers, t.options, static_cast<int>(pass),
                                        range.begin / kBlockVertices, direct.hitViews, texture, &out.bounce, &out.blockEnergy,
                                        &unmapped, stats);
      !s.isOk()) {
    return Status::error(s.code(), label + ": " + s.message());
  }
  PayloadParts payload;
  bounceShardParts(out, &payload);
  return writePlanFile(texelShardPath(ctx.planPath, pass, shard), h, payload);
}

Status mergeTexelPass(const ShardContext& ctx, std::uint32_t pass, bool* skipped, bool* final) {
  PRT_RETURN_IF_ERROR(checkPassShard(ctx, pass, kNoShard));
  *skipped = false;
  const std::uint32_t shards = static_cast<std::uint32_t>(ctx.plan->texelShards.size());
  MergedPass merged;
  std::vector<float> bounce0;
  if (pass == 0) {
    PRT_RETURN_IF_ERROR(needs(ctx, TexelNeeds::kReceivers));
    std::vector<float> shadowed;
    for (std::uint32_t i = 0; i < shards; ++i) {
      MappedFile file;
      DirectShard d;
      PRT_RETURN_IF_ERROR(readTexelDirectShard(ctx, i, DirectShardPart::kTransfer, &file, &d));
      shadowed.insert(shadowed.end(), d.shadowed.begin(), d.shadowed.end());
    }
    double energy0 = 0.0;
    if (ctx.transfer->interreflection) {
      PRT_RETURN_IF_ERROR(texelFirstBounce(ctx.texels->receivers, ctx.transfer->order, shadowed, &bounce0, &energy0));
      merged.bounce = bounce0;
    }
    merged.energies = {energy0};
  } else {
    MappedFile previousFile;
    MergedPassView previous;
    PRT_RETURN_IF_ERROR(passBefore(pass, readTexelMerged(ctx), skipped, &previousFile, &previous));
    if (*skipped) return Status::ok();
    double energy = 0.0;
    for (std::uint32_t i = 0; i < shards; ++i) {
      MappedFile file;
      BounceShardView b;
      PRT_RETURN_IF_ERROR(readTexelBounceShard(ctx, pass, i, &file, &b));
      for (double e : b.blockEnergy) energy += e;  // block order, as the one-machine texel bake sums them
    }
    merged.energies = std::move(previous.energies);
    merged.energies.push_back(energy);
  }
  merged.final = endsAfter(texelTransfer(ctx), pass, merged.energies);
  *final = merged.final;
  PayloadParts payload;
  mergedPassParts(merged, &payload);
  return writePlanFile(texelMergedPassPath(ctx.planPath, pass),
                       texelHeader(ctx, ShardFileKind::kTexelMergedPass, pass, kNoShard, allReceivers(ctx)), payload);
}

Status mergeTexelShards(const ShardContext& ctx, TexelBakeResult* out) {
  *out = TexelBakeResult{};
  PRT_RETURN_IF_ERROR(needs(ctx, TexelNeeds::kSeams));
  MappedFile lastFile;
  MergedPassView last;
  std::uint32_t finalPass = 0;
  for (;; ++finalPass) {
    if (finalPass >= ctx.plan->passes) {
      return Status::error(StatusCode::kCorrupt, "no texel merged pass of the plan ends the texel bounce series");
    }
    PRT_RETURN_IF_ERROR(readTexelMergedPass(ctx, finalPass, &lastFile, &last));
    if (last.final) break;
  }
  const std::uint32_t shards = static_cast<std::uint32_t>(ctx.plan->texelShards.size());
  TexelPasses passes;
  for (std::uint32_t i = 0; i < shards; ++i) {
    MappedFile file;
    DirectShard d;
    PRT_RETURN_IF_ERROR(readTexelDirectShard(ctx, i, DirectShardPart::kTransfer, &file, &d));
    passes.unshadowed.insert(passes.unshadowed.end(), d.unshadowed.begin(), d.unshadowed.end());
    passes.shadowed.insert(passes.shadowed.end(), d.shadowed.begin(), d.shadowed.end());
    passes.visibility.insert(passes.visibility.end(), d.visibility.begin(), d.visibility.end());
    out->texelsOutsideLight += d.verticesOutsideLight;
  }
  // B^0 + B^1 + ... as the one-machine bake sums them: B^0 of the merged shadowed transfer,
  // then each bounce element by element in bounce order.
  if (ctx.transfer->interreflection) {
    double energy0 = 0.0;
    PRT_RETURN_IF_ERROR(texelFirstBounce(ctx.texels->receivers, ctx.transfer->order, passes.shadowed, &passes.interreflected, &energy0));
  }
  const std::size_t stride = 3 * coefficients(ctx);
  for (std::uint32_t pass = 1; pass <= finalPass; ++pass) {
    for (std::uint32_t i = 0; i < shards; ++i) {
      MappedFile file;
      BounceShardView b;
      PRT_RETURN_IF_ERROR(readTexelBounceShard(ctx, pass, i, &file, &b));
      float* total = &passes.interreflected[ctx.plan->texelShards[i].begin * stride];
      for (std::size_t e = 0; e < b.bounce.size(); ++e) total[e] += b.bounce[e];
    }
  }
  passes.bounces = static_cast<int>(finalPass);
  if (ctx.transfer->interreflection) passes.bounceEnergy = last.energies;
  return finishTexelBake(ctx.texels->receivers, ctx.plan->atlases, ctx.texels->options, std::move(passes), out);
}

}  // namespace prt::bake
