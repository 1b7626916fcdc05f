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
  const int bands = static_cast<int>(std::lround(std::sqrt(static_cast<double>(lighting.size()))));
  if (bands < 1 || bands > order || static_cast<std::size_t>(bands * bands) != lighting.size()) {
    return Status::error(StatusCode::kInvalidArgument, "glossy radiance: " + std::to_string(lighting.size()) +
                                                           " lighting coefficients for an order-" + std::to_string(order) + " matrix");
  }
  const std::size_t vertices = positions.size();
  const std::size_t entries = matrixEntryCount(order, packing);
  if (normals.size() != vertices || specular.size() != vertices || out.size() != 3 * vertices ||
      matrices.size() != vertices * static_cast<std::size_t>(channels) * entries) {
    return Status::error(StatusCode::kSizeMismatch, "glossy radiance: matrix, geometry, material and output sizes disagree");
  }
  if (!isFinite(view.eye)) return Status::error(StatusCode::kNotFinite, "glossy radiance: eye is not finite");
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
    const Rgb ks = view.includeFresnel ? schlickFresnel(m.f0, dot(n, toEye)) : m.f0;
    const float k[3] = {ks.r, ks.g, ks.b};
    for (int c = 0; c < 3; ++c) {
      const int matrixChannel = channels == 3 ? c : 0;
      const float* packed = &matrices[(v * channels + matrixChannel) * entries];
      for (std::size_t j = 0; j < rows; ++j) {
        light[j] = static_cast<Acc>(c == 0 ? lighting[j].r : c == 1 ? lighting[j].g : lighting[j].b);
      }
      applyPacked<Acc>(packed, packing, rows, light.data(), transferred.data());
      Acc sum = 0;
      for (std::size_t i = 0; i < rows; ++i) {
        sum += static_cast<Acc>(scales[static_cast<std::size_t>(shBandOf(static_cast<int>(i)))]) * transferred[i] *
               static_cast<Acc>(basis[i]);
      }
      out[3 * v + c] = static_cast<Acc>(k[c]) * sum;
    }
  }
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

}  // namespace prt
