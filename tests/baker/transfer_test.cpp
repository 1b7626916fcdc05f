#include "baker/transfer/transfer_bake.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "baker/test_scenes.h"
#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"

namespace prt::bake {
namespace {

BakeOptions quickOptions() {
  BakeOptions o;
  o.order = 5;
  o.samples = 4096;
  o.threads = 2;
  return o;
}

// Exit radiance under constant unit radiance (L_0 = 2 sqrt(pi), others 0) is T_0 * 2 sqrt(pi).
float underWhiteFurnace(const float* transfer) { return transfer[0] * 2.0f * std::sqrt(static_cast<float>(kPi)); }

TEST(Transfer, UnshadowedMatchesClampedCosineProjection) {
  Scene s;
  test::addSphere(&s, {0, 0, 0}, 1.0f, 24, 12, {0.5f, 0.5f, 0.5f});
  BakeOptions o = quickOptions();
  o.interreflection = false;
  BakeResult r;
  ASSERT_TRUE(bakeTransfer(s, o, &r).isOk());
  const int n2 = shCoeffCount(o.order);
  std::vector<float> zonal(o.order), expected(n2);
  ASSERT_TRUE(zonalClampedCosine(o.order, zonal).isOk());
  for (std::size_t v = 0; v < s.positions.size(); v += 7) {
    // albedo * H_l * y_lm(n) per unit albedo: (1/pi) * clamped-cosine projection
    ASSERT_TRUE(placeZonal(o.order, zonal, s.normals[v], expected).isOk());
    for (int i = 0; i < n2; ++i) {
      ASSERT_NEAR(r.unshadowed[v * n2 + i], expected[i] / kPi, 0.01) << "vertex " << v << " i=" << i;
    }
  }
}

TEST(Transfer, PlaneAloneIsNeverShadowed) {
  Scene s;
  test::addPlane(&s, 1.0f, 64, 0.0f, {0.7f, 0.7f, 0.7f});  // finely tessellated
  BakeResult r;
  ASSERT_TRUE(bakeTransfer(s, quickOptions(), &r).isOk());
  ASSERT_EQ(r.shadowed.size(), r.unshadowed.size());
  for (std::size_t i = 0; i < r.shadowed.size(); ++i) ASSERT_EQ(r.shadowed[i], r.unshadowed[i]) << i;
  // Nothing to bounce off: interreflection adds nothing beyond albedo * shadowed.
  EXPECT_EQ(r.bounceEnergy.size(), 2u);
  EXPECT_EQ(r.bounceEnergy[1], 0.0);
}

TEST(Transfer, PointUnderSphereGetsCosSquaredAlpha) {
  // Constant white light; a point on the plane below a sphere of angular radius alpha sees
  // irradiance pi (1 - sin^2 alpha) = pi cos^2 alpha, so exit radiance rho cos^2 alpha.
  for (float height : {1.5f, 3.0f}) {
    Scene s;
    test::addPlane(&s, 4.0f, 8, 0.0f, {0.6f, 0.6f, 0.6f});  // vertex (4, 4) is the origin
    test::addSphere(&s, {0, height, 0}, 1.0f, 64, 32, {0.5f, 0.5f, 0.5f});
    BakeOptions o = quickOptions();
    o.samples = 16384;
    o.interreflection = false;
    BakeResult r;
    ASSERT_TRUE(bakeTransfer(s, o, &r).isOk());
    const std::size_t origin = 4 * 9 + 4;
    ASSERT_NEAR(length(s.positions[origin]), 0.0f, 1e-6f);
    const float sinAlpha = 1.0f / height;
    const float expected = 0.6f * (1.0f - sinAlpha * sinAlpha);
    const float got = 0.6f * underWhiteFurnace(&r.shadowed[origin * shCoeffCount(o.order)]);
    EXPECT_NEAR(got, expected, 0.01f) << "height " << height;
    EXPECT_NEAR(0.6f * underWhiteFurnace(&r.unshadowed[origin * shCoeffCount(o.order)]), 0.6f, 0.005f);
  }
}

TEST(Transfer, InterreflectionAddsEnergyMonotonicallyAndConverges) {
  Scene s;
  const float rho = 0.8f;
  test::addPlane(&s, 2.0f, 16, 0.0f, {rho, rho, rho});
  test::addSphere(&s, {0, 1.0f, 0}, 0.9f, 32, 16, {rho, rho * 0.5f, rho * 0.25f});
  BakeOptions o = quickOptions();
  o.samples = 1024;
  o.maxBounces = 8;
  o.bounceThreshold = 1e-4;
  BakeResult r;
  ASSERT_TRUE(bakeTransfer(s, o, &r).isOk());
  ASSERT_GE(r.bounces, 2);
  for (std::size_t b = 1; b < r.bounceEnergy.size(); ++b) {
    EXPECT_GE(r.bounceEnergy[b], 0.0) << "bounce " << b;
    // Each bounce carries at most rho_max of the previous one.
    EXPECT_LE(r.bounceEnergy[b], rho * r.bounceEnergy[b - 1] * 1.001) << "bounce " << b;
  }
  // Total energy is bounded by the geometric series of the direct energy.
  double total = 0.0;
  for (double e : r.bounceEnergy) total += e;
  EXPECT_LE(total, r.bounceEnergy[0] / (1.0 - rho));
  EXPECT_GT(total, r.bounceEnergy[0]);
  // Per vertex: interreflected DC never below albedo * shadowed (bounces only add light).
  const int n2 = shCoeffCount(o.order);
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const float direct = s.albedo[v].r * r.shadowed[v * n2];
    ASSERT_GE(r.interreflected[v * 3 * n2] + 1e-6f, direct) << v;
    // and never above a white furnace's limit for this albedo: rho / (1 - rho) * ... <= 1 in total
    ASSERT_LE(underWhiteFurnace(&r.interreflected[v * 3 * n2]), 1.0f) << v;
  }
}

TEST(Transfer, ThreadCountDoesNotChangeResults) {
  Scene s;
  test::addPlane(&s, 2.0f, 20, 0.0f, {0.7f, 0.6f, 0.5f});
  test::addSphere(&s, {0.3f, 0.8f, 0}, 0.7f, 24, 12, {0.4f, 0.8f, 0.3f});
  BakeOptions o = quickOptions();
  o.samples = 256;
  o.maxBounces = 3;
  BakeResult one, many;
  o.threads = 1;
  ASSERT_TRUE(bakeTransfer(s, o, &one).isOk());
  o.threads = 4;
  ASSERT_TRUE(bakeTransfer(s, o, &many).isOk());
  EXPECT_EQ(one.unshadowed, many.unshadowed);
  EXPECT_EQ(one.shadowed, many.shadowed);
  EXPECT_EQ(one.interreflected, many.interreflected);
  // A different seed is a different sample set.
  o.seed = 2;
  BakeResult other;
  ASSERT_TRUE(bakeTransfer(s, o, &other).isOk());
  EXPECT_NE(one.shadowed, other.shadowed);
}

TEST(Transfer, StratifiedSamplingAgreesWithHammersley) {
  Scene s;
  test::addPlane(&s, 2.0f, 8, 0.0f, {0.7f, 0.7f, 0.7f});
  test::addSphere(&s, {0, 1.2f, 0}, 1.0f, 24, 12, {0.5f, 0.5f, 0.5f});
  BakeOptions o = quickOptions();
  o.interreflection = false;
  BakeResult h, st;
  ASSERT_TRUE(bakeTransfer(s, o, &h).isOk());
  o.sampling = Sampling::kStratified;  // 4096 = 64^2
  ASSERT_TRUE(bakeTransfer(s, o, &st).isOk());
  const int n2 = shCoeffCount(o.order);
  for (std::size_t v = 0; v < s.positions.size(); ++v) ASSERT_NEAR(h.shadowed[v * n2], st.shadowed[v * n2], 0.01) << v;
  o.samples = 1000;
  EXPECT_FALSE(bakeTransfer(s, o, &st).isOk()) << "stratified needs a square count";
}

TEST(Transfer, ThinOneSidedWallShadowsBothSides) {
  // A single-sided vertical quad (normal +x) standing on the floor occludes floor points on
  // its front and on its back alike.
  Scene s;
  test::addPlane(&s, 2.0f, 16, 0.0f, {0.5f, 0.5f, 0.5f});  // vertices every 0.25 m
  const auto base = static_cast<std::uint32_t>(s.positions.size());
  for (Vec3 p : {Vec3{0, 0, -1.5f}, Vec3{0, 0, 1.5f}, Vec3{0, 1.5f, -1.5f}, Vec3{0, 1.5f, 1.5f}}) {
    s.positions.push_back(p);
    s.normals.push_back({1, 0, 0});
    s.albedo.push_back({0.5f, 0.5f, 0.5f});
  }
  for (std::uint32_t i : {0u, 2u, 1u, 1u, 2u, 3u}) s.indices.push_back(base + i);
  BakeOptions o = quickOptions();
  o.interreflection = false;
  BakeResult r;
  ASSERT_TRUE(bakeTransfer(s, o, &r).isOk());
  const int n2 = shCoeffCount(o.order);
  auto vertexAt = [&](float x, float z) {
    for (std::size_t v = 0; v < base; ++v)
      if (std::fabs(s.positions[v].x - x) < 1e-4f && std::fabs(s.positions[v].z - z) < 1e-4f) return v;
    return std::size_t{0};
  };
  const std::size_t front = vertexAt(0.25f, 0.0f), back = vertexAt(-0.25f, 0.0f), far = vertexAt(2.0f, 2.0f);
  const float frontRatio = r.shadowed[front * n2] / r.unshadowed[front * n2];
  const float backRatio = r.shadowed[back * n2] / r.unshadowed[back * n2];
  EXPECT_LT(frontRatio, 0.8f);
  EXPECT_NEAR(frontRatio, backRatio, 0.02f) << "the back of the wall must shadow as much as its front";
  EXPECT_GT(r.shadowed[far * n2] / r.unshadowed[far * n2], frontRatio);
}

TEST(Transfer, RayOffsetsScaleWithTheScene) {
  // The same scene at millimetre and kilometre scale bakes to the same transfer.
  auto bakeScaled = [](float scale) {
    Scene s;
    test::addPlane(&s, 2.0f * scale, 12, 0.0f, {0.6f, 0.6f, 0.6f});
    test::addSphere(&s, {0, 0.8f * scale, 0}, 0.7f * scale, 24, 12, {0.4f, 0.4f, 0.4f});
    BakeOptions o = quickOptions();
    o.samples = 1024;
    o.maxBounces = 2;
    BakeResult r;
    EXPECT_TRUE(bakeTransfer(s, o, &r).isOk());
    return r;
  };
  const BakeResult unit = bakeScaled(1.0f), small = bakeScaled(1e-3f), large = bakeScaled(1e3f);
  ASSERT_EQ(unit.shadowed.size(), small.shadowed.size());
  int differing = 0;
  for (std::size_t i = 0; i < unit.shadowed.size(); ++i) {
    differing += std::fabs(unit.shadowed[i] - small.shadowed[i]) > 2e-3f;
    differing += std::fabs(unit.shadowed[i] - large.shadowed[i]) > 2e-3f;
  }
  // Float rounding may flip a grazing ray or two, nothing more.
  EXPECT_LE(differing, static_cast<int>(unit.shadowed.size() / 1000)) << differing << " coefficients differ";
}

TEST(Transfer, RejectsBadOptions) {
  Scene s;
  test::addPlane(&s, 1.0f, 2, 0.0f, {0.5f, 0.5f, 0.5f});
  BakeResult r;
  BakeOptions o = quickOptions();
  o.order = 9;
  EXPECT_FALSE(bakeTransfer(s, o, &r).isOk());
  o = quickOptions();
  o.samples = 3;
  EXPECT_FALSE(bakeTransfer(s, o, &r).isOk());
  Scene empty;
  EXPECT_FALSE(bakeTransfer(empty, quickOptions(), &r).isOk());
}

}  // namespace
}  // namespace prt::bake
