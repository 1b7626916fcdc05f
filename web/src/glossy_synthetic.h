// A synthetic CPCA matrix pass and its plain expansion, for testing the glossy renderer
// without the codec or the baker (tests/web/glossy_core_node_test.mjs, the browser tests'
// hook): random clusters, integer weight levels, steps, mean and basis matrices of a fixed
// seed, shaped like a real pass (a mean near the unoccluded projection, smaller basis terms).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/glossy_lobe.h"
#include "prt/status.h"
#include "prt/transfer_codec.h"

namespace prt::web {

struct SyntheticGlossySpec {
  int bands = 3;              // 1 .. 8
  int channels = 1;           // 1 or 3
  MatrixPacking packing = MatrixPacking::kFull;
  int clusters = 4;           // >= 1
  int vectors = 2;            // N' >= 0
  int weightBits = 8;         // 8 or 16
  std::uint64_t seed = 1;
};

// Fills *out (vertexCount vertices) deterministically from spec.seed. With `glossy` (one flag
// per vertex, else empty) the vertices flagged 0 go to one extra cluster whose matrices are
// all zero, as a bake stores non-glossy vertices: their glossy term is exactly 0 whatever
// the Fresnel factor. Errors on a bad spec or mask size.
Status makeSyntheticCpcaMatrix(const SyntheticGlossySpec& spec, std::uint32_t vertexCount, CpcaMatrixTransfer* out,
                               std::span<const std::uint8_t> glossy = {});

// Expands `cpca` to [vertex][channel][packed entry] floats of order cpca.bands:
// x = mean + sum_j (level_j * step) B_j, summed in j order in float, as
// prt::cpcaMatrixReconstruct documents it (the reference the renderer is measured against).
Status expandCpcaMatrix(const CpcaMatrixTransfer& cpca, std::vector<float>* out);

}  // namespace prt::web
