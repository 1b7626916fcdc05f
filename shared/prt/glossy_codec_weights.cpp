// Row weights of the matrix codec for a scene's glossy lobes (prt/glossy_codec_weights.h).
#include "prt/glossy_codec_weights.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "prt/sh_basis.h"

namespace prt {

Status glossyMatrixRowWeights(int order, std::span<const SpecularMaterial> materials, std::vector<double>* out) {
  if (Status st = checkShOrder(order); !st.isOk()) return st;
  // Distinct exponents of the specular materials: a scene has few, a mesh many vertices.
  std::vector<float> exponents;
  for (const SpecularMaterial& m : materials) {
    const bool specular = m.f0.r > 0.0f || m.f0.g > 0.0f || m.f0.b > 0.0f || m.f90 > 0.0f;
    if (!specular) continue;
    if (!(std::isfinite(m.exponent) && m.exponent >= 0.0f)) {
      return Status::error(StatusCode::kInvalidArgument, "specular exponent " + std::to_string(m.exponent) + " is not finite and >= 0");
    }
    exponents.push_back(m.exponent);
  }
  std::sort(exponents.begin(), exponents.end());
  exponents.erase(std::unique(exponents.begin(), exponents.end()), exponents.end());
  out->clear();
  if (exponents.empty()) return Status::ok();
  std::vector<double> band(static_cast<std::size_t>(order), 0.0), scales(static_cast<std::size_t>(order));
  for (float s : exponents) {
    if (Status st = phongLobeBandScales(order, s, scales); !st.isOk()) return st;
    for (std::size_t l = 0; l < band.size(); ++l) band[l] = std::max(band[l], std::fabs(scales[l]));
  }
  out->resize(static_cast<std::size_t>(order) * static_cast<std::size_t>(order));
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m)
      (*out)[static_cast<std::size_t>(l * (l + 1) + m)] = std::clamp(band[static_cast<std::size_t>(l)], kMinGlossyRowWeight, 1.0);
  return Status::ok();
}

}  // namespace prt
