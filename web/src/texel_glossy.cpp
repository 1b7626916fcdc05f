#include "texel_glossy.h"

#include <algorithm>
#include <cmath>

#include "glossy_texture.h"
#include "prt/glossy_lobe.h"
#include "transfer_texture.h"

namespace prt::web {

int tpflTransferOrder(int bands, int visibilityOrder) { return std::min(std::max(visibilityOrder, bands), 2 * bands - 1); }

Status packTpflProduct(const ShTripleProduct& product, std::span<const Rgb> lighting, TpflProductTexture* out) {
  const int n = product.order(), m = product.transferOrder();
  const std::size_t rows = static_cast<std::size_t>(n) * n, cols = static_cast<std::size_t>(m) * m;
  if (n < 1 || lighting.size() != rows) {
    return Status::error(StatusCode::kSizeMismatch, "TPFL product: " + std::to_string(lighting.size()) +
                                                        " lighting coefficients for an order-" + std::to_string(n) + " product");
  }
  for (const Rgb& l : lighting) {
    if (!std::isfinite(l.r) || !std::isfinite(l.g) || !std::isfinite(l.b)) {
      return Status::error(StatusCode::kNotFinite, "TPFL product: the lighting is not finite");
    }
  }
  TpflProductTexture t;
  t.bands = n;
  t.transferOrder = m;
  t.rowTexels = texelsForOrder(m);
  const std::size_t width = static_cast<std::size_t>(t.rowTexels) * 4;
  t.texels.assign(width * 3 * rows, 0.0f);
  std::vector<float> light(rows), matrix(rows * cols);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t j = 0; j < rows; ++j) light[j] = c == 0 ? lighting[j].r : c == 1 ? lighting[j].g : lighting[j].b;
    product.productMatrixUnchecked(n, light.data(), matrix.data());
    for (std::size_t i = 0; i < rows; ++i) {
      std::copy_n(&matrix[i * cols], cols, &t.texels[(static_cast<std::size_t>(c) * rows + i) * width]);
    }
  }
  *out = std::move(t);
  return Status::ok();
}

void tpflGlossyCpu(const TpflProductTexture& p, const float* visibility, int visibilityLayers, Vec3 position, Vec3 normal,
                   const float specular[5], Vec3 eye, bool fresnel, float out[3]) {
  out[0] = out[1] = out[2] = 0.0f;
  const Vec3 d = eye - position;
  const float distance = length(d);
  if (!(distance > 0.0f)) return;
  const Vec3 toEye = d * (1.0f / distance);
  const Vec3 n = normal;
  Vec3 r = reflectView(toEye, n);
  const float rl = length(r);
  r = rl > 0.0f ? r * (1.0f / rl) : n;
  const int bands = p.bands, rows = bands * bands;
  float y[kMaxGlossyOrder * kMaxGlossyOrder], g[kMaxGlossyOrder], gy[kMaxGlossyOrder * kMaxGlossyOrder];
  glossyShBasis(bands, r, y);
  phongLobeBandScalesUnchecked(bands, specular[3], g);
  for (int i = 0; i < rows; ++i) gy[i] = g[static_cast<int>(std::sqrt(static_cast<float>(i) + 0.5f))] * y[i];
  const Rgb ks = fresnel ? schlickFresnel({specular[0], specular[1], specular[2]}, specular[4], dot(n, toEye))
                         : Rgb{specular[0], specular[1], specular[2]};
  const float k[3] = {ks.r, ks.g, ks.b};
  const int layers = std::min(visibilityLayers, p.rowTexels);
  const std::size_t width = static_cast<std::size_t>(p.rowTexels) * 4;
  for (int c = 0; c < 3; ++c) {
    float sum = 0.0f;
    for (int i = 0; i < rows; ++i) {
      const float* row = &p.texels[(static_cast<std::size_t>(c) * rows + static_cast<std::size_t>(i)) * width];
      float transferred = 0.0f;
      for (int t = 0; t < layers; ++t) {
        const float* pt = row + 4 * t;
        const float* vt = visibility + 4 * t;
        transferred += pt[0] * vt[0] + pt[1] * vt[1] + pt[2] * vt[2] + pt[3] * vt[3];
      }
      sum += gy[i] * transferred;
    }
    out[c] = k[c] * sum;
  }
}

}  // namespace prt::web
