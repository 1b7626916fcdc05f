// The glossy model's shared pieces against independent references: the Phong lobe's band
// scales against Gauss-Legendre integration of the textbook Legendre polynomials, the
// matrix packings' prefix rule by enumeration, and glossy exit radiance against direct
// quadrature of L(w) f(w) over the sphere for band-limited lighting.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "prt/glossy_codec_weights.h"
#include "prt/glossy_lobe.h"
#include "prt/glossy_radiance.h"
#include "prt/sh_basis.h"
#include "prt/transfer_matrix.h"
#include "support/quadrature.h"
#include "support/sh_reference.h"

namespace prt {
namespace {

// P_l(t) by Bonnet's recurrence (independent of the library's SH code).
double legendre(int l, double t) {
  double p0 = 1.0, p1 = t;
  if (l == 0) return p0;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

// (s+1) integral_0^1 t^s P_l(t) dt by 200-point Gauss-Legendre on [0, 1] (t^s with
// non-integer s is smooth enough on [0, 1] away from 0 for this to converge to 1e-9).
double bandScaleByQuadrature(int l, double s) {
  std::vector<double> x, w;
  ref::gaussLegendre(200, &x, &w);
  double sum = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double t = 0.5 * (x[k] + 1.0);
    sum += 0.5 * w[k] * std::pow(t, s) * legendre(l, t);
  }
  return (s + 1.0) * sum;
}

TEST(PhongLobe, BandScalesMatchQuadrature) {
  for (double s : {0.0, 1.0, 2.5, 7.0, 20.0, 100.0}) {
    std::vector<double> g(16);
    ASSERT_TRUE(phongLobeBandScales(16, s, g).isOk());
    for (int l = 0; l < 16; ++l) {
      EXPECT_NEAR(g[l], bandScaleByQuadrature(l, s), 1e-8) << "s " << s << " l " << l;
    }
    EXPECT_DOUBLE_EQ(g[0], 1.0);
  }
}

TEST(PhongLobe, FloatVariantAgrees) {
  std::vector<double> g(8);
  std::vector<float> gf(8);
  ASSERT_TRUE(phongLobeBandScales(8, 12.0, g).isOk());
  phongLobeBandScalesUnchecked(8, 12.0f, gf.data());
  for (int l = 0; l < 8; ++l) EXPECT_NEAR(gf[l], g[l], 1e-6);
}

TEST(PhongLobe, RejectsBadInput) {
  std::vector<double> g(4);
  EXPECT_FALSE(phongLobeBandScales(4, -1.0, g).isOk());
  EXPECT_FALSE(phongLobeBandScales(4, NAN, g).isOk());
  EXPECT_FALSE(phongLobeBandScales(4, INFINITY, g).isOk());
  EXPECT_FALSE(phongLobeBandScales(5, 1.0, g).isOk());
  EXPECT_FALSE(phongLobeBandScales(0, 1.0, g).isOk());
}

TEST(PhongLobe, RoughnessMapping) {
  double s = 0.0;
  ASSERT_TRUE(specularExponentFromRoughness(1.0, kDefaultMaxSpecularExponent, &s).isOk());
  EXPECT_DOUBLE_EQ(s, 0.0);
  ASSERT_TRUE(specularExponentFromRoughness(0.0, kDefaultMaxSpecularExponent, &s).isOk());
  EXPECT_DOUBLE_EQ(s, kDefaultMaxSpecularExponent);
  ASSERT_TRUE(specularExponentFromRoughness(0.5, kDefaultMaxSpecularExponent, &s).isOk());
  EXPECT_DOUBLE_EQ(s, (2.0 / std::pow(0.25, 2) - 2.0) / 4.0);  // alpha = 0.25: 7.5
  double previous = INFINITY;
  for (double r = 0.05; r <= 1.0; r += 0.05) {
    ASSERT_TRUE(specularExponentFromRoughness(r, 1e9, &s).isOk());
    EXPECT_LT(s, previous);
    previous = s;
  }
  EXPECT_FALSE(specularExponentFromRoughness(-0.1, 100.0, &s).isOk());
  EXPECT_FALSE(specularExponentFromRoughness(1.1, 100.0, &s).isOk());
  EXPECT_FALSE(specularExponentFromRoughness(NAN, 100.0, &s).isOk());
}

TEST(PhongLobe, SchlickEndpoints) {
  const Rgb f0{0.04f, 0.5f, 1.0f};
  const Rgb normal = schlickFresnel(f0, 1.0f, 1.0f), grazing = schlickFresnel(f0, 1.0f, 0.0f),
            behind = schlickFresnel(f0, 1.0f, -0.5f);
  EXPECT_FLOAT_EQ(normal.r, 0.04f);
  EXPECT_FLOAT_EQ(normal.g, 0.5f);
  EXPECT_FLOAT_EQ(grazing.r, 1.0f);
  EXPECT_FLOAT_EQ(behind.g, 1.0f);
  EXPECT_FLOAT_EQ(schlickFresnel(f0, 1.0f, 0.5f).r, 0.04f + 0.96f * 0.03125f);
  // KHR_materials_specular scales F90 too: no specular part means none at grazing angles.
  const Rgb none = schlickFresnel({0, 0, 0}, 0.0f, 0.0f);
  EXPECT_EQ(none.r + none.g + none.b, 0.0f);
  EXPECT_FLOAT_EQ(schlickFresnel(f0, 0.5f, 0.0f).r, 0.5f);
}

// The codec's row weights (docs/glossy.md "Compressing in the exit-radiance metric"): the
// band scales of the scene's most demanding lobe, per row of each band; non-specular
// materials ignored; a band no lobe sees floored.
TEST(GlossyCodecWeights, RowsTakeTheSharpestLobesBandScales) {
  const Rgb f0{0.04f, 0.04f, 0.04f};
  std::vector<double> w;
  // One exponent 8: g_l(8) = 1, 9/10, 8/11, 0.525, 0.336 (the recurrence), per row.
  ASSERT_TRUE(glossyMatrixRowWeights(5, std::vector<SpecularMaterial>(3, {f0, 8.0f, 1.0f}), &w).isOk());
  ASSERT_EQ(w.size(), 25u);
  std::vector<double> g(5);
  ASSERT_TRUE(phongLobeBandScales(5, 8.0, g).isOk());
  for (int l = 0; l < 5; ++l)
    for (int m = -l; m <= l; ++m) EXPECT_EQ(w[static_cast<std::size_t>(l * (l + 1) + m)], g[static_cast<std::size_t>(l)]);
  EXPECT_NEAR(w[1], 0.9, 1e-12);
  EXPECT_NEAR(w[4], 8.0 / 11.0, 1e-12);
  // A rougher material and a sharper one that reflects nothing: the exponent-8 lobe rules.
  std::vector<SpecularMaterial> mixed = {{f0, 8.0f, 1.0f}, {f0, 2.0f, 1.0f}, {Rgb{}, 500.0f, 0.0f}};
  std::vector<double> w2;
  ASSERT_TRUE(glossyMatrixRowWeights(5, mixed, &w2).isOk());
  EXPECT_EQ(w2, w);
  // Exponent 1 alone: g_3 = 0 (no lobe sees band 3) is floored; with exponent 0 as well,
  // band 3 takes |g_3(0)| = 1/8 (the larger |g_l| of the two, not the sharper lobe's).
  ASSERT_TRUE(glossyMatrixRowWeights(4, std::vector<SpecularMaterial>(1, {f0, 1.0f, 1.0f}), &w2).isOk());
  EXPECT_EQ(w2[9], kMinGlossyRowWeight);
  EXPECT_NEAR(w2[4], 0.25, 1e-12);
  ASSERT_TRUE(glossyMatrixRowWeights(4, std::vector<SpecularMaterial>{{f0, 1.0f, 1.0f}, {f0, 0.0f, 1.0f}}, &w2).isOk());
  EXPECT_NEAR(w2[9], 0.125, 1e-12);
  // No specular material: no weights (the codec's unweighted metric).
  ASSERT_TRUE(glossyMatrixRowWeights(5, std::vector<SpecularMaterial>(2, {Rgb{}, 8.0f, 0.0f}), &w2).isOk());
  EXPECT_TRUE(w2.empty());
  EXPECT_EQ(glossyMatrixRowWeights(5, std::vector<SpecularMaterial>{{f0, -1.0f, 1.0f}}, &w2).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(glossyMatrixRowWeights(17, std::vector<SpecularMaterial>{{f0, 1.0f, 1.0f}}, &w2).code(), StatusCode::kInvalidArgument);
}

TEST(TransferMatrix, PackingsArePrefixClosedBijections) {
  for (MatrixPacking packing : {MatrixPacking::kSymmetric, MatrixPacking::kFull}) {
    for (int order = 1; order <= 6; ++order) {
      const std::size_t n2 = static_cast<std::size_t>(order) * order, count = matrixEntryCount(order, packing);
      std::set<std::size_t> seen;
      for (std::size_t i = 0; i < n2; ++i) {
        for (std::size_t j = 0; j < n2; ++j) {
          const std::size_t index = matrixEntryIndex(i, j, packing);
          ASSERT_LT(index, count);
          if (packing == MatrixPacking::kSymmetric) EXPECT_EQ(index, matrixEntryIndex(j, i, packing));
          if (packing == MatrixPacking::kFull || j <= i) seen.insert(index);
          // Prefix rule: inside the order-b block exactly when both indices are below b^2.
          for (int b = 1; b <= order; ++b) {
            const std::size_t b2 = static_cast<std::size_t>(b) * b;
            EXPECT_EQ(index < matrixEntryCount(b, packing), i < b2 && j < b2);
          }
        }
      }
      EXPECT_EQ(seen.size(), count);
    }
  }
}

TEST(TransferMatrix, ApplyMatchesDenseProduct) {
  for (MatrixPacking packing : {MatrixPacking::kSymmetric, MatrixPacking::kFull}) {
    const int order = 4;
    const std::size_t n2 = 16;
    std::vector<float> packed(matrixEntryCount(order, packing));
    for (std::size_t k = 0; k < packed.size(); ++k) packed[k] = std::sin(1.7f * static_cast<float>(k) + 0.3f);
    std::vector<float> v(n2), out(n2);
    for (std::size_t j = 0; j < n2; ++j) v[j] = std::cos(0.9f * static_cast<float>(j));
    ASSERT_TRUE(applyPackedMatrix(packed, order, packing, v, out).isOk());
    for (int b = 1; b <= order; ++b) {
      const std::size_t rows = static_cast<std::size_t>(b) * b;
      std::vector<float> block(rows);
      applyPackedMatrixUnchecked(packed.data(), packing, rows, v.data(), block.data());
      for (std::size_t i = 0; i < rows; ++i) {
        double dense = 0.0;
        for (std::size_t j = 0; j < rows; ++j) dense += packed[matrixEntryIndex(i, j, packing)] * double(v[j]);
        EXPECT_NEAR(block[i], dense, 1e-5);
        if (b == order) EXPECT_NEAR(out[i], dense, 1e-5);
      }
    }
    EXPECT_FALSE(applyPackedMatrix(std::span<const float>(packed).first(packed.size() - 1), order, packing, v, out).isOk());
  }
}

// With M = identity the glossy term is the lobe convolved with the lighting at R; for
// lighting band-limited to the matrix order that is exactly integral L(w) f(w) dw.
TEST(GlossyRadiance, IdentityMatrixEqualsLobeIntegral) {
  const int order = 4;
  const std::size_t n2 = 16;
  std::vector<float> identity(matrixEntryCount(order, MatrixPacking::kFull), 0.0f);
  for (std::size_t i = 0; i < n2; ++i) identity[matrixEntryIndex(i, i, MatrixPacking::kFull)] = 1.0f;
  std::vector<Rgb> lighting(n2);
  for (std::size_t i = 0; i < n2; ++i) {
    lighting[i] = {0.8f * std::cos(1.3f * i), 0.5f * std::sin(0.7f * i + 1.0f), i == 0 ? 2.0f : 0.1f};
  }
  const Vec3 p{0.2f, -0.1f, 0.3f}, n{0.0f, 0.6f, 0.8f};
  const auto quadrature = ref::sphereQuadrature(96);
  for (float s : {0.0f, 3.0f, 16.0f}) {
    for (Vec3 eye : {Vec3{0.2f, 3.0f, 4.3f}, Vec3{2.0f, 0.5f, 1.0f}, Vec3{-1.0f, 1.0f, 0.5f}}) {
      const SpecularMaterial material{{0.3f, 0.6f, 0.9f}, s};
      std::vector<float> out(3);
      ASSERT_TRUE(glossyExitRadiance(identity, order, MatrixPacking::kFull, 1, std::span(&p, 1), std::span(&n, 1),
                                     std::span(&material, 1), {eye, false}, lighting, out)
                      .isOk());
      Vec3 v = eye - p;
      v = v * (1.0f / length(v));
      const Vec3 r = n * (2.0f * dot(n, v)) - v;
      double expected[3] = {0, 0, 0};
      for (const auto& q : quadrature) {
        const double c = dot(r, q.dir);
        if (c <= 0.0) continue;
        const double f = (s + 1.0) / (2.0 * kPi) * std::pow(c, s);
        for (std::size_t i = 0; i < n2; ++i) {
          const int l = shBandOf(static_cast<int>(i));
          const double y = ref::shTextbook(l, static_cast<int>(i) - l * (l + 1), q.dir.x, q.dir.y, q.dir.z);
          expected[0] += q.weight * f * y * lighting[i].r;
          expected[1] += q.weight * f * y * lighting[i].g;
          expected[2] += q.weight * f * y * lighting[i].b;
        }
      }
      // The lobe is not band-limited, but the lighting is: only its bands survive the integral.
      EXPECT_NEAR(out[0], 0.3 * expected[0], 2e-3) << "s " << s;
      EXPECT_NEAR(out[1], 0.6 * expected[1], 2e-3) << "s " << s;
      EXPECT_NEAR(out[2], 0.9 * expected[2], 2e-3) << "s " << s;
    }
  }
}

TEST(GlossyRadiance, DoubleAgreesAndSizesChecked) {
  const int order = 3;
  std::vector<float> m(matrixEntryCount(order, MatrixPacking::kSymmetric));
  for (std::size_t k = 0; k < m.size(); ++k) m[k] = 0.1f * static_cast<float>(k % 7) - 0.2f;
  const Vec3 p{0, 0, 0}, n{0, 0, 1};
  const SpecularMaterial material{{1, 1, 1}, 5.0f};
  std::vector<Rgb> lighting(9, Rgb{1.0f, 0.5f, 0.25f});
  std::vector<float> f(3);
  std::vector<double> d(3);
  const GlossyView view{{0.5f, 0.2f, 2.0f}, true};
  ASSERT_TRUE(glossyExitRadiance(m, order, MatrixPacking::kSymmetric, 1, std::span(&p, 1), std::span(&n, 1),
                                 std::span(&material, 1), view, lighting, f).isOk());
  ASSERT_TRUE(glossyExitRadianceDouble(m, order, MatrixPacking::kSymmetric, 1, std::span(&p, 1), std::span(&n, 1),
                                       std::span(&material, 1), view, lighting, d).isOk());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], d[c], 1e-5);
  // A prefix of the lighting uses the leading block only.
  std::vector<float> f1(3);
  ASSERT_TRUE(glossyExitRadiance(m, order, MatrixPacking::kSymmetric, 1, std::span(&p, 1), std::span(&n, 1),
                                 std::span(&material, 1), view, std::span<const Rgb>(lighting).first(1), f1).isOk());
  EXPECT_NEAR(f1[0], schlickFresnel(material.f0, material.f90, dot(n, view.eye * (1.0f / length(view.eye)))).r * m[0] * 1.0f * 0.2820948f, 1e-6);
  std::vector<Rgb> bad(5);
  EXPECT_FALSE(glossyExitRadiance(m, order, MatrixPacking::kSymmetric, 1, std::span(&p, 1), std::span(&n, 1),
                                  std::span(&material, 1), view, bad, f).isOk());
  EXPECT_FALSE(glossyExitRadiance(std::span<const float>(m).first(3), order, MatrixPacking::kSymmetric, 1,
                                  std::span(&p, 1), std::span(&n, 1), std::span(&material, 1), view, lighting, f).isOk());
}

}  // namespace
}  // namespace prt
