#include "prt/sh_triple_product.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/vec3.h"
#include "prt/wigner3j.h"
#include "support/quadrature.h"
#include "support/sh_reference.h"

namespace prt {
namespace {

constexpr int kN = kMaxTripleProductOrder;
constexpr int kCount = kN * kN;                                           // 64: i, j
constexpr int kCountT = kMaxTripleTransferOrder * kMaxTripleTransferOrder;  // 225: k

// Brute-force reference, independent of the Racah/Wigner route the library takes: textbook SH
// (acos/atan2, explicit Legendre power sums) on a Gauss-Legendre x equispaced-azimuth product
// rule, all in double. 16 nodes in z integrate z-polynomials of degree <= 31 exactly and 32
// azimuths integrate frequencies <= 31 exactly; y_i y_j y_k for l_i, l_j <= 7, l_k <= 14 has
// degree <= 28 and frequency <= 28, so the only error is rounding.
struct BruteForce {
  std::vector<double> weight;
  std::vector<std::vector<double>> basis;  // basis[i][p] = y_i at node p

  BruteForce() : basis(kCountT) {
    std::vector<double> z, w;
    ref::gaussLegendre(16, &z, &w);
    const int nphi = 32;
    for (std::size_t a = 0; a < z.size(); ++a) {
      const double r = std::sqrt(std::fmax(0.0, 1.0 - z[a] * z[a]));
      for (int b = 0; b < nphi; ++b) {
        const double phi = 2.0 * kPi * (b + 0.5) / nphi;
        weight.push_back(w[a] * 2.0 * kPi / nphi);
        for (int l = 0; l < kMaxTripleTransferOrder; ++l) {
          for (int m = -l; m <= l; ++m) {
            basis[shIndex(l, m)].push_back(ref::shTextbook(l, m, r * std::cos(phi), r * std::sin(phi), z[a]));
          }
        }
      }
    }
  }

  double triple(int i, int j, int k) const {
    double s = 0.0;
    for (std::size_t p = 0; p < weight.size(); ++p) s += weight[p] * basis[i][p] * basis[j][p] * basis[k][p];
    return s;
  }

