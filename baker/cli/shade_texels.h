// `prt-bake shade ASSET --texels`: the exit radiance of every sampled texel of an asset's
// transfer textures from its own stored transfer, and with a glossy --pass the TPFL glossy
// term of its visibility pass (docs/transfer-textures.md, "Glossy by the triple product").
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/vec3.h"

namespace prt {

struct TexelShade {
  const TransferPass* diffuse = nullptr;     // a texel vector pass of the asset
  const TransferPass* visibility = nullptr;  // the texel visibility pass, or null: no glossy term
  Vec3 eye{};                                // world space; with visibility
  bool glossyOnly = false;                   // print the glossy term alone
};

// Prints every sampled texel (atlas, texel, position, normal, with texel normals the stored
// shading normal, RGB radiance) of `asset` (a
// decoded, valid asset with atlases) under `lighting` (order^2 coefficients, order <= the
// asset's) as a table or JSON to `out`; errors to `err`. The glossy term, when asked for, is
// k_s sum_i g_l(i) (P V)_i y_i(R) at the texel's sample (prt::tpflGlossyExitRadiance), R and
// Schlick's n.v about the asset's stored texel normal when it has one, with the texel's material interpolated from its triangle's vertices, the lighting's `order` bands and
// V cut or zero-padded to the product's transfer order min(max(m, order), 2 order - 1), which
// changes nothing (V's bands past 2 order - 2 do not reach the first order bands). Returns the
// exit status.
int printTexels(const BakedAsset& asset, const TexelShade& shade, const std::string& path, const std::string& light,
                int order, const std::vector<Rgb>& lighting, bool json, std::FILE* out, std::FILE* err);

}  // namespace prt
