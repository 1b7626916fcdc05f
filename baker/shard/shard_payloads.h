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
  // A texel shard with a visibility pass (--texel-glossy): count x visibilityOrder^2, the
  // texels' visibility vectors; never with glossy (texel passes are vectors only).
  bool hasVisibility = false;
  std::vector<float> visibility;
  std::vector<HitBlock> blocks;             // encoding: ceil(count / 64) when hasHits (hitSample filled when glossy)
  // Decoding DirectShardPart::kHits: ceil(count / 64) views of the records in place, into the decoded
  // payload (which must outlive them), their hitStart in `hitStarts`. Nothing is copied: a
  // bounce shard reads 12 bytes a hit, ~160 hits a vertex, again every bounce.
  std::vector<HitBlockView> hitViews;
  std::vector<std::uint32_t> hitStarts;
  std::size_t hitsOffset = 0;  // kHits: where the records begin in the payload (the blocks' records follow one another)
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

// Pass b merged: the energies of bounces 0..b, whether the series stops here (bakeTransfer's
// rule), B^0 after pass 0 (computed by the merge), and the glossy senders' matrices the next
// glossy bounce reads. A bounce's B^b is not copied here: the next bounce's shards read it
// from this pass's shards (why: writing it again cost 40% of a merge, and every shard of the
// next pass checksummed it again). No running sum either: the asset merge sums
// B^0 + B^1 + ... from the shards (only the asset needs it).
struct MergedPass {
  bool final = false;
  std::vector<double> energies;  // b + 1
  std::span<const float> bounce;  // pass 0 with interreflection: B^0, vertices x 3 n2; else empty
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

// A payload as the pieces it is written from, in order: its small fields in `scratch`, its
// arrays viewed where they live (why: a direct shard's ~100 MB of hit records and a bounce
// shard's B^b were copied into one buffer only to be written out). The parts view `scratch`
// and the encoded struct, which must outlive them; a PayloadParts is not copied.
struct PayloadParts {
  std::vector<std::uint8_t> scratch;
  std::vector<std::span<const std::uint8_t>> parts;
};

// xParts: the payload's pieces (the one definition of each layout). encodeX: those pieces
// in one buffer (for tests and small files).
void directShardParts(const DirectShard& s, PayloadParts* out);
std::vector<std::uint8_t> encodeDirectShard(const DirectShard& s);
// What a reader of a direct shard takes from it; both check every size against the plan's.
enum class DirectShardPart : std::uint8_t {
  kTransfer,  // the merges: the transfer and glossy matrices copied out, the hit records' sizes checked only
  kHits,      // the bounce shards: the hit records viewed in place (out->hitViews), the transfer not copied
};
// `count` vertices (or texel receivers) at order^2 = n2 coefficients; a glossy shard's matrices
// `glossyEntries` floats a vertex, a shard with visibility vectors `visibilityEntries` floats a
// receiver (0: the shard may not have them). kHits: `payload` must outlive out->hitViews and be 4-byte aligned (as a
// mapped file is). The records' values (triangle, weight, sample index) are not checked here
// but by gatherBounceRange, their one reader, in its single pass over them (why: checking them
// twice cost a bounce shard two passes over ~100 MB of records).
Status decodeDirectShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, std::size_t glossyEntries,
                         DirectShardPart part, DirectShard* out, std::size_t visibilityEntries = 0);

void bounceShardParts(const BounceShard& s, PayloadParts* out);
std::vector<std::uint8_t> encodeBounceShard(const BounceShard& s);
// `matrices`: a glossy bounce, whose M^b must follow (count x 3 n2^2 floats); else none may.
// `payload` must be 4-byte aligned (a vector's or a mapped file's is).
Status decodeBounceShard(std::span<const std::uint8_t> payload, std::size_t count, int n2, bool matrices,
                         BounceShardView* out);

void mergedPassParts(const MergedPass& m, PayloadParts* out);
std::vector<std::uint8_t> encodeMergedPass(const MergedPass& m);
// Pass `pass` with exactly `bounceFloats` floats of B^0 (pass 0 with interreflection:
// vertices x 3 n2; else 0) and `senderFloats` floats of the senders' matrices. `payload` 4-byte aligned.
Status decodeMergedPass(std::span<const std::uint8_t> payload, std::uint32_t pass, std::uint64_t bounceFloats,
                        std::uint64_t senderFloats, MergedPassView* out);

}  // namespace prt::bake
