#include "prt/glossy_lobe.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "prt/sh_basis.h"

namespace prt {
namespace {

template <typename T>
void bandScales(int order, T s, T* out) {
  // I_l = integral_0^1 t^s P_l(t) dt by the two-step recurrence; g_l = (s+1) I_l.
  T evenPrev = T(1) / (s + T(1)), oddPrev = T(1) / (s + T(2));
  for (int l = 0; l < order; ++l) {
    T value;
    if (l == 0) {
      value = evenPrev;
    } else if (l == 1) {
      value = oddPrev;
    } else {
      T& prev = (l % 2 == 0) ? evenPrev : oddPrev;
      prev = prev * (s - T(l) + T(2)) / (s + T(l) + T(1));
      value = prev;
    }
    out[l] = (s + T(1)) * value;
  }
}

}  // namespace

Status phongLobeBandScales(int order, double s, std::span<double> out) {
  if (Status st = checkShOrder(order); !st.isOk()) return st;
  if (!std::isfinite(s) || s < 0.0) {
    return Status::error(StatusCode::kInvalidArgument, "specular exponent " + std::to_string(s) + " is not finite and >= 0");
  }
  if (out.size() < static_cast<std::size_t>(order)) {
    return Status::error(StatusCode::kSizeMismatch, "phong lobe: output holds fewer than order values");
  }
  bandScales<double>(order, s, out.data());
  return Status::ok();
}

void phongLobeBandScalesUnchecked(int order, float s, float* out) noexcept { bandScales<float>(order, s, out); }

Status specularExponentFromRoughness(double roughness, double maxExponent, double* exponent) {
  if (!(roughness >= 0.0 && roughness <= 1.0)) {
    return Status::error(StatusCode::kInvalidArgument, "roughness " + std::to_string(roughness) + " is outside [0, 1]");
  }
  if (!(maxExponent >= 0.0) || !std::isfinite(maxExponent)) {
    return Status::error(StatusCode::kInvalidArgument, "maximum specular exponent must be finite and >= 0");
  }
  const double alpha = roughness * roughness;
  if (alpha == 0.0) {
    *exponent = maxExponent;
    return Status::ok();
  }
  const double blinn = 2.0 / (alpha * alpha) - 2.0;
  *exponent = std::min(maxExponent, std::max(0.0, blinn / 4.0));
  return Status::ok();
}

Rgb schlickFresnel(Rgb f0, float f90, float cosNormalView) noexcept {
  const float c = std::clamp(cosNormalView, 0.0f, 1.0f);
  const float k = 1.0f - c, k2 = k * k, k5 = k2 * k2 * k;
  return {f0.r + (f90 - f0.r) * k5, f0.g + (f90 - f0.g) * k5, f0.b + (f90 - f0.b) * k5};
}

Vec3 reflectView(Vec3 toEye, Vec3 normal) noexcept { return normal * (2.0f * dot(normal, toEye)) - toEye; }

}  // namespace prt
