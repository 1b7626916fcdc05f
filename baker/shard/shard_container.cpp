#include "baker/shard/shard_container.h"

#include <algorithm>
#include <cstring>

#include "baker/shard/byte_io.h"
#include "prt/checksum.h"

namespace prt::bake {
namespace {

// Eight bytes each; the kind is in the magic so a shard never passes for a plan.
const char* magicFor(ShardFileKind kind) {
  switch (kind) {
    case ShardFileKind::kPlan: return "PRTPLAN1";
    case ShardFileKind::kShard: return "PRTSHRD1";
    case ShardFileKind::kMergedPass: return "PRTPASS1";
    case ShardFileKind::kPreparedScene: return "PRTSCEN1";
    case ShardFileKind::kTexelShard: return "PRTTSHD1";
    case ShardFileKind::kTexelMergedPass: return "PRTTPAS1";
  }
  return "????????";
}

const char* kindName(ShardFileKind kind) {
  switch (kind) {
    case ShardFileKind::kPlan: return "bake plan";
    case ShardFileKind::kShard: return "bake shard";
    case ShardFileKind::kMergedPass: return "merged pass";
    case ShardFileKind::kPreparedScene: return "prepared scene";
    case ShardFileKind::kTexelShard: return "texel bake shard";
    case ShardFileKind::kTexelMergedPass: return "texel merged pass";
  }
  return "file";
}

}  // namespace

std::vector<std::uint8_t> encodeShardFile(const ShardHeader& h, std::span<const std::uint8_t> payload) {
  const std::span<const std::uint8_t> whole[] = {payload};
  const std::array<std::uint8_t, kShardHeaderBytes> header = shardFileHeader(h, whole);
  std::vector<std::uint8_t> out(kShardHeaderBytes + payload.size());
  std::copy(header.begin(), header.end(), out.begin());
  std::copy(payload.begin(), payload.end(), out.begin() + kShardHeaderBytes);
  return out;
}

std::array<std::uint8_t, kShardHeaderBytes> shardFileHeader(const ShardHeader& h,
                                                            std::span<const std::span<const std::uint8_t>> payloadParts) {
  std::uint64_t size = 0;
  std::uint32_t crc = 0;
  for (const std::span<const std::uint8_t> part : payloadParts) {
    size += part.size();
    crc = crc32c(part, crc);
  }
  std::array<std::uint8_t, kShardHeaderBytes> out{};
  std::size_t at = 0;
  auto put = [&](const void* v, std::size_t n) {  // little-endian: this host's (byte_io.h)
    std::memcpy(out.data() + at, v, n);
    at += n;
  };
  const std::uint32_t version = kShardFormatVersion;
  put(magicFor(h.kind), 8);
  put(&version, 4);
  put(&h.planId, 4);
  put(&h.pass, 4);
  put(&h.shard, 4);
  put(&h.vertexBegin, 8);
  put(&h.vertexEnd, 8);
  put(&size, 8);
  put(&crc, 4);
  const std::uint32_t headerCrc = crc32c(std::span<const std::uint8_t>(out).first(at));  // bytes 0..51
  put(&headerCrc, 4);
  return out;
}

Status payloadChecksumMismatch() {
  return Status::error(StatusCode::kChecksumMismatch, "payload checksum mismatch: the file is damaged");
}

Status decodeShardFile(std::span<const std::uint8_t> bytes, ShardFileKind kind, ShardHeader* h,
                       std::span<const std::uint8_t>* payload, PayloadCheck check) {
  const std::string what = kindName(kind);
  const Status notThis = Status::error(StatusCode::kBadMagic, std::string("not a ") + what + " (its first bytes are not " +
                                                                 magicFor(kind) + ")");
  if (bytes.size() < 8) {
    const bool prefix = bytes.empty() || std::memcmp(bytes.data(), magicFor(kind), bytes.size()) == 0;
    return prefix ? Status::error(StatusCode::kTruncated, "truncated: " + std::to_string(bytes.size()) + " bytes") : notThis;
  }
  if (std::memcmp(bytes.data(), magicFor(kind), 8) != 0) return notThis;
  if (bytes.size() < kShardHeaderBytes) {
    return Status::error(StatusCode::kTruncated, "truncated: " + std::to_string(bytes.size()) + " bytes, shorter than the " +
                                                     std::to_string(kShardHeaderBytes) + "-byte header");
  }
  ByteReader r(bytes.subspan(8));
  std::uint32_t version = 0, payloadCrc = 0, headerCrc = 0;
  std::uint64_t payloadBytes = 0;
  r.u32(&version);
  r.u32(&h->planId);
  r.u32(&h->pass);
  r.u32(&h->shard);
  r.u64(&h->vertexBegin);
  r.u64(&h->vertexEnd);
  r.u64(&payloadBytes);
  r.u32(&payloadCrc);
  r.u32(&headerCrc);
  h->payloadCrc = payloadCrc;
  h->kind = kind;
  if (crc32c(bytes.first(52)) != headerCrc) {
    return Status::error(StatusCode::kChecksumMismatch, "header checksum mismatch: the file is damaged");
  }
  if (version != kShardFormatVersion) {
    return Status::error(StatusCode::kBadVersion, what + " format version " + std::to_string(version) + ", this prt-bake reads " +
                                                      std::to_string(kShardFormatVersion));
  }
  const std::uint64_t available = bytes.size() - kShardHeaderBytes;
  if (payloadBytes > available) {
    return Status::error(StatusCode::kTruncated, "truncated: the header declares " + std::to_string(payloadBytes) +
                                                     " payload bytes, the file has " + std::to_string(available));
  }
  if (payloadBytes < available) {
    return Status::error(StatusCode::kCorrupt, std::to_string(available - payloadBytes) + " bytes after the payload");
  }
  *payload = bytes.subspan(kShardHeaderBytes);
  if (check == PayloadCheck::kNow && crc32c(*payload) != payloadCrc) return payloadChecksumMismatch();
  return Status::ok();
}

}  // namespace prt::bake
