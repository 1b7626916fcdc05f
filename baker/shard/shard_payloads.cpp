#include "baker/shard/shard_payloads.h"

#include <cmath>
#include <string>

#include "baker/shard/byte_io.h"

namespace prt::bake {
namespace {

Status corrupt(const std::string& what) { return Status::error(StatusCode::kCorrupt, what); }

std::size_t blocksOf(std::size_t count) { return (count + kBlockVertices - 1) / kBlockVertices; }

}  // namespace

std::vector<std::uint8_t> encodeDirectShard(const DirectShard& s) {
  std::vector<std::uint8_t> out;
  ByteWriter w(&out);
  w.u32(s.hasHits ? 1 : 0);
  w.floats(s.unshadowed);
  w.floats(s.shadowed);
  w.u64(s.verticesOutsideLight);
  if (!s.hasHits) return out;
  for (const HitBlock& b : s.blocks) {
    for (std::size_t v = 0; v + 1 < b.hitStart.size(); ++v) w.u32(b.hitStart[v + 1] - b.hitStart[v]);
  }
  for (const HitBlock& b : s.blocks) {
    for (const Hit& h : b.hits) {
      w.u32(h.triangle);
      w.u32(static_cast<std::uint32_t>(h.u) | static_cast<std::uint32_t>(h.v) << 16);
      w.raw(&h.weight, sizeof h.weight);
    }
  }
  return out;
}

Status decodeDirectShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, std::uint64_t triangles,
                         DirectShard* out) {
  ByteReader r(payload);
  std::uint32_t hasHits = 0;
  const std::uint64_t floats = static_cast<std::uint64_t>(count) * n2;
  if (!r.u32(&hasHits) || hasHits > 1 || !r.floats(floats, &out->unshadowed) || !r.floats(floats, &out->shadowed) ||
      !r.u64(&out->verticesOutsideLight)) {
    return corrupt("the direct pass's transfer (" + std::to_string(floats) + " floats each) is cut short");
  }
  out->hasHits = hasHits == 1;
  out->blocks.clear();
  if (!out->hasHits) {
    if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the transfer");
    return Status::ok();
  }
  std::vector<std::uint32_t> perVertex;
  if (!r.u32s(count, &perVertex)) return corrupt("the per-vertex hit counts are cut short");
  std::uint64_t total = 0;
  for (std::uint32_t c : perVertex) total += c;
  if (total != r.remaining() / 12 || r.remaining() % 12 != 0) {
    return corrupt("the hit counts add up to " + std::to_string(total) + " hits, the file holds " +
                   std::to_string(r.remaining()) + " bytes of them (12 a hit)");
  }
  out->blocks.resize(blocksOf(count));
  for (std::size_t j = 0; j < out->blocks.size(); ++j) {
    HitBlock& b = out->blocks[j];
    const std::size_t first = j * kBlockVertices, last = std::min(count, first + kBlockVertices);
    b.hitStart.assign(1, 0);
    std::uint64_t hits = 0;
    for (std::size_t v = first; v < last; ++v) {
      hits += perVertex[v];
      if (hits > 0xFFFFFFFFu) return corrupt("block " + std::to_string(j) + " holds more than 2^32 hits");
      b.hitStart.push_back(static_cast<std::uint32_t>(hits));
    }
    b.hits.resize(static_cast<std::size_t>(hits));
    for (Hit& h : b.hits) {
      std::uint32_t uv = 0;
      r.u32(&h.triangle);
      r.u32(&uv);
      r.raw(&h.weight, sizeof h.weight);
      h.u = static_cast<std::uint16_t>(uv & 0xFFFFu);
      h.v = static_cast<std::uint16_t>(uv >> 16);
      if (h.triangle >= triangles || !std::isfinite(h.weight)) {
        return corrupt("a hit record names triangle " + std::to_string(h.triangle) + " of " + std::to_string(triangles) +
                       " or has a weight that is not finite");
      }
    }
  }
  return Status::ok();
}

std::vector<std::uint8_t> encodeBounceShard(const BounceShard& s) {
  std::vector<std::uint8_t> out;
  ByteWriter w(&out);
  w.floats(s.bounce);
  w.doubles(s.blockEnergy);
  return out;
}

Status decodeBounceShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, BounceShard* out) {
  ByteReader r(payload);
  const std::uint64_t floats = static_cast<std::uint64_t>(count) * 3 * n2;
  if (!r.floats(floats, &out->bounce) || !r.doubles(blocksOf(count), &out->blockEnergy)) {
    return corrupt("the bounce's transfer or block energies are cut short");
  }
  if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the block energies");
  return Status::ok();
}

std::vector<std::uint8_t> encodeMergedPass(const MergedPass& m) {
  std::vector<std::uint8_t> out;
  ByteWriter w(&out);
  w.u32(m.final ? 1 : 0);
  w.u32(static_cast<std::uint32_t>(m.energies.size()));
  w.doubles(m.energies);
  w.u64(m.bounce.size());
  w.floats(m.bounce);
  w.floats(m.total);
  return out;
}

Status decodeMergedPass(std::span<const std::uint8_t> payload, std::uint32_t pass, std::size_t vertices, int n2,
                        MergedPass* out) {
  ByteReader r(payload);
  std::uint32_t final = 0, energies = 0;
  std::uint64_t floats = 0;
  if (!r.u32(&final) || final > 1 || !r.u32(&energies) || energies != pass + 1 ||
      !r.doubles(energies, &out->energies) || !r.u64(&floats)) {
    return corrupt("the pass's flags or energies are cut short or do not belong to pass " + std::to_string(pass));
  }
  const std::uint64_t expected = static_cast<std::uint64_t>(vertices) * 3 * n2;
  if (floats != expected && floats != 0) {
    return corrupt("holds " + std::to_string(floats) + " floats per array, not " + std::to_string(expected));
  }
  if (!r.floats(floats, &out->bounce) || !r.floats(floats, &out->total)) return corrupt("the bounce transfer is cut short");
  if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the transfer");
  out->final = final == 1;
  return Status::ok();
}

}  // namespace prt::bake
