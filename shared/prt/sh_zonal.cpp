#include "prt/sh_zonal.h"

#include <cmath>
#include <string>
#include <vector>

#include "prt/sh_basis.h"

namespace prt {
namespace {

Status checkSize(std::size_t have, std::size_t need, const char* what) {
  if (have < need) {
    return Status::error(StatusCode::kSizeMismatch, std::string(what) + " holds " + std::to_string(have) +
                                                        " values, " + std::to_string(need) + " needed");
  }
  return Status::ok();
}

double y_l0_at_pole(int l) { return std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)); }

}  // namespace

Status clampedCosineH(int order, std::span<double> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (Status s = checkSize(out.size(), order, "output"); !s.isOk()) return s;
  double h_even = 1.0;  // H_{2n}
  for (int l = 0; l < order; ++l) {
    if (l == 1) {
      out[l] = 2.0 / 3.0;
    } else if (l % 2 == 1) {
      out[l] = 0.0;
    } else {
      out[l] = h_even;
      const int n = l / 2;
      h_even *= (0.5 - n) / (2.0 + n);
    }
  }
  return Status::ok();
}

Status zonalClampedCosine(int order, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (Status s = checkSize(out.size(), order, "output"); !s.isOk()) return s;
  double h[kMaxShOrder];
  (void)clampedCosineH(order, std::span<double>(h, order));
  for (int l = 0; l < order; ++l) out[l] = static_cast<float>(kPi * h[l] * y_l0_at_pole(l));
  return Status::ok();
}

Status zonalCircularLight(int order, float zeta, float radiance, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (Status s = checkSize(out.size(), order, "output"); !s.isOk()) return s;
  if (!std::isfinite(zeta) || !(zeta > 0.0f) || zeta > static_cast<float>(kPi)) {
    return Status::error(StatusCode::kInvalidArgument, "circular light radius must be in (0, pi] radians");
  }
  if (!std::isfinite(radiance)) return Status::error(StatusCode::kNotFinite, "circular light radiance is not finite");
  // f_l(z) = 1/(1-z) int_z^1 P_l(t) dt, eq. 11 recurrence.
  const double z = std::cos(static_cast<double>(zeta));
  double f_prev = 1.0, f = 0.5 * (1.0 + z);
  for (int l = 0; l < order; ++l) {
    double fl;
    if (l == 0) {
      fl = 1.0;
    } else if (l == 1) {
      fl = f;
    } else {
      // f_l from f_{l-1} (= f) and f_{l-2} (= f_prev), eq. 11 with l -> l-1
      const int k = l - 1;
      fl = ((2.0 * k + 1.0) * z * f - (k - 1.0) * f_prev) / (k + 2.0);
      f_prev = f;
      f = fl;
    }
    out[l] = static_cast<float>(radiance * 2.0 * kPi * (1.0 - z) * fl * y_l0_at_pole(l));
  }
  return Status::ok();
}

Status placeZonal(int order, std::span<const float> zonal, Vec3 axis, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (Status s = checkSize(zonal.size(), order, "zonal coefficients"); !s.isOk()) return s;
  float y[kMaxShOrder * kMaxShOrder];
  if (Status s = evalShBasis(order, axis, std::span<float>(y, shCoeffCount(order))); !s.isOk()) return s;
  if (Status s = checkSize(out.size(), shCoeffCount(order), "output"); !s.isOk()) return s;
  for (int l = 0; l < order; ++l) {
    const float scale = static_cast<float>(std::sqrt(4.0 * kPi / (2.0 * l + 1.0))) * zonal[l];
    for (int m = -l; m <= l; ++m) out[shIndex(l, m)] = scale * y[shIndex(l, m)];
  }
  return Status::ok();
}

Status convolveZonal(int order, std::span<const float> kernel, std::span<float> coeffs) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (Status s = checkSize(kernel.size(), order, "kernel"); !s.isOk()) return s;
  if (Status s = checkSize(coeffs.size(), shCoeffCount(order), "coefficients"); !s.isOk()) return s;
  for (int l = 0; l < order; ++l) {
    const float scale = static_cast<float>(std::sqrt(4.0 * kPi / (2.0 * l + 1.0))) * kernel[l];
    for (int m = -l; m <= l; ++m) coeffs[shIndex(l, m)] *= scale;
  }
  return Status::ok();
}

}  // namespace prt
