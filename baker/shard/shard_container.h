// The one container every file of a sharded bake uses (plan, shard, merged pass): a
// 56-byte header naming what the file holds and which plan it belongs to, then a payload,
// each with a CRC-32C (prt/checksum.h). Byte layout: docs/scale-out.md, "Files".
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "prt/status.h"

namespace prt::bake {

// kTexelShard and kTexelMergedPass: a texel plan's texel series (their range: texel receivers).
enum class ShardFileKind : std::uint8_t { kPlan, kShard, kMergedPass, kPreparedScene, kTexelShard, kTexelMergedPass };

// 5: texel plans (the atlases and texel ranges in the plan, atlas UVs and a flags word in the
// prepared scene, the texel files), visibility vectors in a direct shard;
// 4: merged bounce passes without B^b (the next bounce reads it from the shards);
// 3: the prepared scene beside the plan, and the scene's name and files in the plan;
// 2: glossy payloads, and merged passes without the running sum (docs/scale-out.md, "Files").
inline constexpr std::uint32_t kShardFormatVersion = 5;
inline constexpr std::size_t kShardHeaderBytes = 56;
inline constexpr std::uint32_t kNoShard = 0xFFFFFFFFu;  // the header's shard field in plans and merged passes

struct ShardHeader {
  ShardFileKind kind = ShardFileKind::kShard;
  std::uint32_t planId = 0;  // CRC-32C of the plan file; 0 in the plan itself
  std::uint32_t pass = 0;    // 0: the direct pass, b: bounce b
  std::uint32_t shard = kNoShard;
  std::uint64_t vertexBegin = 0, vertexEnd = 0;
  std::uint32_t payloadCrc = 0;  // set by decodeShardFile: CRC-32C of the payload (checked, unless PayloadCheck::kByCaller)
};

// The file's bytes: header (with the payload's size and checksum) then `payload`.
std::vector<std::uint8_t> encodeShardFile(const ShardHeader& header, std::span<const std::uint8_t> payload);

// The header of a file whose payload is `payloadParts` one after another (its size and
// checksum taken over them in order): written before them, the parts need no common buffer.
std::array<std::uint8_t, kShardHeaderBytes> shardFileHeader(const ShardHeader& header,
                                                            std::span<const std::span<const std::uint8_t>> payloadParts);

// When the payload's checksum is verified: kNow by decodeShardFile; kByCaller (a bounce
// shard's hit records) by its reader, from the pieces' checksums as it reads them
// (crc32cCombine), against header->payloadCrc, before it uses or writes anything computed
// from them (why: a separate pass over ~100 MB of records cost it 30 ms a bounce). The
// reader must stay safe on the unverified bytes (every index in them checked) and report a
// mismatch as payloadChecksumMismatch().
enum class PayloadCheck : std::uint8_t { kNow, kByCaller };

// Checks `bytes` as a file of `kind` and returns its header and payload (a view into bytes).
// Errors, each naming the problem: kTruncated (shorter than its header or its declared
// payload), kBadMagic (not this kind of file), kBadVersion (another format version),
// kChecksumMismatch (header, or payload with kNow), kCorrupt (bytes after the payload).
Status decodeShardFile(std::span<const std::uint8_t> bytes, ShardFileKind kind, ShardHeader* header,
                       std::span<const std::uint8_t>* payload, PayloadCheck check = PayloadCheck::kNow);

// The error for a payload whose checksum is not the header's.
Status payloadChecksumMismatch();

}  // namespace prt::bake
