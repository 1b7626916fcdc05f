// What the shard files of a sharded bake hold, and their payloads' byte layouts
// (docs/scale-out.md, "Files"): a direct-pass shard, a bounce shard, a merged pass. The
// decoders take the sizes the plan implies and refuse any payload that does not have them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/transfer/hit_record.h"
#include "prt/status.h"

namespace prt::bake {

// Pass 0 of vertices [begin, end): the direct pass's scalar transfer and hit records.
struct DirectShard {
  std::vector<float> unshadowed, shadowed;  // count x n2
  std::uint64_t verticesOutsideLight = 0;
  bool hasHits = false;                     // interreflection stored
  std::vector<HitBlock> blocks;             // ceil(count / 64) when hasHits
};

// Pass b >= 1 of vertices [begin, end): B^b there and each block's energy.
struct BounceShard {
  std::vector<float> bounce;        // count x 3 n2
  std::vector<double> blockEnergy;  // ceil(count / 64)
};

// Pass b merged over every vertex: B^b, the running sum T_b = B^0 + ... + B^b, the energies
// of bounces 0..b, and whether the series stops here (bakeTransfer's rule).
struct MergedPass {
  bool final = false;
  std::vector<double> energies;     // b + 1
  std::vector<float> bounce, total;  // vertices x 3 n2 each; empty without interreflection
};

std::vector<std::uint8_t> encodeDirectShard(const DirectShard& s);
// `count` vertices at order^2 = n2 coefficients; hit triangles below `triangles`.
Status decodeDirectShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, std::uint64_t triangles,
                         DirectShard* out);

std::vector<std::uint8_t> encodeBounceShard(const BounceShard& s);
Status decodeBounceShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, BounceShard* out);

std::vector<std::uint8_t> encodeMergedPass(const MergedPass& m);
// Pass `pass` over `vertices` vertices (floats expected: vertices x 3 n2, or none).
Status decodeMergedPass(std::span<const std::uint8_t> payload, std::uint32_t pass, std::size_t vertices, int n2,
                        MergedPass* out);

}  // namespace prt::bake
