// The inner sum of a diffuse bounce gather for one receiver, vectorised for the machine it
// runs on: gathered[i] += sum over its hits h and the hit triangle's corners c of
// w_hc previous[v_hc][i]. Every path gives the same bits: each element i adds the same
// products in the same order (hits in record order, corners 0, 1, 2), multiplies and adds
// rounded separately (this file builds with -ffp-contract=off). Private to prt_transfer.
//
// Summing the corner weights per distinct vertex first was measured and dropped: on the
// Stanford dragon a receiver's ~160 hits name ~320 distinct vertices of their ~480 corners,
// and the bookkeeping cost more than the rows it saved (bounce 0.32 -> 0.41 s on res2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/transfer/hit_record.h"

namespace prt::bake {

// Adds the receiver's `hits` to gathered[0, stride): hit.weight times the barycentric weights
// (1 - b1 - b2, b1, b2) of the hit triangle's corners, times each corner's row
// previous[index * stride, +stride). `indices` is the scene's index buffer. Trusted input:
// records checked by hitRecordsFit, indices by checkOptions. Uses the widest path this CPU has.
void gatherHits(std::span<const Hit> hits, const std::uint32_t* indices, const float* previous, std::size_t stride,
                float* gathered);

// The implementations, for tests. kDefault is x86-64's baseline (SSE2), or plain C++ elsewhere.
enum class GatherPath { kDefault, kAvx2, kAvx512 };
const char* gatherPathName(GatherPath path);
std::vector<GatherPath> availableGatherPaths();  // kDefault first; the last is the one gatherHits uses
// gatherHits on `path` (which must be available).
void gatherHitsOn(GatherPath path, std::span<const Hit> hits, const std::uint32_t* indices, const float* previous,
                  std::size_t stride, float* gathered);

}  // namespace prt::bake