  // Order-n projection of the pointwise product of the functions with coefficients f and g.
  std::vector<double> projectProduct(int order, const std::vector<float>& f, const std::vector<float>& g) const {
    const int n2 = shCoeffCount(order);
    std::vector<double> out(n2, 0.0);
    for (std::size_t p = 0; p < weight.size(); ++p) {
      double fv = 0.0, gv = 0.0;
      for (std::size_t i = 0; i < f.size(); ++i) fv += f[i] * basis[i][p];
      for (std::size_t i = 0; i < g.size(); ++i) gv += g[i] * basis[i][p];
      for (int i = 0; i < n2; ++i) out[i] += weight[p] * fv * gv * basis[i][p];
    }
    return out;
  }
};

const BruteForce& bruteForce() {
  static const BruteForce b;
  return b;
}

// C for every sorted triple a <= b <= c with b < 64, c < 225 by brute force, computed once for
// the tests below; brute() sorts its arguments.
const std::vector<double>& bruteTensor() {
  static const std::vector<double> t = [] {
    std::vector<double> c(static_cast<std::size_t>(kCount) * kCount * kCountT, 0.0);
    for (int k = 0; k < kCountT; ++k) {
      for (int j = 0; j <= k && j < kCount; ++j) {
        for (int i = 0; i <= j; ++i) c[(static_cast<std::size_t>(i) * kCount + j) * kCountT + k] = bruteForce().triple(i, j, k);
      }
    }
    return c;
  }();
  return t;
}

double brute(int i, int j, int k) {
  int s[3] = {i, j, k};
  std::sort(s, s + 3);
  EXPECT_LT(s[1], kCount);
  EXPECT_LT(s[2], kCountT);
  return bruteTensor()[(static_cast<std::size_t>(s[0]) * kCount + s[1]) * kCountT + s[2]];
}

// An exact zero comes out of the quadrature below 1e-14; the smallest true non-zero for
// l <= 7 is 4.8e-3 in magnitude, and 6.7e-5 with the third index up to l = 14.
constexpr double kBruteZero = 1e-9;

ShTripleProduct tensor(int order, int transferOrder = 0) {
  ShTripleProduct t;
  EXPECT_TRUE(ShTripleProduct::make(order, transferOrder == 0 ? order : transferOrder, &t).isOk());
  return t;
}

std::vector<float> randomCoeffs(int count, std::uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<float> c(count);
  for (float& v : c) v = 2.0f * rng.nextFloat() - 1.0f;
  return c;
}

TEST(Wigner3j, KnownValuesAndSelectionRules) {
  // Exact values (sympy.physics.wigner.wigner_3j).
  EXPECT_NEAR(wigner3j(1, 1, 0, 0, 0, 0), -1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(wigner3j(2, 2, 2, 0, 0, 0), -std::sqrt(70.0) / 35.0, 1e-15);
  EXPECT_NEAR(wigner3j(1, 1, 2, 1, -1, 0), std::sqrt(30.0) / 30.0, 1e-15);
  EXPECT_NEAR(wigner3j(7, 7, 14, 3, 4, -7), -7.0 * std::sqrt(86710.0) / 20010.0, 1e-14);
  EXPECT_NEAR(wigner3j(3, 2, 3, 2, 0, -2), 0.0, 1e-15);  // a non-trivial zero
  EXPECT_EQ(wigner3j(2, 2, 2, 1, 1, 1), 0.0);            // m1+m2+m3 != 0
  EXPECT_EQ(wigner3j(1, 1, 3, 0, 0, 0), 0.0);            // triangle
  EXPECT_EQ(wigner3j(1, 1, 1, 2, -2, 0), 0.0);           // |m| > j
  EXPECT_TRUE(std::isnan(wigner3j(kMaxWignerJ + 1, 1, kMaxWignerJ, 0, 0, 0)));
  EXPECT_TRUE(std::isnan(wigner3j(-1, 1, 1, 0, 0, 0)));
}

TEST(Wigner3j, OrthogonalityUpToJ14) {
  // sum_{m1,m2} (j1 j2 j3; m1 m2 m3)^2 = 1/(2 j3 + 1) for each allowed m3: pins the Racah sum's
  // accuracy over the whole range a product of two order-8 functions reaches.
  for (int j1 = 0; j1 <= 7; ++j1) {
    for (int j2 = j1; j2 <= 7; ++j2) {
      for (int j3 = j2 - j1; j3 <= j1 + j2; ++j3) {
        for (int m3 = -j3; m3 <= j3; ++m3) {
          double s = 0.0;
          for (int m1 = -j1; m1 <= j1; ++m1) {
            const double w = wigner3j(j1, j2, j3, m1, -m1 - m3, m3);
            s += w * w;
          }
          ASSERT_NEAR(s, 1.0 / (2 * j3 + 1), 1e-13) << j1 << " " << j2 << " " << j3 << " " << m3;
        }
      }
    }
  }
}

TEST(ShTripleProduct, EntriesMatchBruteForceQuadratureForEveryOrder) {
  // Tolerance: both sides are exact up to double rounding. Observed worst: 2e-14 with every
  // l <= 7, 4e-13 with the third index up to l = 14 (the textbook Legendre power sums and the
  // Racah sums both cancel more there), hence 1e-12 and 1e-11. A wrong sign, phase or
  // normalisation is off by at least the smallest non-zero, 6.7e-5.
  for (int order = 1; order <= kN; ++order) {
    for (int transferOrder : {order, 2 * order - 1}) {
      const ShTripleProduct t = tensor(order, transferOrder);
      const int n2 = shCoeffCount(order), m2 = shCoeffCount(transferOrder);
      const double tolerance = transferOrder <= kN ? 1e-12 : 1e-11;
      double worst = 0.0;
      for (int i = 0; i < n2; ++i) {
        for (int j = 0; j < n2; ++j) {
          for (int k = 0; k < m2; ++k) worst = std::max(worst, std::fabs(t.at(i, j, k) - brute(i, j, k)));
        }
      }
      EXPECT_LT(worst, tolerance) << "order " << order << " transfer order " << transferOrder;
      for (const ShTripleEntry& e : t.entries()) {
        ASSERT_LE(e.i, e.j);
        ASSERT_LE(e.j, e.k);
        ASSERT_LT(e.j, n2);
        ASSERT_LT(e.k, m2);
        EXPECT_NEAR(e.value, brute(e.i, e.j, e.k), tolerance);
      }
    }
  }
}

TEST(ShTripleProduct, NonZeroCountsMatchBruteForceCounts) {
  // Canonical (i <= j <= k) and all ordered non-zeros (i, j < n^2, k < m^2) per order n = 1..8,
  // for m = n and m = 2n-1; recorded in docs/triple-product.md.
  const std::size_t canonical[kN] = {1, 4, 25, 77, 238, 549, 1196, 2300};
  const std::size_t ordered[kN] = {1, 10, 83, 353, 1158, 2907, 6460, 12868};
  const std::size_t canonicalWide[kN] = {1, 12, 69, 271, 796, 1949, 4190, 8164};
  const std::size_t orderedWide[kN] = {1, 21, 162, 708, 2229, 5605, 12322, 24366};
  for (int order = 1; order <= kN; ++order) {
    for (int transferOrder : {order, 2 * order - 1}) {
      const int n2 = shCoeffCount(order), m2 = shCoeffCount(transferOrder);
      std::size_t bruteCanonical = 0, bruteOrdered = 0;
      for (int i = 0; i < n2; ++i) {
        for (int j = 0; j < n2; ++j) {
          for (int k = 0; k < m2; ++k) {
            if (std::fabs(brute(i, j, k)) <= kBruteZero) continue;
            ++bruteOrdered;
            // The canonical form of this triple is stored once; count it at its sorted slot.
            int s[3] = {i, j, k};
            std::sort(s, s + 3);
            if (s[0] == i && s[1] == j && s[2] == k) ++bruteCanonical;
          }
        }
      }
      const ShTripleProduct t = tensor(order, transferOrder);
      std::vector<ShTripleEntry> all;
      t.expand(&all);
      EXPECT_EQ(t.entries().size(), bruteCanonical) << "order " << order << " transfer order " << transferOrder;
      EXPECT_EQ(all.size(), bruteOrdered) << "order " << order << " transfer order " << transferOrder;
      const bool square = transferOrder == order;
      EXPECT_EQ(t.entries().size(), (square ? canonical : canonicalWide)[order - 1])
          << "order " << order << " transfer order " << transferOrder;
      EXPECT_EQ(all.size(), (square ? ordered : orderedWide)[order - 1])
          << "order " << order << " transfer order " << transferOrder;
    }
  }
}

TEST(ShTripleProduct, EveryViewIsARestrictionOfTheLargest) {
  const ShTripleProduct top = tensor(kN, kMaxTripleTransferOrder);
  for (int order = 1; order <= kN; ++order) {
    for (int transferOrder = order; transferOrder <= 2 * order - 1; ++transferOrder) {
      const ShTripleProduct t = tensor(order, transferOrder);
      std::vector<ShTripleEntry> want;
      for (const ShTripleEntry& e : top.entries()) {
        if (e.j < shCoeffCount(order) && e.k < shCoeffCount(transferOrder)) want.push_back(e);
      }
      ASSERT_EQ(t.entries().size(), want.size());
      for (std::size_t e = 0; e < want.size(); ++e) {
        ASSERT_EQ(t.entries()[e].i, want[e].i);
        ASSERT_EQ(t.entries()[e].j, want[e].j);
        ASSERT_EQ(t.entries()[e].k, want[e].k);
        ASSERT_EQ(t.entries()[e].value, want[e].value);
      }
    }
  }
}

TEST(ShTripleProduct, SymmetricUnderEveryIndexPermutation) {
  const ShTripleProduct t = tensor(kN);
  for (int i = 0; i < kCount; ++i) {
    for (int j = 0; j < kCount; ++j) {
      for (int k = 0; k < kCount; ++k) {
        const double v = t.at(i, j, k);
        ASSERT_EQ(v, t.at(i, k, j));
        ASSERT_EQ(v, t.at(j, i, k));
        ASSERT_EQ(v, t.at(j, k, i));
        ASSERT_EQ(v, t.at(k, i, j));
        ASSERT_EQ(v, t.at(k, j, i));
      }
    }
  }
  EXPECT_EQ(t.at(-1, 0, 0), 0.0);
  EXPECT_EQ(t.at(0, 0, kCount), 0.0);
  EXPECT_EQ(tensor(2).at(0, 4, 4), 0.0);     // index outside order 2
  EXPECT_EQ(tensor(2, 3).at(4, 4, 0), 0.0);  // two indices outside the order
  EXPECT_NE(tensor(2, 3).at(1, 1, 6), 0.0);  // one within the transfer order: y_1,-1^2 has a y_20 part
  EXPECT_EQ(tensor(2, 3).at(6, 1, 1), tensor(2, 3).at(1, 6, 1));
}

TEST(ShTripleProduct, ExpandedLayoutIsSortedByProductCell) {
  for (int transferOrder : {5, 9}) {
    const ShTripleProduct t = tensor(5, transferOrder);
    std::vector<ShTripleEntry> all;
    t.expand(&all);
    const auto key = [](const ShTripleEntry& x) { return (x.i * 256 + x.k) * 256 + x.j; };
    for (std::size_t e = 1; e < all.size(); ++e) ASSERT_LT(key(all[e - 1]), key(all[e]));
    for (const ShTripleEntry& e : all) {
      ASSERT_LT(e.i, 25);
      ASSERT_LT(e.j, 25);
      ASSERT_LT(e.k, shCoeffCount(transferOrder));
      EXPECT_EQ(e.value, t.at(e.i, e.j, e.k));
    }
  }
}

TEST(ShTripleProduct, DcRowIsIdentityOverSqrt4Pi) {
  const ShTripleProduct t = tensor(kN);
  const double c = 1.0 / std::sqrt(4.0 * kPi);
  for (int j = 0; j < kCount; ++j) {
    for (int k = 0; k < kCount; ++k) EXPECT_NEAR(t.at(0, j, k), j == k ? c : 0.0, 1e-15) << j << " " << k;
  }
}

TEST(ShTripleProduct, ZeroWhereParityOrTriangleRulesForbid) {
  const ShTripleProduct t = tensor(kN, kMaxTripleTransferOrder);
  int forbidden = 0;
  for (int i = 0; i < kCount; ++i) {
    for (int j = 0; j < kCount; ++j) {
      for (int k = 0; k < kCountT; ++k) {
        const int a = shBandOf(i), b = shBandOf(j), c = shBandOf(k);
        if ((a + b + c) % 2 == 0 && c <= a + b && c >= std::abs(a - b)) continue;
        ++forbidden;
        ASSERT_EQ(t.at(i, j, k), 0.0) << i << " " << j << " " << k;
        ASSERT_LT(std::fabs(brute(i, j, k)), kBruteZero);  // the rules hold for the reference too
      }
    }
  }
  EXPECT_GT(forbidden, kCount * kCount * kCountT / 2);
  for (const ShTripleEntry& e : t.entries()) {
    const int a = shBandOf(e.i), b = shBandOf(e.j), c = shBandOf(e.k);
    EXPECT_EQ((a + b + c) % 2, 0);
    EXPECT_LE(c, a + b);
  }
}

TEST(ShTripleProduct, StoredEntriesObeyTheAzimuthalRules) {
  // The azimuthal integral of cos/sin(|m| phi) factors vanishes unless one |m| is the sum of the
  // other two and the number of sine factors (m < 0) is even.
  const ShTripleProduct t = tensor(kN, kMaxTripleTransferOrder);
  for (const ShTripleEntry& e : t.entries()) {
    int m[3], negatives = 0;
    const int idx[3] = {e.i, e.j, e.k};
    for (int a = 0; a < 3; ++a) {
      const int l = shBandOf(idx[a]);
      m[a] = idx[a] - l * (l + 1);
      negatives += m[a] < 0;
      m[a] = std::abs(m[a]);
    }
    EXPECT_EQ(negatives % 2, 0) << e.i << " " << e.j << " " << e.k;
    EXPECT_TRUE(m[0] == m[1] + m[2] || m[1] == m[0] + m[2] || m[2] == m[0] + m[1]) << e.i << " " << e.j << " " << e.k;
  }
}

TEST(ShTripleProduct, ProductMatrixProjectsThePointwiseProduct) {
  // (P t)_i against the quadrature projection of L(w) t(w). Float P and float sums of at most
  // a few hundred O(1) terms: 1e-5 relative to the largest coefficient.
  for (int order = 1; order <= kN; ++order) {
    for (int transferOrder : {order, 2 * order - 1}) {
      const ShTripleProduct t = tensor(order, transferOrder);
      const int n2 = shCoeffCount(order), m2 = shCoeffCount(transferOrder);
      for (int lightingOrder = 1; lightingOrder <= order; ++lightingOrder) {
        const std::vector<float> light = randomCoeffs(shCoeffCount(lightingOrder), 100 + order * 10 + lightingOrder);
        const std::vector<float> transfer = randomCoeffs(m2, 7 + order);
        std::vector<float> p(static_cast<std::size_t>(n2) * m2);
        ASSERT_TRUE(t.productMatrix(lightingOrder, light, p).isOk());
        const std::vector<double> want = bruteForce().projectProduct(order, light, transfer);
        double scale = 0.0;
        for (double v : want) scale = std::max(scale, std::fabs(v));
        std::vector<float> viaMultiply(n2);
        std::vector<float> lightPadded = light;
        lightPadded.resize(n2, 0.0f);
        ASSERT_TRUE(t.multiply(lightPadded, transfer, viaMultiply).isOk());
        for (int i = 0; i < n2; ++i) {
          double got = 0.0;
          for (int k = 0; k < m2; ++k) got += p[i * m2 + k] * transfer[k];
          EXPECT_NEAR(got, want[i], 1e-5 * scale) << "order " << order << " lighting order " << lightingOrder;
          EXPECT_NEAR(viaMultiply[i], want[i], 1e-6 * scale) << "order " << order;
        }
        if (transferOrder == order) {
          for (int i = 0; i < n2 * n2; ++i) ASSERT_EQ(p[i], p[(i % n2) * n2 + i / n2]);
        }
      }
    }
  }
}

TEST(ShTripleProduct, TransferOfOrder2nMinus1MakesTheProductExact) {
  // The order-n projection of L t for a transfer t with more bands than 2n-1 equals the
  // product with t truncated to 2n-1 bands: the higher bands cannot reach the first n. With
  // t truncated to n bands (the square tensor) it does not, which is the truncation TPFL
  // takes when a texel stores only n^2 coefficients.
  for (int order = 2; order <= 7; ++order) {
    const int n2 = shCoeffCount(order), wide = shCoeffCount(2 * order - 1);
    const std::vector<float> light = randomCoeffs(n2, 500 + order);
    const std::vector<float> transfer = randomCoeffs(shCoeffCount(2 * order), 600 + order);  // 2n bands
    const std::vector<double> want = bruteForce().projectProduct(order, light, transfer);
    double scale = 0.0;
    for (double v : want) scale = std::max(scale, std::fabs(v));
    std::vector<float> exact(n2), truncated(n2);
    const ShTripleProduct t = tensor(order, 2 * order - 1);
    ASSERT_TRUE(t.multiply(light, std::span<const float>(transfer.data(), wide), exact).isOk());
    ASSERT_TRUE(tensor(order).multiply(light, std::span<const float>(transfer.data(), n2), truncated).isOk());
    double truncationError = 0.0;
    for (int i = 0; i < n2; ++i) {
      EXPECT_NEAR(exact[i], want[i], 1e-6 * scale) << "order " << order;
      truncationError = std::max(truncationError, std::fabs(truncated[i] - want[i]));
    }
    EXPECT_GT(truncationError, 1e-2 * scale) << "order " << order;
  }
}

TEST(ShTripleProduct, MultiplyingByAConstantScales) {
  const float s = 1.75f;
  for (int order = 1; order <= kN; ++order) {
    for (int transferOrder : {order, 2 * order - 1}) {
      const ShTripleProduct t = tensor(order, transferOrder);
      const int n2 = shCoeffCount(order), m2 = shCoeffCount(transferOrder);
      // The constant function s has the single coefficient s sqrt(4pi).
      std::vector<float> constant(n2, 0.0f);
      constant[0] = static_cast<float>(s * std::sqrt(4.0 * kPi));
      const std::vector<float> f = randomCoeffs(m2, 99 + order);
      std::vector<float> out(n2);
      ASSERT_TRUE(t.multiply(constant, f, out).isOk());
      for (int i = 0; i < n2; ++i) EXPECT_NEAR(out[i], s * f[i], 1e-6);
      std::vector<float> p(static_cast<std::size_t>(n2) * m2);
      ASSERT_TRUE(t.productMatrix(1, std::span<const float>(constant.data(), 1), p).isOk());
      for (int i = 0; i < n2; ++i) {
        for (int k = 0; k < m2; ++k) EXPECT_NEAR(p[i * m2 + k], i == k ? s : 0.0f, 1e-6);
      }
    }
  }
}

TEST(ShTripleProduct, RejectsInvalidOrdersAndInputs) {
  ShTripleProduct t;
  for (int order : {0, -1, kN + 1, 1 << 30}) {
    const Status s = ShTripleProduct::make(order, &t);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << order;
    EXPECT_NE(s.message().find(std::to_string(order)), std::string::npos) << s.message();
  }
  EXPECT_EQ(ShTripleProduct::make(3, nullptr).code(), StatusCode::kInvalidArgument);
  std::vector<float> p(81), light(9, 0.5f), f(9, 0.5f), out(9);
  EXPECT_EQ(ShTripleProduct::make(3, 2, &t).code(), StatusCode::kInvalidArgument);  // below the order
  EXPECT_EQ(ShTripleProduct::make(3, 6, &t).code(), StatusCode::kInvalidArgument);  // above 2n-1
  EXPECT_EQ(ShTripleProduct::make(8, 16, &t).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(ShTripleProduct::make(2, 3, &t).isOk());
  std::vector<float> wide(9, 0.25f), narrow(4, 0.25f), small(4);
  EXPECT_TRUE(t.multiply(narrow, wide, small).isOk());
  EXPECT_EQ(t.multiply(narrow, narrow, small).code(), StatusCode::kSizeMismatch);  // b needs 3^2
  EXPECT_EQ(t.productMatrix(2, narrow, std::span<float>(p.data(), 35)).code(), StatusCode::kSizeMismatch);
  EXPECT_TRUE(t.productMatrix(2, narrow, std::span<float>(p.data(), 36)).isOk());
  t = ShTripleProduct();
  EXPECT_EQ(t.productMatrix(1, light, p).code(), StatusCode::kInvalidArgument);  // not made
  EXPECT_EQ(t.multiply(f, f, out).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(ShTripleProduct::make(3, &t).isOk());
  EXPECT_TRUE(t.productMatrix(3, light, p).isOk());
  EXPECT_EQ(t.productMatrix(0, light, p).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(t.productMatrix(4, light, p).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(t.productMatrix(3, std::span<const float>(light.data(), 8), p).code(), StatusCode::kSizeMismatch);
  EXPECT_EQ(t.productMatrix(3, light, std::span<float>(p.data(), 80)).code(), StatusCode::kSizeMismatch);
  EXPECT_EQ(t.multiply(std::span<const float>(f.data(), 8), f, out).code(), StatusCode::kSizeMismatch);
  EXPECT_EQ(t.multiply(f, f, std::span<float>(out.data(), 8)).code(), StatusCode::kSizeMismatch);
  light[4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(t.productMatrix(3, light, p).code(), StatusCode::kNotFinite);
  f[8] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(t.multiply(out, f, out).code(), StatusCode::kNotFinite);
}

}  // namespace
}  // namespace prt
