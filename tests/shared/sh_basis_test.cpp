#include "prt/sh_basis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shared/test_util.h"
#include "support/quadrature.h"
#include "support/sh_reference.h"

namespace prt {
namespace {

TEST(ShBasis, IndexConvention) {
  EXPECT_EQ(shIndex(0, 0), 0);
  EXPECT_EQ(shIndex(1, -1), 1);
  EXPECT_EQ(shIndex(1, 1), 3);
  EXPECT_EQ(shIndex(2, -2), 4);
  EXPECT_EQ(shCoeffCount(5), 25);
  for (int i = 0; i < shCoeffCount(kMaxShOrder); ++i) {
    const int l = shBandOf(i);
    EXPECT_LE(l * l, i);
    EXPECT_LT(i, (l + 1) * (l + 1));
  }
}

TEST(ShBasis, NoCondonShortleyPhaseBandOne) {
  // y(1,-1) = +0.488603 y, y(1,0) = +0.488603 z, y(1,1) = +0.488603 x (Fujita Table 3).
  float y[4];
  ASSERT_TRUE(evalShBasis(2, {0.36f, 0.48f, 0.8f}, y).isOk());
  EXPECT_NEAR(y[0], 0.2820948f, 1e-6f);
  EXPECT_NEAR(y[1], 0.4886025f * 0.48f, 1e-6f);
  EXPECT_NEAR(y[2], 0.4886025f * 0.8f, 1e-6f);
  EXPECT_NEAR(y[3], 0.4886025f * 0.36f, 1e-6f);
}

TEST(ShBasis, MatchesFujitaClosedFormsUpToL4) {
  for (const Vec3& d : test::testDirections(500)) {
    float y[25];
    evalShBasisUnchecked(5, d, y);
    for (int l = 0; l <= 4; ++l)
      for (int m = -l; m <= l; ++m)
        ASSERT_NEAR(y[shIndex(l, m)], ref::shFujitaTable3(l, m, d.x, d.y, d.z), 2e-6)
            << "l=" << l << " m=" << m << " dir=(" << d.x << "," << d.y << "," << d.z << ")";
  }
}

TEST(ShBasis, MatchesTextbookLegendreForEveryBand) {
  const int order = kMaxShOrder;
  std::vector<float> y(shCoeffCount(order));
  for (const Vec3& d : test::testDirections(400)) {
    evalShBasisUnchecked(order, d, y.data());
    for (int l = 0; l < order; ++l) {
      for (int m = -l; m <= l; ++m) {
        const double expected = ref::shTextbook(l, m, d.x, d.y, d.z);
        // float accuracy; basis values grow like sqrt((2l+1)/4pi)
        ASSERT_NEAR(y[shIndex(l, m)], expected, 2e-5 * std::sqrt(2.0 * l + 1.0))
            << "l=" << l << " m=" << m << " dir=(" << d.x << "," << d.y << "," << d.z << ")";
      }
    }
  }
}

TEST(ShBasis, LowerOrdersArePrefixesOfHigherOrders) {
  for (const Vec3& d : test::testDirections(50)) {
    std::vector<float> full(shCoeffCount(kMaxShOrder));
    evalShBasisUnchecked(kMaxShOrder, d, full.data());
    for (int order = 1; order < kMaxShOrder; ++order) {
      std::vector<float> part(shCoeffCount(order));
      evalShBasisUnchecked(order, d, part.data());
      for (int i = 0; i < shCoeffCount(order); ++i) ASSERT_EQ(part[i], full[i]);
    }
  }
}

TEST(ShBasis, BatchedEqualsSingle) {
  const std::vector<Vec3> dirs = test::testDirections(1000);  // spans several internal chunks
  const std::size_t n = dirs.size();
  std::vector<float> x(n), yy(n), z(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = dirs[k].x;
    yy[k] = dirs[k].y;
    z[k] = dirs[k].z;
  }
  for (int order : {1, 2, 3, 5, 8, 12, kMaxShOrder}) {
    std::vector<float> batch(shCoeffCount(order) * n);
    ASSERT_TRUE(evalShBasisBatch(order, x, yy, z, batch).isOk());
    std::vector<float> single(shCoeffCount(order));
    for (std::size_t k = 0; k < n; ++k) {
      evalShBasisUnchecked(order, dirs[k], single.data());
      for (int i = 0; i < shCoeffCount(order); ++i) ASSERT_FLOAT_EQ(batch[i * n + k], single[i]) << order << " " << i;
    }
  }
}

TEST(ShBasis, CheckedEntryNormalisesItsDirection) {
  float a[16], b[16];
  ASSERT_TRUE(evalShBasis(4, {3.0f, -4.0f, 12.0f}, a).isOk());
  evalShBasisUnchecked(4, {3.0f / 13, -4.0f / 13, 12.0f / 13}, b);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(a[i], b[i], 1e-6f);
}

TEST(ShBasis, OrthonormalUnderExactQuadrature) {
  const int order = 12;
  const int n = shCoeffCount(order);
  const auto quad = ref::sphereQuadrature(order + 2);  // exact for degree <= 2*order+3
  std::vector<double> gram(static_cast<std::size_t>(n) * n, 0.0);
  std::vector<float> y(n);
  for (const auto& q : quad) {
    evalShBasisUnchecked(order, q.dir * (1.0f / length(q.dir)), y.data());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j <= i; ++j) gram[i * n + j] += q.weight * y[i] * y[j];
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) ASSERT_NEAR(gram[i * n + j], i == j ? 1.0 : 0.0, 2e-5) << i << "," << j;
}

}  // namespace
}  // namespace prt
