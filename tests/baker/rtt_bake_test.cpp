// Radiance transfer textures baked from height-field patches (baker/rtt/rtt_bake.h) against
// closed forms, the white furnace and a brute-force integral over the patch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "baker/rtt/periodic_tracer.h"
#include "baker/test_scenes.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/asset.h"
#include "prt/bi_scale.h"
#include "baker/rtt/rtt_bake.h"
#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"

namespace prt::bake {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Legendre P_l(x) by the recurrence (independent of the code under test).
double legendre(int l, double x) {
  double p0 = 1.0, p1 = x;
  if (l == 0) return p0;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

// Clamped cosine in SH about +z: c_l = 2 pi sqrt((2l+1)/(4 pi)) int_0^1 P_l(t) t dt (midpoint rule
// with 20000 steps: exact to 1e-9 for these polynomials).
double clampedCosine(int l) {
  constexpr int kSteps = 20000;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double t = (i + 0.5) / kSteps;
    sum += legendre(l, t) * t / kSteps;
  }
  return 2.0 * kPiD * std::sqrt((2.0 * l + 1.0) / (4.0 * kPiD)) * sum;
}

Rtt bake(const HeightPatch& patch, RttSettings s) {
  Rtt r;
  const Status st = bakeRtt(patch, s, {}, &r);
  EXPECT_TRUE(st.isOk()) << st.toString();
  return r;
}

const float* at(const Rtt& r, int x, int y, int a, int b, int c = 0) {
  const std::size_t S = static_cast<std::size_t>(r.spatial), V = static_cast<std::size_t>(r.views);
  return &r.coeffs[((((static_cast<std::size_t>(y) * S + static_cast<std::size_t>(x)) * V + static_cast<std::size_t>(b)) * V +
                     static_cast<std::size_t>(a)) *
                        static_cast<std::size_t>(r.channels) +
                    static_cast<std::size_t>(c)) *
                   static_cast<std::size_t>(r.order * r.order)];
}

// A flat patch is the Lambertian transfer of its tangent frame, rho / pi times the clamped
// cosine's SH, at every position and every view (the light rule integrates it exactly).
TEST(RttBake, FlatPatchIsTheClampedCosineAtEveryView) {
  HeightPatch flat;
  ASSERT_TRUE(makeProceduralPatch("flat", 16, 0.7f, &flat).isOk());
  RttSettings s;
  s.spatial = 4;
  s.views = 8;
  s.bounces = 2;  // a plane sees nothing of itself: bounces add nothing
  const Rtt r = bake(flat, s);
  ASSERT_EQ(r.channels, 1);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int b = 0; b < 8; ++b)
        for (int a = 0; a < 8; ++a) {
          const float* B = at(r, x, y, a, b);
          for (int l = 0; l < 5; ++l)
            for (int m = -l; m <= l; ++m) {
              const double want = m == 0 ? 0.7 / kPiD * clampedCosine(l) : 0.0;
              EXPECT_NEAR(B[shIndex(l, m)], want, 2e-6) << "l " << l << " m " << m << " view " << a << "," << b;
            }
        }
}

// The white furnace: albedo 1 under uniform unit radiance (L_00 = 2 sqrt(pi)) returns at most
// 1 everywhere, exactly 1 on a plane, and each bounce brings a pit closer to 1.
TEST(RttBake, WhiteFurnaceApproachesOneFromBelow) {
  HeightPatch holes;
  ASSERT_TRUE(makeProceduralPatch("holes", 32, 1.0f, &holes).isOk());
  RttSettings s;
  s.spatial = 8;
  s.views = 2;
  s.supersample = 1;
  const float lighting = 2.0f * std::sqrt(static_cast<float>(kPiD));
  std::vector<double> darkest;
  for (int bounces : {0, 1, 4}) {
    s.bounces = bounces;
    const Rtt r = bake(holes, s);
    double lowest = 1e9, highest = -1e9;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        for (int v = 0; v < 4; ++v) {
          const double radiance = at(r, x, y, v % 2, v / 2)[0] * lighting;
          lowest = std::min(lowest, radiance);
          highest = std::max(highest, radiance);
        }
    EXPECT_LE(highest, 1.0 + 1e-4) << bounces << " bounces";
    EXPECT_NEAR(highest, 1.0, 1e-4) << "the plate around the pits sees the whole sky";
    darkest.push_back(lowest);
  }
  EXPECT_LT(darkest[0], 0.9) << "the pits' floors are shadowed";
  EXPECT_GT(darkest[1], darkest[0] + 0.01);
  EXPECT_GT(darkest[2], darkest[1]);
}

