#include "baker/shard/sharded_bake.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <span>
#include <vector>

#include "baker/shard/plan_files.h"
#include "baker/shard/shard_container.h"
#include "baker/shard/shard_payloads.h"
#include "baker/transfer/diffuse_bounce.h"
#include "baker/transfer/glossy_bake.h"
#include "baker/transfer/transfer_range.h"
#include "native/file_io.h"
#include "native/mapped_file.h"
#include "prt/checksum.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

int coefficients(const ShardContext& ctx) { return shCoeffCount(ctx.transfer->order); }

// Floats of one vertex's glossy shadowed matrix (the packing bakeTransfer stores).
std::size_t glossyEntries(const ShardContext& ctx) {
  return matrixEntryCount(ctx.transfer->order, matrixPackingFor(TransferKind::kShadowed, ctx.transfer->lighting.model));
}

// Whether bounce `pass` gathers glossy matrices too (bakeTransfer's glossyThisBounce).
bool glossyBounce(const BakeOptions& o, std::uint32_t pass) {
  return o.glossy && o.interreflection && pass >= 1 && static_cast<int>(pass) <= o.glossyBounces;
}

// Floats of the glossy senders' matrices merged pass `pass` carries: what bounce pass+1 reads
// when it is glossy (the shadowed matrices after pass 0, M^pass after a bounce), else none.
std::uint64_t senderFloats(const ShardContext& ctx, std::uint32_t pass) {
  if (!glossyBounce(*ctx.transfer, pass + 1)) return 0;
  std::size_t senders = 0;
  glossySenderIndex(*ctx.scene, &senders);
  const std::uint64_t n2 = static_cast<std::uint64_t>(coefficients(ctx));
  return senders * (pass == 0 ? glossyEntries(ctx) : 3 * n2 * n2);
}

// Appends the rows of `perVertex` (floats a vertex, for the vertices from `begin`) that
// belong to glossy senders: shards in range order give the senders in sender order.
void appendSenderRows(const std::vector<std::int32_t>& senderIndex, std::uint64_t begin, std::span<const float> rows,
                      std::size_t perVertex, std::vector<float>* out) {
  for (std::size_t local = 0; local * perVertex < rows.size(); ++local) {
    if (senderIndex[begin + local] < 0) continue;
    const auto first = rows.begin() + static_cast<std::ptrdiff_t>(local * perVertex);
    out->insert(out->end(), first, first + static_cast<std::ptrdiff_t>(perVertex));
  }
}

// A direct shard's payload whose checksum its reader verifies (PayloadCheck::kByCaller).
struct DeferredChecksum {
  std::span<const std::uint8_t> payload;
  std::uint32_t expected = 0;
};

// kHits: the bounce shards need the hit records (out->hitViews, views into *file); the
// merges (kTransfer) only the transfer. With `deferred` (kHits only) the payload's checksum
// is left to the caller (verifyDeferred), which reads every byte of the records anyway.
Status readDirectShard(const ShardContext& ctx, std::uint32_t shard, DirectShardPart part, MappedFile* file,
                       DirectShard* out, DeferredChecksum* deferred = nullptr) {
  const VertexRange range = ctx.plan->shards[shard];
  std::span<const std::uint8_t> payload;
  std::uint32_t expected = 0;
  PRT_RETURN_IF_ERROR(readPlanFile(ctx, shardPath(ctx.planPath, 0, shard), shardLabel(0, shard), ShardFileKind::kShard, 0,
                                   shard, range, file, &payload, deferred ? PayloadCheck::kByCaller : PayloadCheck::kNow,
                                   &expected));
  if (deferred) *deferred = {payload, expected};
  if (Status s = decodeDirectShard(payload, range.end - range.begin, coefficients(ctx), glossyEntries(ctx), part, out);
      !s.isOk()) {
    return Status::error(s.code(), shardLabel(0, shard) + " ('" + shardPath(ctx.planPath, 0, shard) + "') is corrupt: " + s.message());
  }
  if (out->hasHits != ctx.transfer->interreflection || out->glossy != ctx.transfer->glossy) {
    return Status::error(StatusCode::kCorrupt, shardLabel(0, shard) + " ('" + shardPath(ctx.planPath, 0, shard) +
                                                   "') does not match the plan's interreflection or glossy setting");
  }
  return Status::ok();
}

Status damagedDirectShard(const ShardContext& ctx, std::uint32_t shard) {
  const Status s = payloadChecksumMismatch();
  return Status::error(s.code(), shardLabel(0, shard) + " ('" + shardPath(ctx.planPath, 0, shard) + "') is corrupt: " + s.message());
}

