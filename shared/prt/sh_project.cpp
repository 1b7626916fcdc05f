#include "prt/sh_project.h"

#include <cmath>
#include <string>

#include "prt/sh_basis.h"

namespace prt {

Status ShProjector::make(int order, ShProjector* out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  out->order_ = order;
  out->pending_ = 0;
  out->weightSum_ = 0.0;
  for (auto* v : {&out->x_, &out->y_, &out->z_, &out->r_, &out->g_, &out->b_}) v->assign(kBatch, 0.0f);
  out->basis_.assign(static_cast<std::size_t>(shCoeffCount(order)) * kBatch, 0.0f);
  out->sum_.assign(static_cast<std::size_t>(shCoeffCount(order)) * 3, 0.0);
  return Status::ok();
}

void ShProjector::add(Vec3 d, Rgb value, double weight) {
  const float w = static_cast<float>(weight);
  x_[pending_] = d.x;
  y_[pending_] = d.y;
  z_[pending_] = d.z;
  r_[pending_] = value.r * w;
  g_[pending_] = value.g * w;
  b_[pending_] = value.b * w;
  weightSum_ += weight;
  if (++pending_ == kBatch) flush();
}

void ShProjector::flush() {
  if (pending_ == 0) return;
  const std::size_t n = pending_;
  evalShBasisBatchUnchecked(order_, n, x_.data(), y_.data(), z_.data(), basis_.data());
  for (int c = 0; c < shCoeffCount(order_); ++c) {
    const float* __restrict yb = basis_.data() + static_cast<std::size_t>(c) * n;
    float sr = 0.0f, sg = 0.0f, sb = 0.0f;
    for (std::size_t k = 0; k < n; ++k) {
      sr += yb[k] * r_[k];
      sg += yb[k] * g_[k];
      sb += yb[k] * b_[k];
    }
    sum_[c * 3 + 0] += sr;
    sum_[c * 3 + 1] += sg;
    sum_[c * 3 + 2] += sb;
  }
  pending_ = 0;
}

std::vector<Rgb> ShProjector::coefficients() {
  flush();
  std::vector<Rgb> out(static_cast<std::size_t>(shCoeffCount(order_)));
  for (std::size_t c = 0; c < out.size(); ++c) {
    out[c] = {static_cast<float>(sum_[c * 3]), static_cast<float>(sum_[c * 3 + 1]), static_cast<float>(sum_[c * 3 + 2])};
  }
  return out;
}

Status projectSamples(int order, const DirectionSet& dirs, std::span<const Rgb> values, std::vector<Rgb>* out) {
  ShProjector p;
  if (Status s = ShProjector::make(order, &p); !s.isOk()) return s;
  if (dirs.y.size() != dirs.size() || dirs.z.size() != dirs.size() || values.size() != dirs.size()) {
    return Status::error(StatusCode::kSizeMismatch, "direction set has " + std::to_string(dirs.size()) +
                                                        " directions but " + std::to_string(values.size()) +
                                                        " values");
  }
  if (!std::isfinite(dirs.weight)) return Status::error(StatusCode::kNotFinite, "sample weight is not finite");
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const Vec3 d = dirs.at(k);
    const float l2 = dot(d, d);
    if (!std::isfinite(l2) || std::fabs(l2 - 1.0f) > 1e-3f) {
      return Status::error(StatusCode::kInvalidArgument, "direction " + std::to_string(k) + " is not a finite unit vector");
    }
    p.add(d, values[k], dirs.weight);
  }
  *out = p.coefficients();
  return Status::ok();
}

Status projectEquirect(int order, const RgbImage& image, std::vector<Rgb>* out) {
  ShProjector p;
  if (Status s = ShProjector::make(order, &p); !s.isOk()) return s;
  if (Status s = checkImage(image, "equirectangular image"); !s.isOk()) return s;
  const double dphi = 2.0 * kPi / image.width;
  for (int j = 0; j < image.height; ++j) {
    const double latTop = 0.5 * kPi - kPi * j / image.height;
    const double latBottom = 0.5 * kPi - kPi * (j + 1) / image.height;
    const double lat = 0.5 * (latTop + latBottom);
    const double weight = dphi * (std::sin(latTop) - std::sin(latBottom));
    const double cl = std::cos(lat), sl = std::sin(lat);
    for (int i = 0; i < image.width; ++i) {
      const double phi = 2.0 * kPi * ((i + 0.5) / image.width - 0.5);
      const Vec3 d{static_cast<float>(cl * std::cos(phi)), static_cast<float>(sl), static_cast<float>(cl * std::sin(phi))};
      p.add(d, image.at(i, j), weight);
    }
  }
  *out = p.coefficients();
  return Status::ok();
}

