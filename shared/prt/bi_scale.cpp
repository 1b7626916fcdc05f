#include "prt/bi_scale.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "prt/sh_rotation.h"

namespace prt {
namespace {

int squareRootOf(std::size_t n) {
  int b = 0;
  while (static_cast<std::size_t>((b + 1) * (b + 1)) <= n) ++b;
  return static_cast<std::size_t>(b * b) == n ? b : -1;
}

}  // namespace

void rttLookup(const Rtt& rtt, float u, float v, Vec3 view, bool viewDependent, float* out) {
  const std::size_t S = static_cast<std::size_t>(rtt.spatial), V = static_cast<std::size_t>(rtt.views);
  const std::size_t per = static_cast<std::size_t>(rtt.channels * rtt.order * rtt.order);
  const float fu = u - std::floor(u), fv = v - std::floor(v);
  const std::size_t x = std::min(S - 1, static_cast<std::size_t>(fu * static_cast<float>(S)));
  const std::size_t y = std::min(S - 1, static_cast<std::size_t>(fv * static_cast<float>(S)));
  const float* block = &rtt.coeffs[(y * S + x) * V * V * per];
  float a = 0.5f * static_cast<float>(V), b = a;  // the centre of the view square: +z
  if (viewDependent) rttViewCoordinates(view, rtt.views, &a, &b);
  // Bilinear between sample centres (a + 0.5, b + 0.5), clamped to the outermost ones.
  const float maxIndex = static_cast<float>(V - 1);
  const float ca = std::clamp(a - 0.5f, 0.0f, maxIndex), cb = std::clamp(b - 0.5f, 0.0f, maxIndex);
  const std::size_t a0 = static_cast<std::size_t>(ca), b0 = static_cast<std::size_t>(cb);
  const std::size_t a1 = std::min(a0 + 1, V - 1), b1 = std::min(b0 + 1, V - 1);
  const float ta = ca - static_cast<float>(a0), tb = cb - static_cast<float>(b0);
  const float* s00 = &block[(b0 * V + a0) * per];
  const float* s10 = &block[(b0 * V + a1) * per];
  const float* s01 = &block[(b1 * V + a0) * per];
  const float* s11 = &block[(b1 * V + a1) * per];
  for (std::size_t q = 0; q < per; ++q) {
    out[q] = (1.0f - tb) * ((1.0f - ta) * s00[q] + ta * s10[q]) + tb * ((1.0f - ta) * s01[q] + ta * s11[q]);
  }
}

Status biScaleExitRadiance(const Rtt& rtt, std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                           std::span<const Vec3> positions, std::span<const TangentFrame> frames, std::span<const float> patchUv,
                           Vec3 eye, bool viewDependent, std::span<const Rgb> lighting, std::span<float> out) {
  const std::size_t P = positions.size();
  if (rtt.coeffCount() == 0 || rtt.coeffs.size() != rtt.coeffCount()) return Status::error(StatusCode::kInvalidArgument, "bi-scale: RTT shape");
  if (order < 1 || order > 16 || (channels != 1 && channels != 3)) return Status::error(StatusCode::kInvalidArgument, "bi-scale: order or channels");
  const int lightBands = squareRootOf(lighting.size());
  if (lightBands < 1) return Status::error(StatusCode::kSizeMismatch, "bi-scale: lighting is not bands^2 coefficients");
  const std::size_t entries = matrixEntryCount(order, packing);
  if (matrices.size() != P * static_cast<std::size_t>(channels) * entries || frames.size() != P || patchUv.size() != 2 * P ||
      out.size() != 3 * P) {
    return Status::error(StatusCode::kSizeMismatch, "bi-scale: per-point arrays disagree with the point count");
  }
  const int bands = std::min({order, rtt.order, lightBands});
  const std::size_t nb = static_cast<std::size_t>(bands * bands);
  const std::size_t rttN = static_cast<std::size_t>(rtt.order * rtt.order);
  std::vector<float> b(static_cast<std::size_t>(rtt.channels) * rttN), world(nb), local(nb), light(nb);
  for (std::size_t p = 0; p < P; ++p) {
    const TangentFrame& f = frames[p];
    const Vec3 bitangent = cross(f.normal, f.tangent);
    Mat3 toLocal;  // rows: tangent, bitangent, normal
    const Vec3 rows[3] = {f.tangent, bitangent, f.normal};
    for (int r = 0; r < 3; ++r) toLocal.m[r][0] = rows[r].x, toLocal.m[r][1] = rows[r].y, toLocal.m[r][2] = rows[r].z;
    ShRotation rotation;
    if (Status s = ShRotation::make(bands, toLocal, &rotation); !s.isOk()) {
      return Status::error(StatusCode::kInvalidArgument, "bi-scale: point " + std::to_string(p) + "'s tangent frame: " + s.message());
    }
    const Vec3 d = eye - positions[p];
    const float distance = length(d);
    if (!(distance > 0.0f)) {
      out[3 * p] = out[3 * p + 1] = out[3 * p + 2] = 0.0f;
      continue;
    }
    const Vec3 view = toLocal * (d * (1.0f / distance));
    rttLookup(rtt, patchUv[2 * p], patchUv[2 * p + 1], view, viewDependent, b.data());
    for (int c = 0; c < 3; ++c) {
      const float* m = &matrices[(p * static_cast<std::size_t>(channels) + (channels == 3 ? static_cast<std::size_t>(c) : 0)) * entries];
      for (std::size_t i = 0; i < nb; ++i) light[i] = c == 0 ? lighting[i].r : (c == 1 ? lighting[i].g : lighting[i].b);
      applyPackedMatrixUnchecked(m, packing, nb, light.data(), world.data());
      (void)rotation.apply(world, local);
      const float* bc = &b[(rtt.channels == 3 ? static_cast<std::size_t>(c) : 0) * rttN];
      float sum = 0.0f;
      for (std::size_t i = 0; i < nb; ++i) sum += bc[i] * local[i];
      out[3 * p + static_cast<std::size_t>(c)] = sum;
    }
  }
  return Status::ok();
}

}  // namespace prt
