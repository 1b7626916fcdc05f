#include "prt/glossy_radiance.h"

#include <cmath>
#include <string>
#include <vector>

#include "prt/sh_basis.h"

namespace prt {
namespace {

// out = M v over the leading `rows` rows and columns, accumulated in Acc, walking the packed
// array in storage order (prt/transfer_matrix.h) rather than indexing entry by entry.
template <typename Acc>
void applyPacked(const float* packed, MatrixPacking packing, std::size_t rows, const Acc* v, Acc* out) {
  for (std::size_t i = 0; i < rows; ++i) out[i] = 0;
  if (packing == MatrixPacking::kSymmetric) {
    for (std::size_t i = 0; i < rows; ++i) {
      const float* row = packed + i * (i + 1) / 2;
      for (std::size_t j = 0; j < i; ++j) {
        out[i] += static_cast<Acc>(row[j]) * v[j];
        out[j] += static_cast<Acc>(row[j]) * v[i];
      }
      out[i] += static_cast<Acc>(row[i]) * v[i];
    }
    return;
  }
  for (std::size_t k = 0; k < rows; ++k) {
    const float* shell = packed + k * k;
    for (std::size_t j = 0; j < k; ++j) out[k] += static_cast<Acc>(shell[j]) * v[j];
    for (std::size_t i = 0; i < k; ++i) out[i] += static_cast<Acc>(shell[k + i]) * v[k];
    out[k] += static_cast<Acc>(shell[2 * k]) * v[k];
  }
}

// The lobe half, shared by the matrix and the TPFL forms: for each vertex and channel c,
// transfer(v, c, light_c, out) writes the transferred incident radiance T_c (rows
// coefficients) and the exit radiance is k_s,c sum_i g_l(i) T_c,i y_i(R).
template <typename Acc, typename Transfer>
void glossyCore(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const SpecularMaterial> specular,
                const GlossyView& view, std::span<const Rgb> lighting, int bands, Transfer transfer, std::span<Acc> out) {
  const std::size_t vertices = positions.size();
  const std::size_t rows = static_cast<std::size_t>(bands) * bands;
  std::vector<Acc> light(rows), transferred(rows);
  std::vector<float> basis(rows), scales(static_cast<std::size_t>(bands));
  for (std::size_t v = 0; v < vertices; ++v) {
    const Vec3 d = view.eye - positions[v];
    const float distance = length(d);
    const SpecularMaterial& m = specular[v];
    if (!(distance > 0.0f) || !std::isfinite(m.exponent) || m.exponent < 0.0f) {
      out[3 * v] = out[3 * v + 1] = out[3 * v + 2] = 0;
      continue;
    }
    const Vec3 toEye = d * (1.0f / distance);
    const Vec3 n = normals[v];
    Vec3 r = reflectView(toEye, n);
    const float rl = length(r);
    r = rl > 0.0f ? r * (1.0f / rl) : n;
    evalShBasisUnchecked(bands, r, basis.data());
    phongLobeBandScalesUnchecked(bands, m.exponent, scales.data());
    const Rgb ks = view.includeFresnel ? schlickFresnel(m.f0, m.f90, dot(n, toEye)) : m.f0;
    const float k[3] = {ks.r, ks.g, ks.b};
    for (int c = 0; c < 3; ++c) {
      for (std::size_t j = 0; j < rows; ++j) {
        light[j] = static_cast<Acc>(c == 0 ? lighting[j].r : c == 1 ? lighting[j].g : lighting[j].b);
      }
      transfer(v, c, light.data(), transferred.data());
      Acc sum = 0;
      for (std::size_t i = 0; i < rows; ++i) {
        sum += static_cast<Acc>(scales[static_cast<std::size_t>(shBandOf(static_cast<int>(i)))]) * transferred[i] *
               static_cast<Acc>(basis[i]);
      }
      out[3 * v + c] = static_cast<Acc>(k[c]) * sum;
    }
  }
}

// bands from lighting.size() when it is a square of at most maxBands bands.
Status lightingBands(std::span<const Rgb> lighting, int maxBands, const char* what, int* bands) {
  *bands = static_cast<int>(std::lround(std::sqrt(static_cast<double>(lighting.size()))));
  if (*bands < 1 || *bands > maxBands || static_cast<std::size_t>(*bands * *bands) != lighting.size()) {
    return Status::error(StatusCode::kInvalidArgument, std::string(what) + ": " + std::to_string(lighting.size()) +
                                                           " lighting coefficients for order " + std::to_string(maxBands));
  }
  return Status::ok();
}

template <typename Acc>
Status glossyImpl(std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                  std::span<const Vec3> positions, std::span<const Vec3> normals,
                  std::span<const SpecularMaterial> specular, const GlossyView& view, std::span<const Rgb> lighting,
                  std::span<Acc> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (channels != 1 && channels != 3) {
    return Status::error(StatusCode::kInvalidArgument, "glossy radiance: channels " + std::to_string(channels) + " is not 1 or 3");
  }
  if (packing != MatrixPacking::kSymmetric && packing != MatrixPacking::kFull) {
    return Status::error(StatusCode::kInvalidArgument, "glossy radiance: unknown matrix packing");
  }
  int bands = 0;
  if (Status s = lightingBands(lighting, order, "glossy radiance", &bands); !s.isOk()) return s;
  const std::size_t vertices = positions.size();
  const std::size_t entries = matrixEntryCount(order, packing);
  if (normals.size() != vertices || specular.size() != vertices || out.size() != 3 * vertices ||
      matrices.size() != vertices * static_cast<std::size_t>(channels) * entries) {
    return Status::error(StatusCode::kSizeMismatch, "glossy radiance: matrix, geometry, material and output sizes disagree");
  }
  if (!isFinite(view.eye)) return Status::error(StatusCode::kNotFinite, "glossy radiance: eye is not finite");
  const std::size_t rows = static_cast<std::size_t>(bands) * bands;
  glossyCore<Acc>(positions, normals, specular, view, lighting, bands,
                  [&](std::size_t v, int c, const Acc* light, Acc* transferred) {
                    const int matrixChannel = channels == 3 ? c : 0;
                    const float* packed = &matrices[(v * channels + matrixChannel) * entries];
                    applyPacked<Acc>(packed, packing, rows, light, transferred);
                  },
                  out);
  return Status::ok();
}

}  // namespace

Status glossyExitRadiance(std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                          std::span<const Vec3> positions, std::span<const Vec3> normals,
                          std::span<const SpecularMaterial> specular, const GlossyView& view,
                          std::span<const Rgb> lighting, std::span<float> out) {
  return glossyImpl<float>(matrices, order, packing, channels, positions, normals, specular, view, lighting, out);
}

Status glossyExitRadianceDouble(std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                                std::span<const Vec3> positions, std::span<const Vec3> normals,
                                std::span<const SpecularMaterial> specular, const GlossyView& view,
                                std::span<const Rgb> lighting, std::span<double> out) {
  return glossyImpl<double>(matrices, order, packing, channels, positions, normals, specular, view, lighting, out);
}

Status tpflGlossyExitRadiance(const ShTripleProduct& product, std::span<const float> visibility,
                              std::span<const Vec3> positions, std::span<const Vec3> normals,
                              std::span<const SpecularMaterial> specular, const GlossyView& view,
                              std::span<const Rgb> lighting, std::span<float> out) {
  const int n = product.order(), m = product.transferOrder();
  if (n < 1 || m < n) return Status::error(StatusCode::kInvalidArgument, "TPFL radiance: the product tensor is empty");
  if (static_cast<std::size_t>(n * n) != lighting.size()) {
    return Status::error(StatusCode::kInvalidArgument, "TPFL radiance: " + std::to_string(lighting.size()) +
                                                           " lighting coefficients for an order-" + std::to_string(n) +
                                                           " product");
  }
  const std::size_t vertices = positions.size(), rows = static_cast<std::size_t>(n) * n,
                    cols = static_cast<std::size_t>(m) * m;
  if (normals.size() != vertices || specular.size() != vertices || out.size() != 3 * vertices ||
      visibility.size() != vertices * cols) {
    return Status::error(StatusCode::kSizeMismatch, "TPFL radiance: visibility, geometry, material and output sizes disagree");
  }
  if (!isFinite(view.eye)) return Status::error(StatusCode::kNotFinite, "TPFL radiance: eye is not finite");
  // Per frame: one product matrix per channel (the lighting times any function of order m).
  std::vector<float> channelLight(rows), matrix[3];
  for (int c = 0; c < 3; ++c) {
    for (std::size_t j = 0; j < rows; ++j) channelLight[j] = c == 0 ? lighting[j].r : c == 1 ? lighting[j].g : lighting[j].b;
    matrix[c].resize(rows * cols);
    if (Status s = product.productMatrix(n, channelLight, matrix[c]); !s.isOk()) return s;
  }
  // Per point: P_c V replaces M_c L_c.
  glossyCore<float>(positions, normals, specular, view, lighting, n,
                    [&](std::size_t v, int c, const float*, float* transferred) {
                      const float* vis = &visibility[v * cols];
                      for (std::size_t i = 0; i < rows; ++i) {
                        const float* row = &matrix[c][i * cols];
                        float acc = 0.0f;
                        for (std::size_t k = 0; k < cols; ++k) acc += row[k] * vis[k];
                        transferred[i] = acc;
                      }
                    },
                    out);
  return Status::ok();
}

}  // namespace prt