// The deferred checksum of direct shard `shard` (read with kHits): the bytes before its
// records, each block's records from their checksums as the gather took them (`hitCrc`),
// the bytes after (a glossy shard's sample indices). A mismatch names the file, as an
// immediate check would.
Status verifyDeferred(const ShardContext& ctx, std::uint32_t shard, const DirectShard& direct,
                      const DeferredChecksum& deferred, std::span<const std::uint32_t> hitCrc) {
  std::uint32_t crc = crc32c(deferred.payload.first(direct.hitsOffset));
  std::size_t at = direct.hitsOffset;
  for (std::size_t j = 0; j < direct.hitViews.size(); ++j) {
    const std::size_t bytes = direct.hitViews[j].hits.size_bytes();
    crc = crc32cCombine(crc, hitCrc[j], bytes);
    at += bytes;
  }
  crc = crc32c(deferred.payload.subspan(at), crc);
  return crc == deferred.expected ? Status::ok() : damagedDirectShard(ctx, shard);
}

// *out views *file.
Status readBounceShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard, MappedFile* file, BounceShardView* out) {
  const VertexRange range = ctx.plan->shards[shard];
  std::span<const std::uint8_t> payload;
  const std::string path = shardPath(ctx.planPath, pass, shard);
  PRT_RETURN_IF_ERROR(readPlanFile(ctx, path, shardLabel(pass, shard), ShardFileKind::kShard, pass, shard, range, file, &payload));
  if (Status s = decodeBounceShard(payload, range.end - range.begin, coefficients(ctx), glossyBounce(*ctx.transfer, pass), out);
      !s.isOk()) {
    return Status::error(s.code(), shardLabel(pass, shard) + " ('" + path + "') is corrupt: " + s.message());
  }
  return Status::ok();
}

// *out views *file.
Status readMergedPass(const ShardContext& ctx, std::uint32_t pass, MappedFile* file, MergedPassView* out) {
  std::span<const std::uint8_t> payload;
  const std::string path = mergedPassPath(ctx.planPath, pass);
  PRT_RETURN_IF_ERROR(readPlanFile(ctx, path, mergedLabel(pass), ShardFileKind::kMergedPass, pass, kNoShard,
                                   {0, ctx.plan->vertices}, file, &payload));
  // Only merged pass 0 holds a bounce (B^0); bounce b's B^b stays in its shards.
  const std::uint64_t bounceFloats =
      pass == 0 && ctx.transfer->interreflection ? ctx.plan->vertices * 3 * static_cast<std::uint64_t>(coefficients(ctx)) : 0;
  if (Status s = decodeMergedPass(payload, pass, bounceFloats, senderFloats(ctx, pass), out); !s.isOk()) {
    return Status::error(s.code(), mergedLabel(pass) + " ('" + path + "') is corrupt: " + s.message());
  }
  return Status::ok();
}

// B^{pass-1} of every vertex, which bounce `pass` gathers: merged pass 0's B^0 for bounce 1
// (`merged`, viewed), else the shards of pass-1 checked again and put together in range order
// in *storage. Why from the shards: a merged pass holding B^b would be written once and read
// by every shard, 40% of a merge's time, to save each shard this one copy.
Status previousBounce(const ShardContext& ctx, std::uint32_t pass, const MergedPassView& merged,
                      std::vector<float>* storage, std::span<const float>* out) {
  if (pass == 1) {
    *out = merged.bounce;
    return Status::ok();
  }
  const std::uint32_t shards = static_cast<std::uint32_t>(ctx.plan->shards.size());
  storage->clear();
  storage->reserve(ctx.plan->vertices * 3 * static_cast<std::size_t>(coefficients(ctx)));
  for (std::uint32_t i = 0; i < shards; ++i) {
    MappedFile file;
    BounceShardView b;
    PRT_RETURN_IF_ERROR(readBounceShard(ctx, pass - 1, i, &file, &b));
    storage->insert(storage->end(), b.bounce.begin(), b.bounce.end());  // reserved: copied once, never zero-filled
  }
  *out = *storage;
  return Status::ok();
}


ReadMergedPass readMerged(const ShardContext& ctx) {
  return [&ctx](std::uint32_t j, MappedFile* file, MergedPassView* out) { return readMergedPass(ctx, j, file, out); };
}

}  // namespace

std::uint32_t plannedPasses(const BakeOptions& transfer) {
  return transfer.interreflection ? 1 + static_cast<std::uint32_t>(transfer.maxBounces) : 1;
}

