// The inner sum of a bounce gather for one receiver, vectorised for the machine it runs on:
// gathered[i] += sum_j weight_j previous[row_j][i], over the rows its hits read (a vertex
// bake's hit triangle corners, a texel bake's bilinear taps). Every path gives the same bits:
// each element i adds the same products in the same order (j ascending), multiplies and adds
// rounded separately (this file builds with -ffp-contract=off). Private to prt_transfer.
//
// Summing the weights per distinct row first was measured and dropped: on the Stanford
// dragon a receiver's ~160 hits name ~320 distinct vertices among their ~480 corners, and the
// bookkeeping cost more than the rows it saved (bounce 0.32 -> 0.41 s on res2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/transfer/hit_record.h"

namespace prt::bake {

// One receiver's terms, in the order they are summed: row index and weight.
struct WeightedRows {
  std::vector<std::size_t> rows;
  std::vector<float> weights;
  void clear() {
    rows.clear();
    weights.clear();
  }
  void add(std::size_t row, float weight) {
    rows.push_back(row);
    weights.push_back(weight);
  }
};

// gathered[i] += sum_j terms.weights[j] * previous[terms.rows[j] * stride + i] for i in
// [0, stride), j ascending. Trusted input: every row inside `previous`. Uses the widest path
// this CPU has.
void addWeightedRows(const WeightedRows& terms, const float* previous, std::size_t stride, float* gathered);

// A vertex bake's receiver: for each of `hits` in order and each corner c = 0, 1, 2 of its
// triangle, the term (indices[3 triangle + c], hit.weight times the barycentric weight
// (1 - b1 - b2, b1, b2)[c]) added to gathered as addWeightedRows does. `terms` is scratch.
// Trusted input: records checked by hitRecordsFit, indices by checkOptions.
void gatherHits(std::span<const Hit> hits, const std::uint32_t* indices, const float* previous, std::size_t stride,
                float* gathered, WeightedRows* terms);

// The implementations, for tests. kDefault is x86-64's baseline (SSE2), or plain C++ elsewhere.
enum class GatherPath { kDefault, kAvx2, kAvx512 };
const char* gatherPathName(GatherPath path);
std::vector<GatherPath> availableGatherPaths();  // kDefault first; the last is the one addWeightedRows uses
// addWeightedRows on `path` (which must be available).
void addWeightedRowsOn(GatherPath path, const WeightedRows& terms, const float* previous, std::size_t stride,
                       float* gathered);

}  // namespace prt::bake
