#include "prt/cubemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "support/quadrature.h"

namespace prt {
namespace {

CubeMap makeCube(int size, const std::function<Rgb(int face, Vec3 unitDir)>& f) {
  CubeMap cube;
  cube.size = size;
  for (int face = 0; face < 6; ++face) {
    cube.faces[face].resize(static_cast<std::size_t>(size) * size * 3);
    for (int j = 0; j < size; ++j) {
      for (int i = 0; i < size; ++i) {
        Vec3 d = cubeFaceDirection(face, 2.0f * (i + 0.5f) / size - 1.0f, 2.0f * (j + 0.5f) / size - 1.0f);
        const Rgb c = f(face, d * (1.0f / length(d)));
        float* p = &cube.faces[face][(static_cast<std::size_t>(j) * size + i) * 3];
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
      }
    }
  }
  return cube;
}

TEST(CubeMap, FaceDirectionsFollowTheGlTable) {
  // Face centres point along their axes, and the GL (sc, tc, ma) table's orientation.
  const Vec3 centres[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const Vec3 d = cubeFaceDirection(f, 0, 0);
    EXPECT_EQ(d.x, centres[f].x);
    EXPECT_EQ(d.y, centres[f].y);
    EXPECT_EQ(d.z, centres[f].z);
  }
  // +X: s -> -z, t -> -y. +Y: s -> +x, t -> +z. +Z: s -> +x, t -> -y.
  EXPECT_EQ(cubeFaceDirection(kCubePosX, 1, 0).z, -1.0f);
  EXPECT_EQ(cubeFaceDirection(kCubePosX, 0, 1).y, -1.0f);
  EXPECT_EQ(cubeFaceDirection(kCubePosY, 0, 1).z, 1.0f);
  EXPECT_EQ(cubeFaceDirection(kCubePosZ, 1, 0).x, 1.0f);
  EXPECT_EQ(cubeFaceDirection(kCubeNegZ, 1, 0).x, -1.0f);
}

TEST(CubeMap, TexelSolidAnglesSumTo4Pi) {
  for (int size : {1, 2, 3, 7, 16, 64, 255}) {
    double sum = 0.0;
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const double w = cubeTexelSolidAngle(size, i, j);
        ASSERT_GT(w, 0.0);
        sum += w;
      }
    EXPECT_NEAR(6.0 * sum, 4.0 * kPi, 1e-10) << "size " << size;
  }
  // Centre texels subtend more than corner texels (the distortion the weights correct).
  EXPECT_GT(cubeTexelSolidAngle(64, 32, 32), 2.5 * cubeTexelSolidAngle(64, 0, 0));
  // One texel per face: a sixth of the sphere.
  EXPECT_NEAR(cubeTexelSolidAngle(1, 0, 0), 4.0 * kPi / 6.0, 1e-12);
}

TEST(CubeMap, ConstantCubeGivesOnlyTheDcTerm) {
  const CubeMap cube = makeCube(64, [](int, Vec3) { return Rgb{1, 1, 1}; });
  std::vector<Rgb> c;
  ASSERT_TRUE(projectCubeMap(5, cube, &c).isOk());
  EXPECT_NEAR(c[0].r, 2.0 * std::sqrt(kPi), 1e-5);
  // Texel-centre basis values leave an O(texel^2) quadrature error, only in the bands the
  // cube's symmetry allows (l = 4: y_40, y_44); it shrinks 4x when the resolution doubles.
  for (std::size_t i = 1; i < c.size(); ++i) EXPECT_NEAR(c[i].g, 0.0, 1e-3) << "i=" << i;
  std::vector<Rgb> fine;
  ASSERT_TRUE(projectCubeMap(5, makeCube(128, [](int, Vec3) { return Rgb{1, 1, 1}; }), &fine).isOk());
  EXPECT_GT(std::fabs(c[shIndex(4, 0)].g), 1e-5f);
  EXPECT_NEAR(fine[shIndex(4, 0)].g / c[shIndex(4, 0)].g, 0.25, 0.02);
}

TEST(CubeMap, OneLitFaceMatchesItsAnalyticIntegral) {
  const int order = 5;
  const CubeMap cube = makeCube(64, [](int face, Vec3) { return face == kCubePosZ ? Rgb{1, 2, 3} : Rgb{0, 0, 0}; });
  std::vector<Rgb> c;
  ASSERT_TRUE(projectCubeMap(order, cube, &c).isOk());
  // Closed forms: the face subtends 4pi/6; int z dOmega over it is the unit-square form
  // factor 2 sqrt(2) atan(1/sqrt(2)); x and y integrate to zero by symmetry.
  EXPECT_NEAR(c[0].r, 4.0 * kPi / 6.0 * 0.28209479177, 1e-5);
  EXPECT_NEAR(c[shIndex(1, 0)].r, std::sqrt(3.0 / (4 * kPi)) * 2.0 * std::sqrt(2.0) * std::atan(1.0 / std::sqrt(2.0)), 1e-4);
  EXPECT_NEAR(c[shIndex(1, 1)].r, 0.0, 1e-6);
  EXPECT_NEAR(c[shIndex(1, -1)].b, 0.0, 1e-6);
  // Every coefficient against a 2D Gauss-Legendre integral over the face.
  std::vector<double> nodes, weights;
  ref::gaussLegendre(40, &nodes, &weights);
  std::vector<double> expected(shCoeffCount(order), 0.0);
  std::vector<float> y(shCoeffCount(order));
  for (std::size_t a = 0; a < nodes.size(); ++a)
    for (std::size_t b = 0; b < nodes.size(); ++b) {
      const double s = nodes[a], t = nodes[b], r2 = 1 + s * s + t * t;
      Vec3 d = cubeFaceDirection(kCubePosZ, static_cast<float>(s), static_cast<float>(t));
      evalShBasisUnchecked(order, d * (1.0f / length(d)), y.data());
      for (int i = 0; i < shCoeffCount(order); ++i) expected[i] += weights[a] * weights[b] / (r2 * std::sqrt(r2)) * y[i];
    }
  for (int i = 0; i < shCoeffCount(order); ++i) {
    EXPECT_NEAR(c[i].r, expected[i], 2e-4) << "i=" << i;
    EXPECT_NEAR(c[i].b, 3.0 * expected[i], 6e-4) << "i=" << i;
  }
}

TEST(CubeMap, ReproducesABandLimitedFunction) {
  const int order = 4;
  std::vector<float> truth(shCoeffCount(order));
  for (int i = 0; i < shCoeffCount(order); ++i) truth[i] = std::sin(1.7f * i + 0.3f);
  const CubeMap cube = makeCube(96, [&](int, Vec3 d) {
    std::vector<float> y(shCoeffCount(order));
    evalShBasisUnchecked(order, d, y.data());
    float v = 0;
    for (int i = 0; i < shCoeffCount(order); ++i) v += truth[i] * y[i];
    return Rgb{v, -v, 0};
  });
  std::vector<Rgb> c;
  ASSERT_TRUE(projectCubeMap(order, cube, &c).isOk());
  for (int i = 0; i < shCoeffCount(order); ++i) {
    EXPECT_NEAR(c[i].r, truth[i], 2e-3) << "i=" << i;
    EXPECT_NEAR(c[i].g, -truth[i], 2e-3);
  }
}

RgbImage crossFrom(const CubeMap& cube, bool horizontal) {
  const int f = cube.size;
  RgbImage img;
  img.width = horizontal ? 4 * f : 3 * f;
  img.height = horizontal ? 3 * f : 4 * f;
  img.rgb.assign(static_cast<std::size_t>(img.width) * img.height * 3, -1.0f);
  auto put = [&](int face, int col, int row, bool rotated) {
    for (int j = 0; j < f; ++j)
      for (int i = 0; i < f; ++i) {
        const int si = rotated ? f - 1 - i : i, sj = rotated ? f - 1 - j : j;
        for (int ch = 0; ch < 3; ++ch)
          img.rgb[((static_cast<std::size_t>(row) * f + sj) * img.width + col * f + si) * 3 + ch] =
              cube.faces[face][(static_cast<std::size_t>(j) * f + i) * 3 + ch];
      }
  };
  put(kCubePosY, 1, 0, false);
  put(kCubeNegX, 0, 1, false);
  put(kCubePosZ, 1, 1, false);
  put(kCubePosX, 2, 1, false);
  put(kCubeNegY, 1, 2, false);
  if (horizontal) put(kCubeNegZ, 3, 1, false);
  else put(kCubeNegZ, 1, 3, true);
  return img;
}

TEST(CubeMap, CrossLayoutsRoundTrip) {
  const CubeMap cube = makeCube(8, [](int face, Vec3 d) { return Rgb{d.x, d.y + face, d.z}; });
  for (bool horizontal : {true, false}) {
    CubeMap back;
    ASSERT_TRUE(cubeMapFromCross(crossFrom(cube, horizontal), &back).isOk());
    ASSERT_EQ(back.size, 8);
    for (int f = 0; f < 6; ++f) EXPECT_EQ(back.faces[f], cube.faces[f]) << "face " << f << (horizontal ? " h" : " v");
  }
}

TEST(CubeMap, HorizontalCrossIsSeamless) {
  // Neighbouring texels across the +Z / +X seam must point in nearly the same direction.
  const int f = 16;
  const CubeMap dirs = makeCube(f, [](int, Vec3 d) { return Rgb{d.x, d.y, d.z}; });
  const RgbImage cross = crossFrom(dirs, true);
  for (int row = f; row < 2 * f; ++row) {
    for (int seamCol : {f, 2 * f, 3 * f}) {
      const Rgb a = cross.at(seamCol - 1, row), b = cross.at(seamCol, row);
      const float dotp = a.r * b.r + a.g * b.g + a.b * b.b;
      EXPECT_GT(dotp, std::cos(0.2f)) << "row " << row << " col " << seamCol;
    }
  }
}

}  // namespace
}  // namespace prt
