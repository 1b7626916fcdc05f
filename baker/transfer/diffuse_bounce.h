// The diffuse interreflection gather of one bounce over a run of vertex blocks, shared by the
// one-machine bake (transfer_bake.cpp, every block) and a sharded bake's bounce shards
// (transfer_range.h, one shard's blocks): one routine, so both give the same bytes.
// Private to prt_transfer and the shard library (baker/shard).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/transfer_bake.h"

namespace prt::bake {

// Per vertex, a third of the area of every triangle it is a corner of (bounce energies
// weigh the DC transfer by it).
std::vector<double> vertexAreas(const Scene& scene);

// Bounce 0, B0_ci = rho_c S_i for every vertex ([vertex][channel][coefficient]), and its
// energy (sum over vertices, in vertex order, of area x DC term, all channels).
void firstBounce(const Scene& scene, int order, std::span<const float> shadowed, std::span<const double> vertexArea,
                 std::vector<float>* bounce0, double* energy0);

struct DiffuseBounceJob {
  const Scene* scene = nullptr;
  const BakeOptions* options = nullptr;  // order, progress
  std::string name;                      // progress and PassStats name: "bounce N"
  std::size_t firstBlock = 0;            // blocks[j] is the direct pass's block firstBlock + j
  std::span<const HitBlockView> blocks;
  const float* previous = nullptr;    // B^{b-1} of every vertex, [vertex][channel][coefficient]
  const float* fromGlossy = nullptr;  // nullptr, or per vertex of the blocks (as current) the light glossy senders add (glossy_bake.h)
  std::span<const double> vertexArea;
  float* current = nullptr;       // B^b of the blocks' vertices, from the first block's first vertex
  double* blockEnergy = nullptr;  // one per block: its vertices' area x DC term, all channels
  unsigned threads = 1;
  // Records read from a file (a sharded bake's, transfer_range.h): when > 0, each block's
  // records are checked (triangle below this count, weight finite) just before the block is
  // gathered, while they are in cache (why: a separate pass over ~100 MB of records cost a
  // bounce shard as much again); a block that fails is not gathered and is flagged in
  // badBlocks. 0: the bake's own records, not checked.
  std::size_t checkTriangles = 0;
  std::uint8_t* badBlocks = nullptr;  // with checkTriangles: one per block, set to 1 for a block that failed
  // With checkTriangles, optional: one per block, the CRC-32C of its records' bytes, taken
  // as they are checked, so that the caller verifies their file's checksum from the pieces
  // (crc32cCombine) without another pass over them.
  std::uint32_t* hitCrc = nullptr;
};

// Gathers bounce b for the job's blocks: Bb_ci(x) = rho_c(x) sum_hits w Bb-1_ci(h) (+ fromGlossy).
// Deterministic whatever job.threads; returns the pass's stats (no rays).
PassStats gatherDiffuseBounce(const DiffuseBounceJob& job);

}  // namespace prt::bake
