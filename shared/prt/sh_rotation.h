// Rotation of real SH coefficient vectors (Ivanic & Ruedenberg 1996, with their 1998
// corrections), built directly from a 3x3 rotation matrix: no Euler angles, no
// trigonometry, stable for every rotation including gimbal-lock cases.
//
// Semantics: if f has coefficients c, the function rotated by R, f'(u) = f(R^T u), has
// coefficients c' = D(R) c, with D block diagonal, one (2l+1)x(2l+1) orthogonal block per
// band. D(R1 R2) = D(R1) D(R2).
#pragma once

#include <span>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

class ShRotation {
 public:
  // Builds the band matrices for orders up to `order` from rotation `r`. `r` must be
  // finite and orthonormal with det +1 within 1e-3; otherwise an error naming the problem.
  static Status make(int order, const Mat3& r, ShRotation* out);

  int order() const { return order_; }
  // Entry D^l_{mn}, -l <= m, n <= l, l < order. Unchecked.
  float at(int l, int m, int n) const { return values_[offset(l) + (m + l) * (2 * l + 1) + (n + l)]; }

  // out = D in, for one channel; in.size() and out.size() >= order*order; in and out
  // must not overlap.
  Status apply(std::span<const float> in, std::span<float> out) const;
  // Same for RGB coefficient vectors.
  Status apply(std::span<const Rgb> in, std::span<Rgb> out) const;

 private:
  template <typename T>
  Status applyTo(std::span<const T> in, std::span<T> out) const;
  static int offset(int l) { return l * (2 * l - 1) * (2 * l + 1) / 3; }  // sum_{k<l} (2k+1)^2
  int order_ = 0;
  std::vector<float> values_;
};

}  // namespace prt
