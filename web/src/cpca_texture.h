// Packs a CPCA transfer pass (prt/transfer_codec.h) for rendering straight from the
// compressed form (Sloan et al. 2003; docs/web-client.md, "CPCA rendering"). GL-free, so the
// packing is tested under Node like the rest of the client core.
//
// Per frame the renderer first computes a table of per-cluster constants, then one weighted
// sum per vertex:
//   table[k][0]     = sum over bands l of  L_l . mean_kl               (per channel)
//   table[k][1 + e] = L_l . (step_kl * basis_klj)    for weight e = (band l, vector j)
//   radiance_c(v)   = table[k][0]_c + sum_e level_ve * table[k][1 + e]_c
// where the quantisation step of each cluster and band is folded into its axes, so a
// vertex stores only its cluster id and its integer weight levels. The table is computed on
// the GPU by the same shader as uncompressed transfer (prt.vert), with the entries below as
// its "vertices": each entry is a transfer vector in the packTransfer layout.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/status.h"
#include "prt/transfer_codec.h"
#include "transfer_texture.h"

namespace prt::web {

struct CpcaTextures {
  int order = 0;              // bands packed (those decoded so far)
  int channels = 0;           // 1 or 3
  int clusters = 0;           // K
  int weightCount = 0;        // N = sum of n'_l over the packed bands
  int weightTexels = 0;       // ceil(N / 4) integer RGBA texels per vertex (at least 1)
  int entriesPerCluster = 0;  // E = 1 + 4 * weightTexels (weights padded to whole texels)
  int weightBits = 8;         // 8: RGBA8I levels; 16: RGBA16I
  // weightsBefore[b] = sum of n'_l for l < b, b = 0 .. order: the weights a display order
  // of b uses (the others multiply table entries that are zero under lighting cut to b bands).
  std::vector<int> weightsBefore;
  // K * E entries, entry k * E + e, in the packTransfer layout at `order` (prt.vert reads it).
  TransferTexture entries;
  // Integer levels, vertex v's weights at texels v * weightTexels .. +weightTexels-1 of a
  // kTransferTextureWidth-wide texture, 4 per texel; int8 (weightBits 8) or int16 values,
  // little-endian, ready for texImage2D.
  int weightWidth = 0, weightHeight = 0;
  std::vector<std::uint8_t> weightData;
  std::vector<std::uint16_t> clusterOf;  // per vertex (K <= 65536): an integer vertex attribute
  // The table's texture: K * E RGB32F texels, kTransferTextureWidth wide.
  int tableWidth = 0, tableHeight = 0;
};

// Packs `cpca` (its decoded bands, 1 .. order) for a device whose textures hold at most
// `maxHeight` rows (MAX_TEXTURE_SIZE). Errors name what does not fit, or inconsistent input.
Status packCpca(const CpcaTransfer& cpca, int maxHeight, CpcaTextures* out);

// The renderer's arithmetic on the CPU, for tests: exit radiance (RGB per vertex) of the
// packed pass under `lighting` (packLighting layout, kPackedLightingFloats floats, cut to displayOrder) at
// display order `displayOrder`; scalar passes are multiplied by `albedo` (3 floats per vertex).
std::vector<float> cpcaRadiance(const CpcaTextures& packed, const float* lighting, int displayOrder,
                                const std::vector<float>& albedo);

}  // namespace prt::web
