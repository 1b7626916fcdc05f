#include "prt/cube_sh_weights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "prt/cubemap.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "support/sh_reference.h"

namespace prt {
namespace {

std::vector<float> faceWeights(int order, int size, int face) {
  std::vector<float> w(static_cast<std::size_t>(size) * size * shCoeffCount(order));
  EXPECT_TRUE(cubeShWeightRows(order, size, face, 0, size, w).isOk());
  return w;
}

Vec3 texelDirection(int size, int face, int i, int j) {
  const Vec3 d = cubeFaceDirection(face, 2.0f * (i + 0.5f) / size - 1.0f, 2.0f * (j + 0.5f) / size - 1.0f);
  return d * (1.0f / length(d));
}

TEST(CubeShWeights, RejectsBadArguments) {
  std::vector<float> w(4 * 4 * 9);
  EXPECT_FALSE(cubeShWeightRows(0, 4, 0, 0, 4, w).isOk());
  EXPECT_FALSE(cubeShWeightRows(kMaxShOrder + 1, 4, 0, 0, 4, w).isOk());
  EXPECT_FALSE(cubeShWeightRows(3, 0, 0, 0, 0, w).isOk());
  EXPECT_FALSE(cubeShWeightRows(3, 4, 6, 0, 4, w).isOk());
  EXPECT_FALSE(cubeShWeightRows(3, 4, -1, 0, 4, w).isOk());
  EXPECT_FALSE(cubeShWeightRows(3, 4, 0, 3, 2, w).isOk());
  EXPECT_FALSE(cubeShWeightRows(3, 4, 0, -1, 1, w).isOk());
  const Status small = cubeShWeightRows(3, 4, 0, 0, 4, std::span<float>(w).first(w.size() - 1));
  EXPECT_EQ(small.code(), StatusCode::kSizeMismatch);
  EXPECT_TRUE(cubeShWeightRows(3, 4, 0, 1, 3, w).isOk());
  EXPECT_TRUE(cubeShWeightRows(3, 4, 0, 4, 0, std::span<float>()).isOk());
}

TEST(CubeShWeights, AreTextbookBasisTimesTexelSolidAngle) {
  const int order = 5, size = 9;
  for (int face = 0; face < 6; ++face) {
    const std::vector<float> w = faceWeights(order, size, face);
    for (int j = 0; j < size; j += 4) {
      for (int i = 0; i < size; i += 3) {
        const Vec3 d = texelDirection(size, face, i, j);
        const double area = cubeTexelSolidAngle(size, i, j);
        for (int l = 0; l < order; ++l) {
          for (int m = -l; m <= l; ++m) {
            const double expected = ref::shTextbook(l, m, d.x, d.y, d.z) * area;
            const float got = w[(static_cast<std::size_t>(j) * size + i) * 25 + shIndex(l, m)];
            EXPECT_NEAR(got, expected, 2e-6 * area) << "face " << face << " texel " << i << "," << j << " l" << l << " m" << m;
          }
        }
      }
    }
  }
}

TEST(CubeShWeights, RowRangesTileTheFace) {
  const int order = 3, size = 7;
  const std::vector<float> whole = faceWeights(order, size, kCubeNegY);
  std::vector<float> part(static_cast<std::size_t>(3) * size * 9);
  ASSERT_TRUE(cubeShWeightRows(order, size, kCubeNegY, 2, 3, part).isOk());
  for (std::size_t k = 0; k < part.size(); ++k) EXPECT_EQ(part[k], whole[2 * size * 9 + k]);
}

// The constant function: sum_texels w_0 = 4pi y_0 = 2 sqrt(pi) (the solid angles tile the
// sphere exactly), every other band sums to zero by the cube's symmetry.
TEST(CubeShWeights, ConstantProjectsOntoBandZeroOnly) {
  const int order = 4, size = 16;
  std::vector<double> sum(16, 0.0);
  for (int face = 0; face < 6; ++face) {
    const std::vector<float> w = faceWeights(order, size, face);
    for (std::size_t t = 0; t < w.size(); ++t) sum[t % 16] += w[t];
  }
  EXPECT_NEAR(sum[0], 2.0 * std::sqrt(kPi), 1e-5);
  for (int k = 1; k < 16; ++k) EXPECT_NEAR(sum[k], 0.0, 1e-5) << k;
}

// The weights are a quadrature: sum w_i y_j(dir) approaches the orthonormality integral.
TEST(CubeShWeights, AreANearOrthonormalQuadrature) {
  const int order = 4, size = 64, n = 16;
  std::vector<double> gram(n * n, 0.0);
  std::vector<float> y(n);
  for (int face = 0; face < 6; ++face) {
    const std::vector<float> w = faceWeights(order, size, face);
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        evalShBasisUnchecked(order, texelDirection(size, face, i, j), y.data());
        const float* wt = &w[(static_cast<std::size_t>(j) * size + i) * n];
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) gram[a * n + b] += static_cast<double>(wt[a]) * y[b];
      }
  }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) EXPECT_NEAR(gram[a * n + b], a == b ? 1.0 : 0.0, 2e-3) << a << "," << b;
}

// Reducing a cube map against the table gives projectCubeMap's coefficients.
TEST(CubeShWeights, ReductionMatchesProjectCubeMap) {
  const int order = 5, size = 24, n = 25;
  CubeMap cube;
  cube.size = size;
  Pcg32 rng(7);
  for (auto& face : cube.faces) {
    face.resize(static_cast<std::size_t>(size) * size * 3);
    for (float& v : face) v = rng.nextFloat() < 0.1f ? 20.0f * rng.nextFloat() : rng.nextFloat();
  }
  std::vector<Rgb> expected;
  ASSERT_TRUE(projectCubeMap(order, cube, &expected).isOk());
  std::vector<double> sum(3 * n, 0.0);
  for (int face = 0; face < 6; ++face) {
    const std::vector<float> w = faceWeights(order, size, face);
    for (std::size_t t = 0; t < static_cast<std::size_t>(size) * size; ++t)
      for (int k = 0; k < n; ++k)
        for (int c = 0; c < 3; ++c) sum[3 * k + c] += static_cast<double>(w[t * n + k]) * cube.faces[face][3 * t + c];
  }
  double scale = 0.0;
  for (const Rgb& e : expected) scale = std::max({scale, static_cast<double>(std::fabs(e.r)), static_cast<double>(std::fabs(e.g)), static_cast<double>(std::fabs(e.b))});
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(sum[3 * k], expected[k].r, 1e-5 * scale) << k;
    EXPECT_NEAR(sum[3 * k + 1], expected[k].g, 1e-5 * scale) << k;
    EXPECT_NEAR(sum[3 * k + 2], expected[k].b, 1e-5 * scale) << k;
  }
}

}  // namespace
}  // namespace prt
