// Glossy transfer textures by the triple product with fixed lighting (TPFL; PRTT §3,
// docs/web-client.md "Glossy transfer textures"), the GL-free half: the per-frame product
// matrix P_c(L) packed as the RGBA32F texture texel_prt.frag reads, and that shader's
// glossy arithmetic on the CPU (tests/web/texel_core_node_test.mjs compares it with
// prt::tpflGlossyExitRadiance). The visibility vectors themselves are packed by
// packTexelTransfer (texel_texture.h) as a 1-channel texel pass of the visibility's order.
#pragma once

#include <span>
#include <vector>

#include "prt/asset.h"
#include "prt/sh_triple_product.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::web {

// The most visibility bands the shader reads: ShTripleProduct's 2 * 8 - 1 = 15 (bands past
// 2n - 1 do not reach the product's first n bands), so at most ceil(15^2 / 4) = 57 layers.
inline constexpr int kMaxTpflVisibilityLayers = (kMaxTripleTransferOrder * kMaxTripleTransferOrder + 3) / 4;

// The product's transfer order for `bands` lighting/output bands and an order-`visibilityOrder`
// visibility: clamp(visibilityOrder, bands, 2 bands - 1), as prt-bake shade --texels takes it.
int tpflTransferOrder(int bands, int visibilityOrder);

// P_c(L) for the three channels, as texel_prt.frag reads it with texelFetch: a texture
// rowTexels wide and 3 * bands^2 high, texel (t, c * bands^2 + i) = P_c[i][4t .. 4t+3] (zero
// past transferOrder^2). Size: 16 * rowTexels * 3 bands^2 bytes, at most 57 x 192 texels
// (175 KiB) at bands 8.
struct TpflProductTexture {
  int bands = 0, transferOrder = 0, rowTexels = 0;
  std::vector<float> texels;  // rowTexels * 3 * bands^2 * 4 floats, row-major
};

// Packs P_c = sum_j C_ijk L_c,j (product.productMatrixUnchecked, per channel) for `lighting`
// (product.order()^2 RGB coefficients) into *out. Errors (out untouched): a size mismatch,
// non-finite lighting.
Status packTpflProduct(const ShTripleProduct& product, std::span<const Rgb> lighting, TpflProductTexture* out);

// One fragment's glossy term as texel_prt.frag computes it, in its order of operations:
// T_c,i = sum_t dot(P texel (t, c n^2 + i), v_t) over the first `visibilityLayers` vec4 of
// `visibility` (the texel's values as the shader samples them), then
// k_s,c sum_i g_l(i)(s) y_i(R) T_c,i with R = reflect(-v, n) of the unit normal n, Schlick's
// k_s from (f0 r, g, b, s, f90) = `specular` (k_s = f0 when !fresnel). A point at the eye
// gets 0. visibilityLayers is at most product.rowTexels.
void tpflGlossyCpu(const TpflProductTexture& product, const float* visibility, int visibilityLayers, Vec3 position, Vec3 normal,
                   const float specular[5], Vec3 eye, bool fresnel, float out[3]);

}  // namespace prt::web