// Exit radiance from the RTT under a cap light equals a brute-force integral over the patch
// (visibility by the same periodic ray caster, a fine quadrature of its own, no light rule),
// for the SH-truncated cap to quadrature accuracy; against the true cap, within the truncation
// error of the SH lighting (what the same brute force shows between the two lights).
TEST(RttBake, MatchesBruteForceUnderACap) {
  HeightPatch holes;
  ASSERT_TRUE(makeProceduralPatch("holes", 64, 0.6f, &holes).isOk());
  RttSettings s;
  s.spatial = 8;  // sample centres (8x + 4) / 64: on grid points
  s.views = 4;
  s.supersample = 1;
  s.bounces = 0;
  s.lightPolar = 48;
  s.lightAzimuth = 96;
  const Rtt r = bake(holes, s);
  PeriodicTracer tracer;
  ASSERT_TRUE(PeriodicTracer::build(holes, &tracer).isOk());
  constexpr int kOrder = 5, kN = kOrder * kOrder;
  const float zeta = 0.5f;  // cap half-angle, rad
  double worstTruncated = 0.0, peak = 0.0;
  for (const Vec3 axisRaw : {Vec3{0.3f, 0.2f, 0.9f}, Vec3{-0.6f, 0.1f, 0.5f}}) {
    const Vec3 axis = axisRaw * (1.0f / length(axisRaw));
    float zonal[kOrder], light[kN];
    ASSERT_TRUE(zonalCircularLight(kOrder, zeta, 1.0f, zonal).isOk());
    ASSERT_TRUE(placeZonal(kOrder, zonal, axis, light).isOk());
    // Brute force at a grid point g: (rho / pi) int V max(0, n.s) L(s) ds over the upper
    // hemisphere, 160 x 320 midpoint cells in (cos theta, phi), for the truncated and true cap.
    auto bruteAtPoint = [&](int gi, int gj, double* truncated, double* cap) {
      const int n = holes.size;
      auto h = [&](int a, int b) { return holes.height[static_cast<std::size_t>((b + n) % n) * n + static_cast<std::size_t>((a + n) % n)]; };
      const float sp = 1.0f / n;
      const Vec3 g{-(h(gi + 1, gj) - h(gi - 1, gj)) / (2 * sp), -(h(gi, gj + 1) - h(gi, gj - 1)) / (2 * sp), 1.0f};
      const Vec3 normal = g * (1.0f / length(g));
      const Vec3 x{gi * sp, gj * sp, h(gi, gj)};
      constexpr int kTheta = 160, kPhi = 320;
      double t = 0.0, c = 0.0;
      float y[kN];
      for (int i = 0; i < kTheta; ++i)
        for (int j = 0; j < kPhi; ++j) {
          const double ct = (i + 0.5) / kTheta, st = std::sqrt(1.0 - ct * ct), phi = 2.0 * kPiD * (j + 0.5) / kPhi;
          const Vec3 dir{static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)), static_cast<float>(ct)};
          const double cosine = dot(normal, dir);
          if (cosine <= 0.0) continue;
          if (tracer.firstHit(x + normal * (1e-3f * sp), dir).hit) continue;
          const double dw = (1.0 / kTheta) * (2.0 * kPiD / kPhi);
          evalShBasisUnchecked(kOrder, dir, y);
          double l = 0.0;
          for (int q = 0; q < kN; ++q) l += light[q] * y[q];
          t += cosine * l * dw;
          c += dot(dir, axis) >= std::cos(zeta) ? cosine * dw : 0.0;
        }
      *truncated = 0.6 / kPiD * t;
      *cap = 0.6 / kPiD * c;
    };
    for (const auto& [sx, sy] : {std::pair{1, 1}, std::pair{2, 5}, std::pair{6, 6}}) {
      for (const auto& [va, vb] : {std::pair{1, 2}, std::pair{0, 3}}) {
        const Vec3 w = rttViewDirection(va, vb, 4);
        const PeriodicHit hit = tracer.viewHit({(sx + 0.5f) / 8, (sy + 0.5f) / 8, 0.5f * (tracer.minHeight() + tracer.maxHeight())}, w);
        ASSERT_TRUE(hit.hit);
        // The RTT interpolates over the hit triangle's grid points: so does the reference.
        std::vector<float> truncatedAt(static_cast<std::size_t>(holes.size) * holes.size, 0.0f), capAt(truncatedAt.size(), 0.0f);
        std::vector<std::size_t> corners = tracer.triangleGridPoints(hit);
        for (std::size_t p : corners) {
          double t = 0, c = 0;
          bruteAtPoint(static_cast<int>(p % holes.size), static_cast<int>(p / holes.size), &t, &c);
          truncatedAt[p] = static_cast<float>(t);
          capAt[p] = static_cast<float>(c);
        }
        float bruteTruncated = 0, bruteCap = 0;
        tracer.interpolate(hit, truncatedAt, 1, &bruteTruncated);
        tracer.interpolate(hit, capAt, 1, &bruteCap);
        const float* B = at(r, sx, sy, va, vb);
        double rtt = 0.0;
        for (int q = 0; q < kN; ++q) rtt += B[q] * light[q];
        worstTruncated = std::max(worstTruncated, std::fabs(rtt - bruteTruncated));
        peak = std::max(peak, static_cast<double>(bruteCap));
        EXPECT_NEAR(rtt, bruteTruncated, 2e-3) << "sample " << sx << "," << sy << " view " << va << "," << vb;
        EXPECT_LE(std::fabs(rtt - bruteCap), std::fabs(bruteTruncated - bruteCap) + 2e-3) << "against the true cap";
      }
    }
  }
  EXPECT_GT(peak, 0.05) << "the cap lights the samples";
  std::printf("RTT vs brute force, truncated SH cap: worst %.2e (peak %.3f)\n", worstTruncated, peak);
}

