// The matrix codec's row weights for glossy transfer (docs/glossy.md "Compressing in the
// exit-radiance metric", docs/transfer-codec.md "Row weights"). Exit radiance is
//   L_o = k_s sum_i g_l(i)(s) (M L)_i y_i(R),
// so, averaged over reflection directions R (orthonormal y_i), an error dM costs
//   (1/4pi) sum_i g_l(i)(s)^2 ((dM L)_i)^2:
// row i of a transfer matrix matters in proportion to |g_l(i)(s)|. For a scene the weights
// are those of its most demanding lobe, band by band, so the metric is conservative for
// every material in it.
#pragma once

#include <span>
#include <vector>

#include "prt/glossy_lobe.h"
#include "prt/status.h"

namespace prt {

// Smallest row weight glossyMatrixRowWeights gives: a band that no lobe of the scene sees
// (g_l = 0, e.g. l = 2 for s = 0) is still fitted, at 1/64 of full weight, so the stored
// matrices stay a bounded approximation of the baked ones (and their rows can be unscaled).
inline constexpr double kMinGlossyRowWeight = 1.0 / 64.0;

// Row weights (order^2 values, row i = l(l+1)+m) for TransferCodecSettings::
// cpcaMatrixRowWeights: w_i = max(kMinGlossyRowWeight, max over specular materials of
// |g_l(i)(s)|), a material being specular when f0 or f90 is nonzero. That maximum is the
// sharpest lobe's g_l except where a smaller exponent's oscillating tail exceeds it
// (s_max < l - 1). *out is empty (unweighted) when no material is specular. Errors:
// kInvalidArgument (order outside 1..16, an exponent not finite and >= 0).
Status glossyMatrixRowWeights(int order, std::span<const SpecularMaterial> materials, std::vector<double>* out);

}  // namespace prt
