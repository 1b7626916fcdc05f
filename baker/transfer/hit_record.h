// The direct pass's record of occluded rays that hit a front face, kept per vertex block for
// the interreflection gathers (diffuse bounces in transfer_bake.cpp, glossy ones in
// glossy_bake.cpp). Internal to prt_transfer.
#pragma once

#include <cstddef>
#include <cstdint>
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

}  // namespace prt::bake
