#include "baker/shard/shard_payloads.h"

#include <algorithm>
#include <cstddef>
#include <string>

#include "baker/shard/byte_io.h"

namespace prt::bake {
namespace {

Status corrupt(const std::string& what) { return Status::error(StatusCode::kCorrupt, what); }

std::size_t blocksOf(std::size_t count) { return (count + kBlockVertices - 1) / kBlockVertices; }

// The direct shard's flags word.
constexpr std::uint32_t kHasHits = 1, kGlossy = 2, kVisibility = 4;

// A hit record in the file (u32 triangle, u16 u, u16 v, f32 weight, little-endian) is Hit's
// layout on this (little-endian) host, so blocks of them are copied whole.
constexpr bool kHitLayoutIsTheFiles = sizeof(Hit) == 12 && offsetof(Hit, triangle) == 0 && offsetof(Hit, u) == 4 &&
                                      offsetof(Hit, v) == 6 && offsetof(Hit, weight) == 8;
static_assert(kHitLayoutIsTheFiles, "the shard file's hit records are copied as Hit structs");

// An array's bytes, as the file stores them (little-endian: this host's, byte_io.h).
template <typename T>
std::span<const std::uint8_t> bytesOf(std::span<const T> v) {
  return {reinterpret_cast<const std::uint8_t*>(v.data()), v.size_bytes()};
}
template <typename T>
std::span<const std::uint8_t> bytesOf(const std::vector<T>& v) {
  return bytesOf(std::span<const T>(v));
}

std::vector<std::uint8_t> joined(const PayloadParts& p) {
  std::size_t size = 0;
  for (const std::span<const std::uint8_t> part : p.parts) size += part.size();
  std::vector<std::uint8_t> out;
  out.reserve(size);
  for (const std::span<const std::uint8_t> part : p.parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

}  // namespace

void directShardParts(const DirectShard& s, PayloadParts* out) {
  std::size_t vertices = 0;
  for (const HitBlock& b : s.blocks) vertices += b.hitStart.size() - 1;
  // The small fields first, all of them, so no part's view into scratch moves: the flags,
  // the count outside the light, each vertex's hit count.
  out->scratch.clear();
  out->scratch.reserve(4 + 8 + (s.hasHits ? vertices * 4 : 0));
  ByteWriter w(&out->scratch);
  w.u32((s.hasHits ? kHasHits : 0) | (s.glossy ? kGlossy : 0) | (s.hasVisibility ? kVisibility : 0));
  w.u64(s.verticesOutsideLight);
  if (s.hasHits) {
    for (const HitBlock& b : s.blocks) {
      for (std::size_t v = 0; v + 1 < b.hitStart.size(); ++v) w.u32(b.hitStart[v + 1] - b.hitStart[v]);
    }
  }
  const std::span<const std::uint8_t> scratch = out->scratch;
  std::vector<std::span<const std::uint8_t>>& p = out->parts;
  p = {scratch.first(4), bytesOf(s.unshadowed), bytesOf(s.shadowed), scratch.subspan(4, 8)};
  if (s.glossy) p.push_back(bytesOf(s.glossyShadowed));
  if (s.hasVisibility) p.push_back(bytesOf(s.visibility));
  if (!s.hasHits) return;
  p.push_back(scratch.subspan(12));
  for (const HitBlock& b : s.blocks) p.push_back(bytesOf(b.hits));
  if (s.glossy) {
    for (const HitBlock& b : s.blocks) p.push_back(bytesOf(b.hitSample));
  }
}

std::vector<std::uint8_t> encodeDirectShard(const DirectShard& s) {
  PayloadParts parts;
  directShardParts(s, &parts);
  return joined(parts);
}

Status decodeDirectShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, std::size_t glossyEntries,
                         DirectShardPart part, DirectShard* out, std::size_t visibilityEntries) {
  ByteReader r(payload);
  std::uint32_t flags = 0;
  const std::uint64_t floats = static_cast<std::uint64_t>(count) * n2;
  const std::uint64_t glossyFloats = static_cast<std::uint64_t>(count) * glossyEntries;
  if (!r.u32(&flags)) return corrupt("the flags are cut short");
  if ((flags & ~(kHasHits | kGlossy | kVisibility)) != 0 || ((flags & kGlossy) && (flags & kVisibility))) {
    return corrupt("unknown flags " + std::to_string(flags));
  }
  out->hasHits = (flags & kHasHits) != 0;
  out->glossy = (flags & kGlossy) != 0;
  out->hasVisibility = (flags & kVisibility) != 0;
  if (out->hasVisibility && visibilityEntries == 0) return corrupt("holds visibility vectors the plan has none of");
  out->visibility.clear();
  out->unshadowed.clear();
  out->shadowed.clear();
  out->glossyShadowed.clear();
  // The bounce shards skip the transfer (viewed, not copied: its size is still checked).
  std::span<const float> skipped;
  const bool transfer = part == DirectShardPart::kTransfer;
  if (!(transfer ? r.floats(floats, &out->unshadowed) && r.floats(floats, &out->shadowed)
                 : r.floatView(floats, &skipped) && r.floatView(floats, &skipped)) ||
      !r.u64(&out->verticesOutsideLight)) {
    return corrupt("the direct pass's transfer (" + std::to_string(floats) + " floats each) is cut short");
  }
  if (out->glossy && !(transfer ? r.floats(glossyFloats, &out->glossyShadowed) : r.floatView(glossyFloats, &skipped))) {
    return corrupt("the glossy shadowed matrices (" + std::to_string(glossyFloats) + " floats) are cut short");
  }
  const std::uint64_t visibilityFloats = static_cast<std::uint64_t>(count) * visibilityEntries;
  if (out->hasVisibility && !(transfer ? r.floats(visibilityFloats, &out->visibility) : r.floatView(visibilityFloats, &skipped))) {
    return corrupt("the visibility vectors (" + std::to_string(visibilityFloats) + " floats) are cut short");
  }
  out->blocks.clear();
  out->hitViews.clear();
  out->hitStarts.clear();
  if (!out->hasHits) {
    if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the transfer");
    return Status::ok();
  }
  std::vector<std::uint32_t> perVertex;
  if (!r.u32s(count, &perVertex)) return corrupt("the per-vertex hit counts are cut short");
  std::uint64_t total = 0;
  for (std::uint32_t c : perVertex) total += c;
  // A glossy shard's hits also have their sample index (4 bytes each, after the records).
  const std::uint64_t hitBytes = out->glossy ? 16 : 12;
  if (total != r.remaining() / hitBytes || r.remaining() % hitBytes != 0) {
    return corrupt("the hit counts add up to " + std::to_string(total) + " hits, the file holds " +
                   std::to_string(r.remaining()) + " bytes of them (" + std::to_string(hitBytes) + " a hit)");
  }
  if (transfer) return Status::ok();
  // The records, then (glossy) their sample indices, in place: Hit's own bytes (kHitLayoutIsTheFiles).
  out->hitsOffset = payload.size() - r.remaining();
  const std::span<const std::uint8_t> rest = payload.subspan(out->hitsOffset);
  if (reinterpret_cast<std::uintptr_t>(rest.data()) % alignof(Hit) != 0) {
    return corrupt("the hit records are not 4-byte aligned in memory (read the file mapped or from an aligned buffer)");
  }
  const std::span<const Hit> hits(reinterpret_cast<const Hit*>(rest.data()), static_cast<std::size_t>(total));
  const std::span<const std::uint32_t> samples =
      out->glossy ? std::span<const std::uint32_t>(reinterpret_cast<const std::uint32_t*>(rest.data() + total * 12),
                                                   static_cast<std::size_t>(total))
                  : std::span<const std::uint32_t>();
  const std::size_t blocks = blocksOf(count);
  out->hitStarts.reserve(count + blocks);
  out->hitViews.resize(blocks);
  std::uint64_t first = 0;  // the block's first hit
  for (std::size_t j = 0; j < blocks; ++j) {
    const std::size_t v0 = j * kBlockVertices, v1 = std::min(count, v0 + kBlockVertices);
    const std::size_t start = out->hitStarts.size();
    std::uint64_t hitsOfBlock = 0;
    out->hitStarts.push_back(0);
    for (std::size_t v = v0; v < v1; ++v) {
      hitsOfBlock += perVertex[v];
      if (hitsOfBlock > 0xFFFFFFFFu) return corrupt("block " + std::to_string(j) + " holds more than 2^32 hits");
      out->hitStarts.push_back(static_cast<std::uint32_t>(hitsOfBlock));
    }
    HitBlockView& b = out->hitViews[j];
    b.hitStart = std::span<const std::uint32_t>(out->hitStarts).subspan(start, v1 - v0 + 1);  // reserved: never moves
    b.hits = hits.subspan(first, hitsOfBlock);
    if (out->glossy) b.hitSample = samples.subspan(first, hitsOfBlock);
    first += hitsOfBlock;
  }
  return Status::ok();
}

void bounceShardParts(const BounceShard& s, PayloadParts* out) {
  out->scratch.clear();
  out->parts = {bytesOf(s.bounce), bytesOf(s.blockEnergy), bytesOf(s.matrices)};
}

std::vector<std::uint8_t> encodeBounceShard(const BounceShard& s) {
  PayloadParts parts;
  bounceShardParts(s, &parts);
  return joined(parts);
}

Status decodeBounceShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, bool matrices,
                         BounceShardView* out) {
  ByteReader r(payload);
  const std::uint64_t floats = static_cast<std::uint64_t>(count) * 3 * n2;
  if (!r.floatView(floats, &out->bounce) || !r.doubles(blocksOf(count), &out->blockEnergy)) {
    return corrupt("the bounce's transfer or block energies are cut short");
  }
  out->matrices = {};
  if (matrices && !r.floatView(floats * n2, &out->matrices)) return corrupt("the glossy bounce's matrices are cut short");
  if (r.remaining() != 0) {
    return corrupt(std::to_string(r.remaining()) + " bytes after the " + (matrices ? "glossy matrices" : "block energies"));
  }
  return Status::ok();
}

void mergedPassParts(const MergedPass& m, PayloadParts* out) {
  out->scratch.clear();
  out->scratch.reserve(8 + m.energies.size() * 8 + 8);
  ByteWriter w(&out->scratch);
  w.u32(m.final ? 1 : 0);
  w.u32(static_cast<std::uint32_t>(m.energies.size()));
  w.doubles(m.energies);
  w.u64(m.bounce.size());
  const std::size_t head = out->scratch.size();
  w.u64(m.senderMatrices.size());
  const std::span<const std::uint8_t> scratch = out->scratch;
  out->parts = {scratch.first(head), bytesOf(m.bounce), scratch.subspan(head), bytesOf(m.senderMatrices)};
}

std::vector<std::uint8_t> encodeMergedPass(const MergedPass& m) {
  PayloadParts parts;
  mergedPassParts(m, &parts);
  return joined(parts);
}

Status decodeMergedPass(std::span<const std::uint8_t> payload, std::uint32_t pass, std::uint64_t bounceFloats,
                        std::uint64_t senderFloats, MergedPassView* out) {
  ByteReader r(payload);
  std::uint32_t final = 0, energies = 0;
  std::uint64_t floats = 0;
  if (!r.u32(&final) || final > 1 || !r.u32(&energies) || energies != pass + 1 ||
      !r.doubles(energies, &out->energies) || !r.u64(&floats)) {
    return corrupt("the pass's flags or energies are cut short or do not belong to pass " + std::to_string(pass));
  }
  if (floats != bounceFloats) {
    return corrupt("holds " + std::to_string(floats) + " floats of bounce transfer, not " + std::to_string(bounceFloats));
  }
  if (!r.floatView(floats, &out->bounce)) return corrupt("the bounce transfer is cut short");
  std::uint64_t senders = 0;
  if (!r.u64(&senders)) return corrupt("the glossy senders' matrix count is cut short");
  if (senders != senderFloats) {
    return corrupt("holds " + std::to_string(senders) + " floats of glossy senders' matrices, not " + std::to_string(senderFloats));
  }
  if (!r.floatView(senders, &out->senderMatrices)) return corrupt("the glossy senders' matrices are cut short");
  if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the transfer");
  out->final = final == 1;
  return Status::ok();
}

}  // namespace prt::bake
