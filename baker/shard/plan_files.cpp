#include "baker/shard/plan_files.h"

#include <array>
#include <cstdio>

#include "native/file_io.h"

namespace prt::bake {

namespace {

constexpr std::uint64_t kMaxShardFileBytes = std::uint64_t{1} << 40;

}  // namespace

std::string shardLabel(std::uint32_t pass, std::uint32_t shard) {
  return "shard " + std::to_string(shard) + " of pass " + std::to_string(pass);
}

std::string mergedLabel(std::uint32_t pass) { return "merged pass " + std::to_string(pass); }

Status readPlanFile(const ShardContext& ctx, const std::string& path, const std::string& label, ShardFileKind kind,
                    std::uint32_t pass, std::uint32_t shard, VertexRange range, MappedFile* file,
                    std::span<const std::uint8_t>* payload, PayloadCheck check, std::uint32_t* payloadCrc) {
  const std::string named = label + " ('" + path + "')";
  if (Status s = MappedFile::open(path, kMaxShardFileBytes, file); !s.isOk()) {
    if (s.code() == StatusCode::kNotFound) {
      return Status::error(StatusCode::kNotFound, named + " is missing" +
                                                      (kind == ShardFileKind::kShard || kind == ShardFileKind::kTexelShard
                                                           ? " (run prt-bake bake-shard --plan " + ctx.planPath + " --shard " +
                                                                 std::to_string(shard) + " --pass " + std::to_string(pass) + ")"
                                                           : " (run prt-bake merge --plan " + ctx.planPath + " --pass " +
                                                                 std::to_string(pass) + ")"));
    }
    return Status::error(s.code(), named + ": " + s.message());
  }
  ShardHeader h;
  if (Status s = decodeShardFile(file->bytes(), kind, &h, payload, check); !s.isOk()) {
    return Status::error(s.code(), named + " is corrupt: " + s.message());
  }
  if (payloadCrc) *payloadCrc = h.payloadCrc;
  if (h.planId != ctx.plan->id) {
    char text[120];
    std::snprintf(text, sizeof text, " belongs to another plan (plan id %08x, this plan is %08x)", h.planId, ctx.plan->id);
    return Status::error(StatusCode::kInvalidArgument, named + text);
  }
  if (h.pass != pass || h.shard != shard || h.vertexBegin != range.begin || h.vertexEnd != range.end) {
    return Status::error(StatusCode::kCorrupt,
                         named + " holds pass " + std::to_string(h.pass) + " shard " +
                             (h.shard == kNoShard ? std::string("(merged)") : std::to_string(h.shard)) + " over [" +
                             std::to_string(h.vertexBegin) + ", " + std::to_string(h.vertexEnd) + "), the plan expects [" +
                             std::to_string(range.begin) + ", " + std::to_string(range.end) + ")");
  }
  return Status::ok();
}

Status writePlanFile(const std::string& path, const ShardHeader& h, const PayloadParts& payload) {
  const std::array<std::uint8_t, kShardHeaderBytes> header = shardFileHeader(h, payload.parts);
  std::vector<std::span<const std::uint8_t>> file = {header};
  file.insert(file.end(), payload.parts.begin(), payload.parts.end());
  return writePartsAtomically(path, file);
}

Status passBefore(std::uint32_t pass, const ReadMergedPass& read, bool* ended, MappedFile* file, MergedPassView* previous) {
  *ended = false;
  Status first;
  for (std::uint32_t j = pass; j-- > 0;) {
    const Status s = read(j, file, previous);
    if (s.code() == StatusCode::kNotFound) {
      if (first.isOk()) first = s;
      continue;
    }
    PRT_RETURN_IF_ERROR(s);
    if (j + 1 == pass || previous->final) {
      *ended = previous->final;
      return Status::ok();
    }
    return first;  // pass j did not end the series, so merged pass j+1 should be there
  }
  return first;
}

bool endsAfter(const BakeOptions& o, std::uint32_t pass, const std::vector<double>& energies) {
  if (!o.interreflection || static_cast<int>(pass) >= o.maxBounces) return true;
  return pass > 0 && !(energies[pass] > o.bounceThreshold * energies[0]);
}

Status checkPassShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard) {
  if (pass >= ctx.plan->passes) {
    return Status::error(StatusCode::kInvalidArgument, "pass " + std::to_string(pass) + " is outside the plan's passes 0 … " +
                                                           std::to_string(ctx.plan->passes - 1));
  }
  if (shard != kNoShard && shard >= ctx.plan->shards.size()) {
    return Status::error(StatusCode::kInvalidArgument, "shard " + std::to_string(shard) + " is outside the plan's shards 0 … " +
                                                           std::to_string(ctx.plan->shards.size() - 1));
  }
  return Status::ok();
}

}  // namespace prt::bake