Status bakeShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard, bool* skipped, PassStats* stats) {
  PRT_RETURN_IF_ERROR(checkPassShard(ctx, pass, shard));
  *skipped = false;
  const VertexRange range = ctx.plan->shards[shard];
  ShardHeader h;
  h.kind = ShardFileKind::kShard;
  h.planId = ctx.plan->id;
  h.pass = pass;
  h.shard = shard;
  h.vertexBegin = range.begin;
  h.vertexEnd = range.end;
  if (pass == 0) {
    DirectRange r;
    PRT_RETURN_IF_ERROR(bakeDirectRange(*ctx.scene, *ctx.transfer, range.begin, range.end, &r));
    DirectShard s;
    s.unshadowed = std::move(r.unshadowed);
    s.shadowed = std::move(r.shadowed);
    s.verticesOutsideLight = r.verticesOutsideLight;
    s.hasHits = ctx.transfer->interreflection;
    s.glossy = ctx.transfer->glossy;
    s.glossyShadowed = std::move(r.glossyShadowed);
    s.blocks = std::move(r.blocks);
    *stats = r.stats;
    PayloadParts payload;
    directShardParts(s, &payload);
    return writePlanFile(shardPath(ctx.planPath, pass, shard), h, payload);
  }
  MappedFile previousFile;
  MergedPassView previous;
  PRT_RETURN_IF_ERROR(passBefore(pass, readMerged(ctx), skipped, &previousFile, &previous));
  if (*skipped) return Status::ok();
  std::vector<float> previousStorage;
  std::span<const float> previousB;
  PRT_RETURN_IF_ERROR(previousBounce(ctx, pass, previous, &previousStorage, &previousB));
  MappedFile directFile;
  DirectShard direct;
  DeferredChecksum deferred;
  PRT_RETURN_IF_ERROR(readDirectShard(ctx, shard, DirectShardPart::kHits, &directFile, &direct, &deferred));
  BounceShard out;
  const GlossyRangeBounce glossy{previous.senderMatrices, &out.matrices};
  std::vector<std::uint32_t> hitCrc;
  const Status gathered = gatherBounceRange(*ctx.scene, *ctx.transfer, static_cast<int>(pass), range.begin / kBlockVertices,
                                            direct.hitViews, previousB, glossyBounce(*ctx.transfer, pass) ? &glossy : nullptr,
                                            &out.bounce, &out.blockEnergy, &hitCrc, stats);
  if (!gathered.isOk()) {
    // Records refused before their checksum was verified: a damaged file says so by name.
    if (crc32c(deferred.payload) != deferred.expected) return damagedDirectShard(ctx, shard);
    return gathered;
  }
  // Nothing computed from the records is written before their file's checksum is verified.
  PRT_RETURN_IF_ERROR(verifyDeferred(ctx, shard, direct, deferred, hitCrc));
  PayloadParts payload;
  bounceShardParts(out, &payload);
  return writePlanFile(shardPath(ctx.planPath, pass, shard), h, payload);
}

Status mergePass(const ShardContext& ctx, std::uint32_t pass, bool* skipped, bool* final) {
  PRT_RETURN_IF_ERROR(checkPassShard(ctx, pass, kNoShard));
  *skipped = false;
  const std::uint32_t shards = static_cast<std::uint32_t>(ctx.plan->shards.size());
  MergedPass merged;
  std::vector<float> bounce0;  // pass 0: B^0, computed here
  // The glossy senders' part of this pass, which the next (glossy) bounce reads.
  const bool keepSenders = senderFloats(ctx, pass) > 0;
  std::size_t senders = 0;
  const std::vector<std::int32_t> senderIndex = keepSenders ? glossySenderIndex(*ctx.scene, &senders) : std::vector<std::int32_t>{};
  if (pass == 0) {
    std::vector<float> shadowed;
    for (std::uint32_t i = 0; i < shards; ++i) {
      MappedFile file;
      DirectShard d;
      PRT_RETURN_IF_ERROR(readDirectShard(ctx, i, DirectShardPart::kTransfer, &file, &d));
      shadowed.insert(shadowed.end(), d.shadowed.begin(), d.shadowed.end());
      if (keepSenders) {
        appendSenderRows(senderIndex, ctx.plan->shards[i].begin, d.glossyShadowed, glossyEntries(ctx), &merged.senderMatrices);
      }
    }
    double energy0 = 0.0;
    if (ctx.transfer->interreflection) {
      firstBounce(*ctx.scene, ctx.transfer->order, shadowed, vertexAreas(*ctx.scene), &bounce0, &energy0);
      merged.bounce = bounce0;
    }
    merged.energies = {energy0};
  } else {
    MappedFile previousFile;
    MergedPassView previous;
    PRT_RETURN_IF_ERROR(passBefore(pass, readMerged(ctx), skipped, &previousFile, &previous));
    if (*skipped) return Status::ok();
    double energy = 0.0;
    for (std::uint32_t i = 0; i < shards; ++i) {
      MappedFile file;
      BounceShardView b;
      PRT_RETURN_IF_ERROR(readBounceShard(ctx, pass, i, &file, &b));
      for (double e : b.blockEnergy) energy += e;  // block order, as bakeTransfer sums them
      if (keepSenders) {
        const std::size_t n2 = static_cast<std::size_t>(coefficients(ctx));
        appendSenderRows(senderIndex, ctx.plan->shards[i].begin, b.matrices, 3 * n2 * n2, &merged.senderMatrices);
      }
    }
    merged.energies = std::move(previous.energies);
    merged.energies.push_back(energy);
  }
  merged.final = endsAfter(*ctx.transfer, pass, merged.energies);
  *final = merged.final;
  ShardHeader h;
  h.kind = ShardFileKind::kMergedPass;
  h.planId = ctx.plan->id;
  h.pass = pass;
  h.shard = kNoShard;
  h.vertexEnd = ctx.plan->vertices;
  PayloadParts payload;
  mergedPassParts(merged, &payload);
  return writePlanFile(mergedPassPath(ctx.planPath, pass), h, payload);
}

