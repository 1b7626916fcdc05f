// What the vertex and the texel series of a sharded bake (sharded_bake.h, sharded_texels.h)
// share about their files: labels for errors, the checked read and the atomic write of one
// file of the plan, where a bounce pass finds the merged pass before it, the stopping rule
// and the check of a pass and shard against the plan. Private to prt_shard.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "baker/shard/shard_container.h"
#include "baker/shard/shard_payloads.h"
#include "baker/shard/sharded_bake.h"
#include "native/mapped_file.h"
#include "prt/status.h"

namespace prt::bake {

// "shard 2 of pass 1", "merged pass 1": how errors name a file of the vertex series (the
// texel series prefixes "texel ").
std::string shardLabel(std::uint32_t pass, std::uint32_t shard);
std::string mergedLabel(std::uint32_t pass);

// Reads and checks one file of the plan: present, this kind, this plan, pass, shard and range.
// The file is mapped, not copied (*payload views *file): the hit records are read in place.
// check, *payloadCrc: as decodeShardFile's (kByCaller: the caller verifies *payloadCrc).
// Errors name the file as `label ('path')`; a missing one says which command writes it.
Status readPlanFile(const ShardContext& ctx, const std::string& path, const std::string& label, ShardFileKind kind,
                    std::uint32_t pass, std::uint32_t shard, VertexRange range, MappedFile* file,
                    std::span<const std::uint8_t>* payload, PayloadCheck check = PayloadCheck::kNow,
                    std::uint32_t* payloadCrc = nullptr);

// Writes a file of the plan: its header, then its payload's parts where they lie (no copy), atomically.
Status writePlanFile(const std::string& path, const ShardHeader& h, const PayloadParts& payload);

// Reads merged pass j of one series into *previous (viewing *file).
using ReadMergedPass = std::function<Status(std::uint32_t j, MappedFile* file, MergedPassView* previous)>;

// Before pass `pass` >= 1: merged pass pass-1 (one read: it exists only when no earlier pass
// ended the series), or *ended when it is the last, or when it is absent because an earlier
// merged pass was the last (then passes after that one wrote nothing).
Status passBefore(std::uint32_t pass, const ReadMergedPass& read, bool* ended, MappedFile* file, MergedPassView* previous);

// bakeTransfer's (and the texel bake's) stopping rule after bounce `pass`, given energies 0..pass.
bool endsAfter(const BakeOptions& o, std::uint32_t pass, const std::vector<double>& energies);

// kInvalidArgument when `pass` or `shard` (kNoShard: none) is outside the plan.
Status checkPassShard(const ShardContext& ctx, std::uint32_t pass, std::uint32_t shard);

}  // namespace prt::bake