Status projectAngularMap(int order, const RgbImage& image, std::vector<Rgb>* out) {
  ShProjector p;
  if (Status s = ShProjector::make(order, &p); !s.isOk()) return s;
  if (Status s = checkImage(image, "angular map"); !s.isOk()) return s;
  if (image.width != image.height) {
    return Status::error(StatusCode::kInvalidArgument, "angular map must be square, got " + std::to_string(image.width) +
                                                           "x" + std::to_string(image.height));
  }
  const int n = image.width;
  constexpr int kSub = 4;
  const double cell = 2.0 / n, subArea = (cell / kSub) * (cell / kSub);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      double weight = 0.0;
      for (int sj = 0; sj < kSub; ++sj) {
        for (int si = 0; si < kSub; ++si) {
          const double u = -1.0 + cell * (i + (si + 0.5) / kSub);
          const double v = 1.0 - cell * (j + (sj + 0.5) / kSub);
          const double r = std::sqrt(u * u + v * v);
          if (r > 1.0) continue;
          weight += (r > 1e-12 ? kPi * std::sin(kPi * r) / r : kPi * kPi) * subArea;
        }
      }
      if (weight <= 0.0) continue;
      const double u = -1.0 + cell * (i + 0.5), v = 1.0 - cell * (j + 0.5);
      double r = std::sqrt(u * u + v * v);
      Vec3 d{0.0f, 0.0f, 1.0f};
      if (r > 1e-12) {
        const double theta = kPi * std::fmin(r, 1.0);
        const double s = std::sin(theta) / r;
        d = {static_cast<float>(s * u), static_cast<float>(s * v), static_cast<float>(std::cos(theta))};
        d = d * (1.0f / length(d));
      }
      p.add(d, image.at(i, j), weight);
    }
  }
  *out = p.coefficients();
  return Status::ok();
}

Status projectCubeMap(int order, const CubeMap& cube, std::vector<Rgb>* out) {
  ShProjector p;
  if (Status s = ShProjector::make(order, &p); !s.isOk()) return s;
  if (Status s = checkCubeMap(cube); !s.isOk()) return s;
  const int n = cube.size;
  std::vector<double> solidAngle(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) solidAngle[static_cast<std::size_t>(j) * n + i] = cubeTexelSolidAngle(n, i, j);
  for (int face = 0; face < 6; ++face) {
    const float* texels = cube.faces[face].data();
    for (int j = 0; j < n; ++j) {
      const float t = 2.0f * (j + 0.5f) / n - 1.0f;
      for (int i = 0; i < n; ++i) {
        const float s = 2.0f * (i + 0.5f) / n - 1.0f;
        Vec3 d = cubeFaceDirection(face, s, t);
        d = d * (1.0f / length(d));
        const std::size_t k = static_cast<std::size_t>(j) * n + i;
        p.add(d, {texels[k * 3], texels[k * 3 + 1], texels[k * 3 + 2]}, solidAngle[k]);
      }
    }
  }
  *out = p.coefficients();
  return Status::ok();
}

Status evalShExpansion(int order, std::span<const Rgb> coeffs, Vec3 dir, Rgb* out) {
  float y[kMaxShOrder * kMaxShOrder];
  if (Status s = evalShBasis(order, dir, std::span<float>(y, kMaxShOrder * kMaxShOrder)); !s.isOk()) return s;
  if (coeffs.size() < static_cast<std::size_t>(shCoeffCount(order))) {
    return Status::error(StatusCode::kSizeMismatch, "expansion needs " + std::to_string(shCoeffCount(order)) + " coefficients");
  }
  Rgb acc;
  for (int i = 0; i < shCoeffCount(order); ++i) acc = acc + coeffs[i] * y[i];
  *out = acc;
  return Status::ok();
}

}  // namespace prt
