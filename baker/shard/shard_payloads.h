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

// Pass 0 of vertices [begin, end): the direct pass's scalar transfer, glossy shadowed
// matrices and hit records.
struct DirectShard {
  std::vector<float> unshadowed, shadowed;  // count x n2
  std::uint64_t verticesOutsideLight = 0;
  bool hasHits = false;                     // interreflection stored
  bool glossy = false;                      // --glossy: matrices, and each hit's sample index
  std::vector<float> glossyShadowed;        // glossy: count x the packing's entries
  std::vector<HitBlock> blocks;             // encoding: ceil(count / 64) when hasHits (hitSample filled when glossy)
  // Decoding with readHits: ceil(count / 64) views of the records in place, into the decoded
  // payload (which must outlive them), their hitStart in `hitStarts`. Nothing is copied: a
  // bounce shard reads 12 bytes a hit, ~160 hits a vertex, again every bounce.
  std::vector<HitBlockView> hitViews;
  std::vector<std::uint32_t> hitStarts;
};

// Pass b >= 1 of vertices [begin, end): B^b there, each block's energy and, for a glossy
// bounce, M^b there.
struct BounceShard {
  std::vector<float> bounce;        // count x 3 n2
  std::vector<double> blockEnergy;  // ceil(count / 64)
  std::vector<float> matrices;      // glossy bounces: count x 3 n2^2 ([vertex][channel][dense]); else empty
};

// A decoded bounce shard: the arrays viewed in place in the payload (which must outlive
// them), so a merge copies each float once, into its output.
struct BounceShardView {
  std::span<const float> bounce;
  std::vector<double> blockEnergy;  // copied: doubles need not be 8-byte aligned in the file
  std::span<const float> matrices;
};

// Pass b merged over every vertex: B^b, the energies of bounces 0..b, whether the series
// stops here (bakeTransfer's rule), and the glossy senders' matrices the next glossy bounce
// reads. No running sum: the asset merge sums B^0 + B^1 + ... from the shards (why: every
// merge and bounce shard would read and write it again, and only the asset needs it).
struct MergedPass {
  bool final = false;
  std::vector<double> energies;  // b + 1
  // vertices x 3 n2 in parts, stored one after another (the shards' ranges in order, viewed
  // where they lie: no copy); none without interreflection.
  std::vector<std::span<const float>> bounce;
  // M^b at the glossy senders, in sender order, when bounce b+1 is glossy: for b = 0 the
  // shadowed matrices (packed), for b >= 1 [sender][channel][dense n2 x n2]; else empty.
  std::vector<float> senderMatrices;
};

// A decoded merged pass, its arrays viewed in place in the payload (which must outlive them).
struct MergedPassView {
  bool final = false;
  std::vector<double> energies;
  std::span<const float> bounce;
  std::span<const float> senderMatrices;
};

// encodeX: the payload's bytes. appendX: the same appended to *out, its size reserved first
// (no regrowth): the writers put the container's header before it in the same buffer.
std::vector<std::uint8_t> encodeDirectShard(const DirectShard& s);
void appendDirectShard(const DirectShard& s, std::vector<std::uint8_t>* out);
// `count` vertices at order^2 = n2 coefficients; hit triangles below `triangles`; a glossy
// shard's matrices `glossyEntries` floats a vertex and its hits' sample indices below `samples`.
// With `readHits` the hit records are checked one by one and viewed in place (out->hitViews:
// `payload` must outlive them, and be 4-byte aligned, as a mapped file is); without it their
// sizes are checked but not the records (out->hitViews stays empty): for readers that use
// the transfer only.
Status decodeDirectShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, std::uint64_t triangles,
                         std::size_t glossyEntries, std::uint64_t samples, bool readHits, DirectShard* out);

std::vector<std::uint8_t> encodeBounceShard(const BounceShard& s);
void appendBounceShard(const BounceShard& s, std::vector<std::uint8_t>* out);
// `matrices`: a glossy bounce, whose M^b must follow (count x 3 n2^2 floats); else none may.
// `payload` must be 4-byte aligned (a vector's or a mapped file's is).
Status decodeBounceShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, bool matrices,
                         BounceShardView* out);

std::vector<std::uint8_t> encodeMergedPass(const MergedPass& m);
void appendMergedPass(const MergedPass& m, std::vector<std::uint8_t>* out);
// Pass `pass` over `vertices` vertices (floats expected: vertices x 3 n2, or none) with
// exactly `senderFloats` floats of the senders' matrices. `payload` 4-byte aligned.
Status decodeMergedPass(std::span<const std::uint8_t> payload, std::uint32_t pass, std::size_t vertices, int n2,
                        std::uint64_t senderFloats, MergedPassView* out);

}  // namespace prt::bake
