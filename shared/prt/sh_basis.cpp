#include "prt/sh_basis.h"

#include <cmath>
#include <string>

namespace prt {
namespace {

// Normalisation K_lm of the real SH without Condon-Shortley phase:
// K_l0 = sqrt((2l+1)/4pi), K_lm = sqrt(2) sqrt((2l+1)/4pi (l-|m|)!/(l+|m|)!).
double shNorm(int l, int m) {
  int am = m < 0 ? -m : m;
  double ratio = 1.0;  // (l-|m|)! / (l+|m|)!
  for (int k = l - am + 1; k <= l + am; ++k) ratio /= k;
  double k2 = (2.0 * l + 1.0) / (4.0 * kPi) * ratio;
  return am == 0 ? std::sqrt(k2) : std::sqrt(2.0 * k2);
}

// Coefficients of Lisle & Huang's recurrence with the normalisation folded in, so each
// basis value comes straight out normalised:
//   interior |m| < l:  y_lm  = a[i] z y_{l-1,m} - b[i] y_{l-2,m}
//   edges:             y_ll  = a[i] (x y_{l-1,l-1} - y y_{l-1,-(l-1)})
//                      y_l-l = a[i] (y y_{l-1,l-1} + x y_{l-1,-(l-1)})
// The edge signs differ from the paper's base case (Y_1,-1 = -y, Y_1,1 = -x) because we
// drop the Condon-Shortley phase: Y_ll ~ Re (x+iy)^l and Y_l,-l ~ Im (x+iy)^l.
struct RecurrenceTable {
  float y00 = 0, k1 = 0;
  float a[kMaxShOrder * kMaxShOrder] = {};
  float b[kMaxShOrder * kMaxShOrder] = {};

