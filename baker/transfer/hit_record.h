// The direct pass's record of occluded rays that hit a front face, kept per vertex block for
// the interreflection gathers (diffuse bounces in transfer_bake.cpp, glossy ones in
// glossy_bake.cpp). Internal to prt_transfer.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace prt::bake {

// Vertices per block: the unit of parallel work and of hit storage.
inline constexpr std::size_t kBlockVertices = 64;

// One occluded ray that hit a front face: where, and how much it weighs at its origin.
struct Hit {
  std::uint32_t triangle;
  std::uint16_t u, v;  // barycentrics of vertices 1 and 2, unorm16
  float weight;        // w max(0, n.w) / pi
};

struct HitBlock {
  std::vector<std::uint32_t> hitStart;  // per vertex of the block, plus one
  std::vector<Hit> hits;
  std::vector<std::uint32_t> hitSample;  // glossy bakes only: the sample index k of each hit (w_k)
};

// What the bounce gathers read of a block: views of a HitBlock, or of a sharded bake's
// direct shard mapped in place (baker/shard), so neither copies the records.
struct HitBlockView {
  std::span<const std::uint32_t> hitStart;
  std::span<const Hit> hits;
  std::span<const std::uint32_t> hitSample;
};

// Whether every record names a triangle below `triangles` (an index into the scene) and has a
// finite weight: what a reader of records it did not make checks before using them.
inline bool hitRecordsFit(std::span<const Hit> hits, std::size_t triangles) {
  bool fit = true;
  for (const Hit& h : hits) fit &= h.triangle < triangles && std::isfinite(h.weight);  // no branch per record
  return fit;
}

// The records' bytes, as a sharded bake's file holds them (Hit is its layout: baker/shard), for their checksum.
inline std::span<const std::uint8_t> hitRecordBytes(std::span<const Hit> hits) {
  return {reinterpret_cast<const std::uint8_t*>(hits.data()), hits.size_bytes()};
}

// Views of `blocks`, which must outlive them.
inline std::vector<HitBlockView> hitBlockViews(std::span<const HitBlock> blocks) {
  std::vector<HitBlockView> views;
  views.reserve(blocks.size());
  for (const HitBlock& b : blocks) views.push_back({b.hitStart, b.hits, b.hitSample});
  return views;
}

}  // namespace prt::bake