Status mergeShards(const ShardContext& ctx, BakeResult* out) {
  *out = BakeResult{};
  out->order = ctx.transfer->order;
  MappedFile lastFile;
  MergedPassView last;
  std::uint32_t finalPass = 0;
  for (;; ++finalPass) {
    if (finalPass >= ctx.plan->passes) {
      return Status::error(StatusCode::kCorrupt, "no merged pass of the plan ends the bounce series");
    }
    PRT_RETURN_IF_ERROR(readMergedPass(ctx, finalPass, &lastFile, &last));
    if (last.final) break;
  }
  const std::uint32_t shards = static_cast<std::uint32_t>(ctx.plan->shards.size());
  for (std::uint32_t i = 0; i < shards; ++i) {
    MappedFile file;
    DirectShard d;
    PRT_RETURN_IF_ERROR(readDirectShard(ctx, i, DirectShardPart::kTransfer, &file, &d));
    out->unshadowed.insert(out->unshadowed.end(), d.unshadowed.begin(), d.unshadowed.end());
    out->shadowed.insert(out->shadowed.end(), d.shadowed.begin(), d.shadowed.end());
    out->glossyShadowed.insert(out->glossyShadowed.end(), d.glossyShadowed.begin(), d.glossyShadowed.end());
    out->verticesOutsideLight += d.verticesOutsideLight;
  }
  // The glossy interreflected series, summed as bakeTransfer sums it: the shadowed matrices,
  // then each glossy bounce's M^b in bounce order.
  const BakeOptions& o = *ctx.transfer;
  const bool glossySeries = o.glossy && o.interreflection && o.glossyBounces > 0;
  if (glossySeries) {
    out->glossyInterreflected =
        expandShadowedMatrices(out->glossyShadowed, o.order, matrixPackingFor(TransferKind::kShadowed, o.lighting.model));
  }
  const std::size_t fullEntries = matrixEntryCount(o.order, MatrixPacking::kFull);
  // The interreflected transfer as bakeTransfer sums it: B^0 (firstBounce of the shadowed
  // transfer), then each bounce's B^b in bounce order, element by element.
  if (o.interreflection) {
    double energy0 = 0.0;
    firstBounce(*ctx.scene, o.order, out->shadowed, vertexAreas(*ctx.scene), &out->interreflected, &energy0);
  }
  const std::size_t stride = 3 * static_cast<std::size_t>(coefficients(ctx));
  // The bounce shards were merged already; they are read again for the sums (which only the
  // asset needs) and so that a lost or damaged one is named.
  for (std::uint32_t pass = 1; pass <= finalPass; ++pass) {
    for (std::uint32_t i = 0; i < shards; ++i) {
      MappedFile file;
      BounceShardView b;
      PRT_RETURN_IF_ERROR(readBounceShard(ctx, pass, i, &file, &b));
      float* total = &out->interreflected[ctx.plan->shards[i].begin * stride];
      for (std::size_t e = 0; e < b.bounce.size(); ++e) total[e] += b.bounce[e];
      if (glossyBounce(o, pass)) {
        const VertexRange range = ctx.plan->shards[i];
        addBounceMatrices(b.matrices.data(), range.end - range.begin, o.order,
                          &out->glossyInterreflected[range.begin * 3 * fullEntries]);
      }
    }
  }
  if (glossySeries) out->glossyBounces = std::min(o.glossyBounces, static_cast<int>(finalPass));
  out->bounces = static_cast<int>(finalPass);
  out->bounceEnergy = ctx.transfer->interreflection ? last.energies : std::vector<double>{};
  return Status::ok();
}

}  // namespace prt::bake