  RecurrenceTable() {
    y00 = static_cast<float>(shNorm(0, 0));
    k1 = static_cast<float>(shNorm(1, 0));
    for (int l = 2; l < kMaxShOrder; ++l) {
      for (int m = -l; m <= l; ++m) {
        int am = m < 0 ? -m : m;
        int i = shIndex(l, m);
        if (am == l) {
          a[i] = static_cast<float>((2.0 * l - 1.0) * shNorm(l, m) / shNorm(l - 1, l - 1));
        } else {
          a[i] = static_cast<float>((2.0 * l - 1.0) / (l - am) * shNorm(l, m) / shNorm(l - 1, m));
          b[i] = am <= l - 2
                     ? static_cast<float>((l + am - 1.0) / (l - am) * shNorm(l, m) / shNorm(l - 2, m))
                     : 0.0f;
        }
      }
    }
  }
};

const RecurrenceTable& table() {
  static const RecurrenceTable t;
  return t;
}

// Chunking bounds the working set: each recurrence step re-reads only the rows of bands
// l-1 and l-2 of the current chunk, which were just written and are still in cache.
constexpr std::size_t kBatchChunk = 256;

void evalChunk(int order, std::size_t count, std::size_t stride, const float* __restrict x,
               const float* __restrict y, const float* __restrict z, float* out) {
  const RecurrenceTable& t = table();
  {
    float* __restrict r0 = out;
    for (std::size_t k = 0; k < count; ++k) r0[k] = t.y00;
  }
  if (order == 1) return;
  {
    float* __restrict rm = out + 1 * stride;
    float* __restrict r0 = out + 2 * stride;
    float* __restrict rp = out + 3 * stride;
    const float k1 = t.k1;
    for (std::size_t k = 0; k < count; ++k) {
      rm[k] = k1 * y[k];
      r0[k] = k1 * z[k];
      rp[k] = k1 * x[k];
    }
  }
  for (int l = 2; l < order; ++l) {
    // interior, |m| <= l-2: two-term recurrence in l
    for (int m = -(l - 2); m <= l - 2; ++m) {
      const int i = shIndex(l, m);
      const float a = t.a[i], b = t.b[i];
      float* __restrict dst = out + i * stride;
      const float* __restrict p1 = out + shIndex(l - 1, m) * stride;
      const float* __restrict p2 = out + shIndex(l - 2, m) * stride;
      for (std::size_t k = 0; k < count; ++k) dst[k] = a * z[k] * p1[k] - b * p2[k];
    }
    // |m| = l-1: the y_{l-2,m} term does not exist
    for (int m : {-(l - 1), l - 1}) {
      const int i = shIndex(l, m);
      const float a = t.a[i];
      float* __restrict dst = out + i * stride;
      const float* __restrict p1 = out + shIndex(l - 1, m) * stride;
      for (std::size_t k = 0; k < count; ++k) dst[k] = a * z[k] * p1[k];
    }
    // edges |m| = l
    {
      const float c = t.a[shIndex(l, l)];
      float* __restrict dp = out + shIndex(l, l) * stride;
      float* __restrict dn = out + shIndex(l, -l) * stride;
      const float* __restrict sp = out + shIndex(l - 1, l - 1) * stride;
      const float* __restrict sn = out + shIndex(l - 1, -(l - 1)) * stride;
      for (std::size_t k = 0; k < count; ++k) {
        dp[k] = c * (x[k] * sp[k] - y[k] * sn[k]);
        dn[k] = c * (y[k] * sp[k] + x[k] * sn[k]);
      }
    }
  }
}

}  // namespace

int shBandOf(int index) {
  int l = static_cast<int>(std::sqrt(static_cast<double>(index)));
  while (l * l > index) --l;
  while ((l + 1) * (l + 1) <= index) ++l;
  return l;
}

Status checkShOrder(int order) {
  if (order < kMinShOrder || order > kMaxShOrder) {
    return Status::error(StatusCode::kInvalidArgument,
                         "SH order " + std::to_string(order) + " is outside [" +
                             std::to_string(kMinShOrder) + ", " + std::to_string(kMaxShOrder) + "]");
  }
  return Status::ok();
}

void evalShBasisUnchecked(int order, Vec3 d, float* out) noexcept {
  const RecurrenceTable& t = table();
  out[0] = t.y00;
  if (order == 1) return;
  out[1] = t.k1 * d.y;
  out[2] = t.k1 * d.z;
  out[3] = t.k1 * d.x;
  for (int l = 2; l < order; ++l) {
    const int base = l * (l + 1), base1 = (l - 1) * l, base2 = (l - 2) * (l - 1);
    for (int m = -(l - 2); m <= l - 2; ++m) {
      out[base + m] = t.a[base + m] * d.z * out[base1 + m] - t.b[base + m] * out[base2 + m];
    }
    out[base - (l - 1)] = t.a[base - (l - 1)] * d.z * out[base1 - (l - 1)];
    out[base + (l - 1)] = t.a[base + (l - 1)] * d.z * out[base1 + (l - 1)];
    const float sp = out[base1 + (l - 1)], sn = out[base1 - (l - 1)];
    const float c = t.a[base + l];
    out[base + l] = c * (d.x * sp - d.y * sn);
    out[base - l] = c * (d.y * sp + d.x * sn);
  }
}

Status evalShBasis(int order, Vec3 dir, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (!isFinite(dir)) return Status::error(StatusCode::kNotFinite, "direction has a NaN or infinite component");
  // Scale by the largest component first so tiny or huge (finite) vectors normalise
  // without underflow or overflow.
  const float largest = std::fmax(std::fabs(dir.x), std::fmax(std::fabs(dir.y), std::fabs(dir.z)));
  if (!(largest > 0.0f)) {
    return Status::error(StatusCode::kInvalidArgument, "direction has zero length");
  }
  dir = dir * (1.0f / largest);
  const float len = length(dir);
  if (out.size() < static_cast<std::size_t>(shCoeffCount(order))) {
    return Status::error(StatusCode::kSizeMismatch,
                         "output holds " + std::to_string(out.size()) + " floats, order " +
                             std::to_string(order) + " needs " + std::to_string(shCoeffCount(order)));
  }
  evalShBasisUnchecked(order, dir * (1.0f / len), out.data());
  return Status::ok();
}

void evalShBasisBatchUnchecked(int order, std::size_t count, const float* x, const float* y,
                               const float* z, float* out) noexcept {
  for (std::size_t start = 0; start < count; start += kBatchChunk) {
    const std::size_t n = count - start < kBatchChunk ? count - start : kBatchChunk;
    evalChunk(order, n, count, x + start, y + start, z + start, out + start);
  }
}

Status evalShBasisBatch(int order, std::span<const float> x, std::span<const float> y,
                        std::span<const float> z, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  const std::size_t count = x.size();
  if (y.size() != count || z.size() != count) {
    return Status::error(StatusCode::kSizeMismatch, "x, y and z arrays differ in length");
  }
  const std::size_t needed = static_cast<std::size_t>(shCoeffCount(order)) * count;
  if (count != 0 && needed / count != static_cast<std::size_t>(shCoeffCount(order))) {
    return Status::error(StatusCode::kSizeMismatch, "direction count overflows the output size");
  }
  if (out.size() < needed) {
    return Status::error(StatusCode::kSizeMismatch,
                         "output holds " + std::to_string(out.size()) + " floats, " +
                             std::to_string(needed) + " needed");
  }
  for (std::size_t k = 0; k < count; ++k) {
    const float l2 = x[k] * x[k] + y[k] * y[k] + z[k] * z[k];
    if (!std::isfinite(l2)) {
      return Status::error(StatusCode::kNotFinite, "direction " + std::to_string(k) + " is not finite");
    }
    if (std::fabs(l2 - 1.0f) > 1e-3f) {
      return Status::error(StatusCode::kInvalidArgument,
                           "direction " + std::to_string(k) + " is not unit length (|d|^2 = " +
                               std::to_string(l2) + ")");
    }
  }
  evalShBasisBatchUnchecked(order, count, x.data(), y.data(), z.data(), out.data());
  return Status::ok();
}

}  // namespace prt