TEST(RttBake, RefusesBadSettings) {
  HeightPatch flat;
  ASSERT_TRUE(makeProceduralPatch("flat", 8, 0.5f, &flat).isOk());
  Rtt r;
  RttSettings s;
  s.order = 9;
  EXPECT_EQ(bakeRtt(flat, s, {}, &r).code(), StatusCode::kInvalidArgument);
  s = {};
  s.views = 0;
  EXPECT_EQ(bakeRtt(flat, s, {}, &r).code(), StatusCode::kInvalidArgument);
  HeightPatch broken = flat;
  broken.albedo.pop_back();
  EXPECT_EQ(bakeRtt(broken, RttSettings{}, {}, &r).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(makeProceduralPatch("plaid", 64, 0.5f, &flat).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(makeProceduralPatch("weave", 4, 0.5f, &flat).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(makeProceduralPatch("weave", 64, 1.5f, &flat).code(), StatusCode::kInvalidArgument);
}

// A coloured albedo map makes an RGB RTT whose channels scale with the albedo (direct light).
TEST(RttBake, AlbedoMapGivesChannels) {
  RgbImage height, albedo;
  height.width = height.height = albedo.width = albedo.height = 16;
  height.rgb.assign(16 * 16 * 3, 0.0f);
  albedo.rgb.assign(16 * 16 * 3, 0.0f);
  for (std::size_t i = 0; i < 16 * 16; ++i) {
    albedo.rgb[3 * i] = 0.9f;
    albedo.rgb[3 * i + 1] = 0.45f;
    albedo.rgb[3 * i + 2] = 0.1f;
  }
  HeightPatch patch;
  ASSERT_TRUE(makeImagePatch(height, 0.1f, &albedo, 0.5f, &patch).isOk());
  RttSettings s;
  s.spatial = 2;
  s.views = 2;
  const Rtt r = bake(patch, s);
  ASSERT_EQ(r.channels, 3);
  EXPECT_NEAR(at(r, 0, 0, 0, 0, 1)[0] / at(r, 0, 0, 0, 0, 0)[0], 0.5f, 1e-5f);
  EXPECT_NEAR(at(r, 0, 0, 0, 0, 2)[0] / at(r, 0, 0, 0, 0, 0)[0], 0.1f / 0.9f, 1e-5f);
  albedo.rgb[0] = 1.5f;
  EXPECT_EQ(makeImagePatch(height, 0.1f, &albedo, 0.5f, &patch).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace prt::bake

namespace prt::bake {
namespace {

// Reduction: bi-scale with a flat RTT of albedo rho is plain diffuse PRT of the same bake,
// rho times the shadowed transfer vector dotted with the lighting, up to the order-5
// truncation of the clamped cosine that the RTT holds (the matrix M carries the visibility,
// the RTT the cosine); whatever the tangent directions (a flat RTT is zonal about +z).
TEST(BiScale, FlatRttIsDiffusePrtOfTheSameBake) {
  Scene scene;
  test::addPlane(&scene, 1.0f, 8, 0.0f, {0.5f, 0.5f, 0.5f});
  test::addSphere(&scene, {0.0f, 0.6f, 0.0f}, 0.35f, 16, 8, {0.5f, 0.5f, 0.5f});
  BakeOptions o;
  o.order = 5;
  o.samples = 2048;
  o.seed = 3;
  o.glossy = true;
  o.glossyBounces = 0;
  o.interreflection = false;
  o.threads = 2;
  BakeResult r;
  ASSERT_TRUE(bakeTransfer(scene, o, &r).isOk());
  HeightPatch flat;
  ASSERT_TRUE(makeProceduralPatch("flat", 8, 0.7f, &flat).isOk());
  RttSettings s;
  s.spatial = 2;
  s.views = 4;
  Rtt rtt;
  ASSERT_TRUE(bakeRtt(flat, s, {}, &rtt).isOk());

  const std::size_t V = scene.positions.size();
  std::vector<TangentFrame> frames(V), turned(V);
  std::vector<float> uv(2 * V);
  for (std::size_t v = 0; v < V; ++v) {
    const Vec3 n = scene.normals[v];
    const Vec3 helper = std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 t = cross(helper, n);
    t = t * (1.0f / length(t));
    frames[v] = {t, n};
    const Vec3 b = cross(n, t);
    turned[v] = {(t * 0.6f) + (b * 0.8f), n};  // another tangent in the same plane
    uv[2 * v] = 0.37f * static_cast<float>(v % 7);
    uv[2 * v + 1] = 0.11f * static_cast<float>(v % 5);
  }
  std::vector<Rgb> light(25);
  for (int i = 0; i < 25; ++i) light[i] = {0.8f - 0.03f * i, 0.2f + 0.01f * i, (i % 3) * 0.1f};
  light[0] = {1.5f, 1.2f, 0.9f};
  const Vec3 eye{0.4f, 2.0f, 1.5f};
  const MatrixPacking packing = matrixPackingFor(TransferKind::kShadowed, LightingModel::kDistant);
  std::vector<float> biScale(3 * V), biScaleTurned(3 * V);
  ASSERT_TRUE(biScaleExitRadiance(rtt, r.glossyShadowed, 5, packing, 1, scene.positions, frames, uv, eye, true, light, biScale).isOk());
  ASSERT_TRUE(
      biScaleExitRadiance(rtt, r.glossyShadowed, 5, packing, 1, scene.positions, turned, uv, eye, true, light, biScaleTurned).isOk());
  double worst = 0.0, peak = 0.0, turnedWorst = 0.0;
  for (std::size_t v = 0; v < V; ++v) {
    for (int c = 0; c < 3; ++c) {
      double diffuse = 0.0;
      for (int i = 0; i < 25; ++i) diffuse += r.shadowed[v * 25 + i] * (c == 0 ? light[i].r : (c == 1 ? light[i].g : light[i].b));
      diffuse *= 0.7;
      worst = std::max(worst, std::fabs(diffuse - biScale[3 * v + c]));
      peak = std::max(peak, std::fabs(diffuse));
      turnedWorst = std::max(turnedWorst, static_cast<double>(std::fabs(biScale[3 * v + c] - biScaleTurned[3 * v + c])));
    }
  }
  std::printf("flat-RTT bi-scale vs diffuse PRT: worst %.2e of peak %.3f; tangent turned: %.1e\n", worst, peak, turnedWorst);
  EXPECT_GT(peak, 0.1);
  EXPECT_LT(worst, 0.02 * peak) << "beyond the clamped cosine's order-5 truncation";
  EXPECT_LT(turnedWorst, 1e-5 * peak);
}

}  // namespace
}  // namespace prt::bake
