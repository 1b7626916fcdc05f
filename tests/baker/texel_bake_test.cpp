// Transfer textures (baker/transfer/texel_bake.h) with real Embree: against closed forms, the
// vertex bake, and the properties a user checks first (no light under a box, no seam lines).
#include "baker/transfer/texel_bake.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "baker/test_scenes.h"
#include "baker/texture/atlas_samples.h"
#include "baker/transfer/texel_range.h"
#include "prt/glossy_radiance.h"
#include "prt/sh_basis.h"
#include "prt/sh_triple_product.h"
#include "prt/sh_zonal.h"

namespace prt::bake {
namespace {

constexpr float kSqrt4Pi = 3.5449077f;  // DC of constant unit radiance is 2 sqrt(pi)

// A scene with its lightmap UVs, built chart by chart.
struct AtlasScene {
  Scene scene;
  std::vector<Uv> uv;
};

// Appends the quad p0 p1 p2 p3 (in order around it) as two triangles facing `normal`, its
// UVs spanning uv0 (at p0) to uv1 (at p2), u along p0→p1, v along p1→p2.
void addQuad(AtlasScene* s, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, Vec3 normal, Uv uv0, Uv uv1, Rgb albedo) {
  const auto base = static_cast<std::uint32_t>(s->scene.positions.size());
  const Vec3 p[4] = {p0, p1, p2, p3};
  const Uv uv[4] = {uv0, {uv1.u, uv0.v}, uv1, {uv0.u, uv1.v}};
  for (int k = 0; k < 4; ++k) {
    s->scene.positions.push_back(p[k]);
    s->scene.normals.push_back(normal);
    s->scene.albedo.push_back(albedo);
    s->uv.push_back(uv[k]);
  }
  const bool ccw = dot(cross(p1 - p0, p2 - p0), normal) > 0.0f;
  const std::uint32_t order[6] = {0, 1, 2, 0, 2, 3};
  for (int k = 0; k < 6; k += 3) {
    s->scene.indices.push_back(base + order[k]);
    s->scene.indices.push_back(base + (ccw ? order[k + 1] : order[k + 2]));
    s->scene.indices.push_back(base + (ccw ? order[k + 2] : order[k + 1]));
  }
}

// The floor [-half, half]^2 at y = 0, facing +y, as one two-triangle chart over uv [lo, hi]^2.
void addFloor(AtlasScene* s, float half, float lo, float hi, Rgb albedo) {
  addQuad(s, {-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}, {0, 1, 0}, {lo, lo}, {hi, hi},
          albedo);
}

// A closed box [lo, hi] with outward faces, each face its own chart in a 3 x 2 grid of cells
// inside uv [u0, u1] x [v0, v1] (a gap of a tenth of a cell around each chart).
void addBox(AtlasScene* s, Vec3 lo, Vec3 hi, float u0, float u1, float v0, float v1, Rgb albedo) {
  const float cw = (u1 - u0) / 3.0f, ch = (v1 - v0) / 2.0f;
  int cell = 0;
  auto face = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 n) {
    const float cu = u0 + cw * static_cast<float>(cell % 3), cv = v0 + ch * static_cast<float>(cell / 3);
    ++cell;
    addQuad(s, a, b, c, d, n, {cu + 0.1f * cw, cv + 0.1f * ch}, {cu + 0.9f * cw, cv + 0.9f * ch}, albedo);
  };
  face({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}, {0, -1, 0});
  face({lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, {0, 1, 0});
  face({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}, {0, 0, -1});
  face({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, {0, 0, 1});
  face({lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}, {-1, 0, 0});
  face({hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, {1, 0, 0});
}

// A UV sphere whose latitude-longitude grid is its chart, inside uv [u0, u1] x [v0, v1].
void addSphereChart(AtlasScene* s, Vec3 centre, float radius, float u0, float u1, float v0, float v1, Rgb albedo) {
  const std::size_t first = s->scene.positions.size();
  const int slices = 32, stacks = 16;
  test::addSphere(&s->scene, centre, radius, slices, stacks, albedo);
  for (std::size_t k = first; k < s->scene.positions.size(); ++k) {
    const int i = static_cast<int>((k - first) % (slices + 1)), j = static_cast<int>((k - first) / (slices + 1));
    s->uv.push_back({u0 + (u1 - u0) * static_cast<float>(i) / slices, v0 + (v1 - v0) * static_cast<float>(j) / stacks});
  }
}

TexelBakeOptions quickOptions() {
  TexelBakeOptions o;
  o.transfer.order = 4;
  o.transfer.samples = 4096;
  o.transfer.threads = 2;
  return o;
}

std::uint32_t triangleCount(const Scene& s) { return static_cast<std::uint32_t>(s.indices.size() / 3); }

// A plain bilinear read of channel 0 at `uv` (texel centres at (x + 0.5) / size, edges
// clamped), as the client's sampler does: no knowledge of coverage.
float bilinearDc(const std::vector<float>& texture, int stride, const TextureAtlas& atlas, std::uint64_t first, Uv uv) {
  const int w = static_cast<int>(atlas.width), h = static_cast<int>(atlas.height);
  const float px = uv.u * static_cast<float>(w) - 0.5f, py = uv.v * static_cast<float>(h) - 0.5f;
  const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
  const float fx = px - static_cast<float>(x0), fy = py - static_cast<float>(y0);
  float acc = 0.0f;
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, w - 1), y = std::clamp(y0 + dy, 0, h - 1);
      const float weight = (dx ? fx : 1.0f - fx) * (dy ? fy : 1.0f - fy);
      acc += weight * texture[(first + static_cast<std::uint64_t>(y) * atlas.width + x) * stride];
    }
  }
  return acc;
}

// Under constant unit radiance a point of the floor below a sphere (centre c, radius R) at
// distance D sees irradiance pi (1 - (R/D)^2 cos(theta_c)), theta_c the angle from the normal
// to the sphere's centre, while the sphere's cap is wholly above the horizon.
double floorUnderSphere(Vec3 p, Vec3 c, float radius) {
  const Vec3 d = c - p;
  const double dist = length(d);
  return 1.0 - (radius / dist) * (radius / dist) * (d.y / dist);
}

TEST(TexelBake, TwoTriangleFloorShowsTheContactShadowOfASphere) {
  // A vertex bake of this floor has 4 samples, all far from the shadow: it cannot show it.
  AtlasScene s;
  addFloor(&s, 2.0f, 0.0f, 1.0f, {0.5f, 0.5f, 0.5f});
  const Vec3 centre{0.2f, 1.2f, -0.1f};
  const float radius = 0.9f;  // below its centre's height: the cap never reaches the horizon
  addSphereChart(&s, centre, radius, 0.0f, 1.0f, 0.0f, 1.0f, {0.5f, 0.5f, 0.5f});
  const std::vector<TextureAtlas> atlases = {{32, 32, 0, 2}, {64, 32, 2, triangleCount(s.scene) - 2}};
  TexelBakeOptions o = quickOptions();
  o.transfer.interreflection = false;
  TexelBakeResult r;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &r).isOk());
  const int n2 = shCoeffCount(o.transfer.order);
  ASSERT_EQ(r.texels, 32u * 32u + 64u * 32u);
  ASSERT_EQ(r.shadowed.size(), r.texels * n2);
  // Every floor texel is sampled (the chart fills its atlas) at the texel centre.
  double worst = 0.0, darkest = 1.0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const std::size_t t = static_cast<std::size_t>(y) * 32 + x;
      ASSERT_EQ(r.coverage[t], static_cast<std::uint8_t>(TexelCoverage::kSampled));
      const Vec3 p{-2.0f + 4.0f * (x + 0.5f) / 32.0f, 0.0f, -2.0f + 4.0f * (y + 0.5f) / 32.0f};
      const double expected = floorUnderSphere(p, centre, radius);
      const double got = r.shadowed[t * n2] * kSqrt4Pi;
      worst = std::max(worst, std::abs(got - expected));
      darkest = std::min(darkest, got);
      ASSERT_NEAR(r.unshadowed[t * n2] * kSqrt4Pi, 1.0, 1e-3) << x << ", " << y;
    }
  }
  EXPECT_LT(worst, 0.02);   // Monte Carlo with 2048 rays above the plane
  EXPECT_LT(darkest, 0.5);  // the umbra is resolved (closed form 0.4375 below the centre)
}

TEST(TexelBake, NoLightUnderABoxRestingOnTheFloor) {
  // The box's bottom face lies in the floor's plane: a texel sample under it starts its rays
  // inside the box, where every ray hits a back face. It must get no light at all, direct or
  // bounced, however close to the box's edge (and the ray offset must not lift it out).
  AtlasScene s;
  addFloor(&s, 2.0f, 0.0f, 1.0f, {0.8f, 0.8f, 0.8f});
  const Vec3 lo{-0.5f, 0.0f, -0.3f}, hi{0.5f, 0.7f, 0.4f};
  addBox(&s, lo, hi, 0.0f, 1.0f, 0.0f, 1.0f, {0.8f, 0.8f, 0.8f});
  const std::vector<TextureAtlas> atlases = {{64, 64, 0, 2}, {48, 32, 2, 12}};
  TexelBakeOptions o = quickOptions();
  o.transfer.samples = 1024;
  o.transfer.maxBounces = 2;
  TexelBakeResult r;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &r).isOk());
  ASSERT_EQ(r.bounces, 2);
  const int n2 = shCoeffCount(o.transfer.order);
  int under = 0, besideLit = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const std::size_t t = static_cast<std::size_t>(y) * 64 + x;
      const float px = -2.0f + 4.0f * (x + 0.5f) / 64.0f, pz = -2.0f + 4.0f * (y + 0.5f) / 64.0f;
      const bool inside = px > lo.x && px < hi.x && pz > lo.z && pz < hi.z;
      if (inside) {
        ++under;
        for (int i = 0; i < n2; ++i) ASSERT_EQ(r.shadowed[t * n2 + i], 0.0f) << x << ", " << y;
        for (int i = 0; i < 3 * n2; ++i) ASSERT_EQ(r.interreflected[t * 3 * n2 + i], 0.0f) << x << ", " << y;
      } else if (std::abs(px - hi.x) < 0.07f && pz > lo.z && pz < hi.z) {
        // The texels just outside the box's side: half the sky and the lit box wall.
        ++besideLit;
        EXPECT_GT(r.shadowed[t * n2] * kSqrt4Pi, 0.3f) << x << ", " << y;
        EXPECT_GT(r.interreflected[t * 3 * n2], r.shadowed[t * n2] * 0.8f) << x << ", " << y;
      }
    }
  }
  EXPECT_GT(under, 50);
  EXPECT_GT(besideLit, 5);
}

// A floor split along x = 0 into two charts far apart in the atlas, with a sphere's shadow
// across the cut. Measured: how far a client's bilinear read at the cut, from either side,
// is from the continuous surface's value there (the mean of the two texels whose centres
// straddle the cut, half a texel either side), and the largest step between neighbouring
// texels inside a chart (what the shadow's gradient gives anyway).
struct SeamMeasure {
  double seamError = 0, interiorStep = 0;
};

SeamMeasure measureSeam(int dilation, bool stitch) {
  AtlasScene s;
  const Rgb grey{0.5f, 0.5f, 0.5f};
  // Left half x in [-2, 0] -> u in [4, 28] / 64; right half x in [0, 2] -> u in [36, 60] / 64.
  addQuad(&s, {-2, 0, -2}, {0, 0, -2}, {0, 0, 2}, {-2, 0, 2}, {0, 1, 0}, {4 / 64.0f, 4 / 64.0f}, {28 / 64.0f, 52 / 64.0f}, grey);
  addQuad(&s, {0, 0, -2}, {2, 0, -2}, {2, 0, 2}, {0, 0, 2}, {0, 1, 0}, {36 / 64.0f, 4 / 64.0f}, {60 / 64.0f, 52 / 64.0f}, grey);
  addSphereChart(&s, {0.4f, 1.0f, 0.0f}, 0.8f, 0.0f, 1.0f, 0.0f, 1.0f, grey);
  const std::vector<TextureAtlas> atlases = {{64, 64, 0, 4}, {64, 32, 4, triangleCount(s.scene) - 4}};
  TexelBakeOptions o = quickOptions();
  o.transfer.samples = 1024;
  o.transfer.interreflection = false;
  o.dilation = dilation;
  o.stitchSeams = stitch;
  TexelBakeResult r;
  EXPECT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &r).isOk());
  if (stitch && dilation > 0) {
    EXPECT_GE(r.seamTexels, 2u * 46u);  // both sides of the cut, every row but the corners
  }
  const int n2 = shCoeffCount(o.transfer.order);
  SeamMeasure m;
  for (int k = 0; k <= 200; ++k) {
    const float z = -1.8f + 3.6f * static_cast<float>(k) / 200.0f;  // along the seam x = 0
    const float v = (4.0f + 48.0f * (z + 2.0f) / 4.0f) / 64.0f;
    const float left = bilinearDc(r.shadowed, n2, atlases[0], 0, {28 / 64.0f, v});
    const float right = bilinearDc(r.shadowed, n2, atlases[0], 0, {36 / 64.0f, v});
    const float continuous = 0.5f * (bilinearDc(r.shadowed, n2, atlases[0], 0, {27.5f / 64.0f, v}) +
                                     bilinearDc(r.shadowed, n2, atlases[0], 0, {36.5f / 64.0f, v}));
    m.seamError = std::max({m.seamError, static_cast<double>(std::abs(left - continuous)),
                            static_cast<double>(std::abs(right - continuous))});
  }
  for (int y = 5; y < 51; ++y) {
    for (int x = 4; x < 59; ++x) {
      if (x == 27 || (x >= 28 && x < 36)) continue;  // pairs that straddle the gutter
      const std::size_t t = static_cast<std::size_t>(y) * 64 + x;
      m.interiorStep = std::max(m.interiorStep, static_cast<double>(std::abs(r.shadowed[t * n2] - r.shadowed[(t + 1) * n2])));
      m.interiorStep = std::max(m.interiorStep, static_cast<double>(std::abs(r.shadowed[t * n2] - r.shadowed[(t + 64) * n2])));
    }
  }
  return m;
}

TEST(TexelBake, ChartSeamsShowNoLineUnderBilinearFiltering) {
  const SeamMeasure stitched = measureSeam(3, true);
  ASSERT_GT(stitched.interiorStep, 0.002);  // the shadow does cross the seam
  // Both sides read the same texels across the cut: far below one texel step.
  EXPECT_LE(stitched.seamError, 0.1 * stitched.interiorStep);
  // Dilation alone repeats each chart's edge, half a texel step off on each side: a line
  // where the gradient is steep, which this measure sees and the stitching removes.
  const SeamMeasure dilated = measureSeam(3, false);
  EXPECT_GT(dilated.seamError, 0.25 * stitched.interiorStep);
  // Without gutters the filter blends in the empty background: a dark line.
  const SeamMeasure bare = measureSeam(0, true);
  EXPECT_GT(bare.seamError, 3.0 * stitched.interiorStep);
  std::printf("seam error / largest texel step: stitched %.3f, dilated only %.3f, no gutter %.3f\n",
              stitched.seamError / stitched.interiorStep, dilated.seamError / stitched.interiorStep,
              bare.seamError / stitched.interiorStep);
}

// A cube's six charts meet at creases, not seams: the radiance is discontinuous across a
// cube's edge, so each face's gutter must repeat the face (dilation), not carry the
// neighbouring face's transfer over the edge, which would blend the two faces in the last
// texel of each. Measured on the l = 1 coefficients (the transfer's direction, which differs
// from face to face; a lone convex box sees the whole sky from every face, so each face's
// transfer is one vector up to Monte Carlo noise).
TEST(TexelBake, ChartEdgesOfACubeAreCreasesNotSeams) {
  AtlasScene s;
  addBox(&s, {-0.5f, 0.5f, -0.5f}, {0.5f, 1.5f, 0.5f}, 0.0f, 1.0f, 0.0f, 1.0f, Rgb{0.5f, 0.5f, 0.5f});
  const std::vector<TextureAtlas> atlases = {{64, 64, 0, triangleCount(s.scene)}};
  TexelBakeOptions o = quickOptions();
  o.transfer.order = 2;
  o.transfer.samples = 1024;
  o.transfer.interreflection = false;
  TexelBakeResult r;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &r).isOk());
  EXPECT_EQ(r.seamTexels, 0u);
  const int n2 = shCoeffCount(o.transfer.order);
  double worst = 0.0, magnitude = 0.0;
  for (int cell = 0; cell < 6; ++cell) {
    const float cw = 1.0f / 3.0f, ch = 0.5f;
    const float cu = cw * static_cast<float>(cell % 3), cv = ch * static_cast<float>(cell / 3);
    const Uv centre{cu + 0.5f * cw, cv + 0.5f * ch};
    const Uv edges[4] = {{cu + 0.1f * cw, centre.v}, {cu + 0.9f * cw, centre.v}, {centre.u, cv + 0.1f * ch}, {centre.u, cv + 0.9f * ch}};
    for (int i = 1; i < n2; ++i) {
      std::vector<float> coefficient(r.shadowed.size() / n2);
      for (std::size_t t = 0; t < coefficient.size(); ++t) coefficient[t] = r.shadowed[t * n2 + i];
      const float inside = bilinearDc(coefficient, 1, atlases[0], 0, centre);
      magnitude = std::max(magnitude, static_cast<double>(std::abs(inside)));
      for (const Uv& e : edges) worst = std::max(worst, static_cast<double>(std::abs(bilinearDc(coefficient, 1, atlases[0], 0, e) - inside)));
    }
  }
  ASSERT_GT(magnitude, 0.25);  // albedo 0.5 x the clamped cosine's l = 1 part, 0.65: half a face's blend would show
  EXPECT_LE(worst, 0.02 * magnitude);
  std::printf("cube chart edges: largest l=1 difference edge - centre %.4f of %.3f\n", worst, magnitude);
}

TEST(TexelBake, CoverageMarksSamplesAndTheDilatedGutter) {
  AtlasScene s;
  // One chart in the middle of a 32 x 32 atlas: texels 8..23 in both directions.
  addFloor(&s, 1.0f, 8 / 32.0f, 24 / 32.0f, {0.5f, 0.5f, 0.5f});
  const std::vector<TextureAtlas> atlases = {{32, 32, 0, 2}};
  TexelBakeOptions o = quickOptions();
  o.transfer.samples = 64;
  o.transfer.interreflection = false;
  o.dilation = 2;
  TexelBakeResult r;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &r).isOk());
  EXPECT_EQ(r.sampledTexels, 16u * 16u);
  const int n2 = shCoeffCount(o.transfer.order);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const int distance = std::max(std::max(8 - x, x - 23), std::max(8 - y, y - 23));
      const auto expected = distance <= 0 ? TexelCoverage::kSampled : distance <= 2 ? TexelCoverage::kGutter : TexelCoverage::kEmpty;
      const std::size_t t = static_cast<std::size_t>(y) * 32 + x;
      ASSERT_EQ(r.coverage[t], static_cast<std::uint8_t>(expected)) << x << ", " << y;
      // A lone plane is lit the same everywhere: the gutter holds exactly the chart's value.
      if (expected == TexelCoverage::kEmpty) {
        ASSERT_EQ(r.shadowed[t * n2], 0.0f);
      } else {
        ASSERT_FLOAT_EQ(r.shadowed[t * n2], r.shadowed[(16 * 32 + 16) * n2]);
      }
    }
  }
}

// An L of floor and wall, n x n quads each, every quad its own pair of triangles; the floor's
// UVs on the atlas's left half, the wall's on its right.
AtlasScene makeFloorAndWall(int n) {
  AtlasScene s;
  const Rgb floorColour{0.8f, 0.6f, 0.4f}, wallColour{0.3f, 0.7f, 0.9f};
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float x0 = -1.0f + 2.0f * i / n, x1 = -1.0f + 2.0f * (i + 1) / n;
      const float a0 = 2.0f * j / n, a1 = 2.0f * (j + 1) / n;
      const float u0 = 0.02f + 0.46f * i / n, u1 = 0.02f + 0.46f * (i + 1) / n;
      const float v0 = 0.02f + 0.96f * j / n, v1 = 0.02f + 0.96f * (j + 1) / n;
      addQuad(&s, {x0, 0, a0}, {x1, 0, a0}, {x1, 0, a1}, {x0, 0, a1}, {0, 1, 0}, {u0, v0}, {u1, v1}, floorColour);
      addQuad(&s, {x0, a0, 0}, {x1, a0, 0}, {x1, a1, 0}, {x0, a1, 0}, {0, 0, 1}, {u0 + 0.5f, v0}, {u1 + 0.5f, v1},
              wallColour);
    }
  }
  return s;
}

TEST(TexelBake, BouncesAgreeWithAConvergedVertexBake) {
  // The texel bake's bounce textures (bilinear texel reads at the hit points) against the
  // vertex bake's independent gather (vertex interpolation), on a mesh dense enough for the
  // latter to have converged: refining it from 24 to 48 quads a side moves bounce 3 by 10%,
  // towards the texel bake, so the reference is the 48 one (and the texel bake's 24-quad mesh
  // has bigger triangles than texels, as transfer textures are meant for).
  AtlasScene coarse = makeFloorAndWall(24);
  const std::vector<TextureAtlas> atlases = {{128, 128, 0, triangleCount(coarse.scene)}};
  TexelBakeOptions o = quickOptions();
  o.transfer.samples = 1024;
  o.transfer.maxBounces = 3;
  o.transfer.bounceThreshold = 0.0;
  TexelBakeResult texel;
  ASSERT_TRUE(bakeTexelTransfer(coarse.scene, coarse.uv, atlases, o, &texel).isOk());
  BakeResult vertex;
  ASSERT_TRUE(bakeTransfer(makeFloorAndWall(48).scene, o.transfer, &vertex).isOk());
  ASSERT_EQ(texel.bounces, 3);
  ASSERT_EQ(vertex.bounces, 3);
  EXPECT_EQ(texel.unmappedHits, 0u);
  for (int b = 0; b <= 3; ++b) {
    ASSERT_GT(vertex.bounceEnergy[b], 0.0);
    EXPECT_NEAR(texel.bounceEnergy[b] / vertex.bounceEnergy[b], 1.0, 0.05) << "bounce " << b;
  }
}

TEST(TexelBake, ResultsDoNotDependOnTheThreadCount) {
  AtlasScene s;
  addFloor(&s, 2.0f, 0.0f, 1.0f, {0.7f, 0.6f, 0.5f});
  addBox(&s, {-0.5f, 0.0f, -0.5f}, {0.5f, 0.8f, 0.5f}, 0.0f, 1.0f, 0.0f, 1.0f, {0.4f, 0.8f, 0.3f});
  const std::vector<TextureAtlas> atlases = {{40, 40, 0, 2}, {30, 20, 2, 12}};
  TexelBakeOptions o = quickOptions();
  o.transfer.samples = 256;
  o.transfer.maxBounces = 2;
  TexelBakeResult one, two;
  o.transfer.threads = 1;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &one).isOk());
  o.transfer.threads = 2;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &two).isOk());
  EXPECT_EQ(one.unshadowed, two.unshadowed);
  EXPECT_EQ(one.shadowed, two.shadowed);
  EXPECT_EQ(one.interreflected, two.interreflected);
  EXPECT_EQ(one.coverage, two.coverage);
  EXPECT_EQ(one.bounceEnergy, two.bounceEnergy);
}

// The pieces a sharded bake runs (texel_range.h): the direct pass over two block ranges is the
// whole pass's, and a bounce's gather refuses hit records that do not fit the scene (a
// sharded bake reads them from a file) before it reads the texture at them.
TEST(TexelBake, RangesPutTogetherAreTheWholeDirectPassAndBadHitsAreRefused) {
  AtlasScene s;
  addFloor(&s, 2.0f, 0.0f, 1.0f, {0.7f, 0.6f, 0.5f});
  addBox(&s, {-0.5f, 0.0f, -0.5f}, {0.5f, 0.8f, 0.5f}, 0.0f, 1.0f, 0.0f, 1.0f, {0.4f, 0.8f, 0.3f});
  const std::vector<TextureAtlas> atlases = {{40, 40, 0, 2}, {30, 20, 2, 12}};
  TexelBakeOptions o = quickOptions();
  o.transfer.maxBounces = 1;
  TexelReceivers rec;
  ASSERT_TRUE(prepareTexelReceivers(s.scene, s.uv, atlases, o, &rec).isOk());
  ASSERT_GT(rec.count(), 2 * kBlockVertices);
  TexelDirectRange whole, first, rest;
  ASSERT_TRUE(bakeTexelDirectRange(s.scene, rec, o, 0, rec.count(), &whole).isOk());
  ASSERT_TRUE(bakeTexelDirectRange(s.scene, rec, o, 0, kBlockVertices, &first).isOk());
  ASSERT_TRUE(bakeTexelDirectRange(s.scene, rec, o, kBlockVertices, rec.count(), &rest).isOk());
  std::vector<float> shadowed = first.shadowed;
  shadowed.insert(shadowed.end(), rest.shadowed.begin(), rest.shadowed.end());
  EXPECT_EQ(shadowed, whole.shadowed);
  ASSERT_EQ(rest.blocks.size() + 1, whole.blocks.size());
  EXPECT_EQ(rest.blocks[0].hitStart, whole.blocks[1].hitStart);
  EXPECT_EQ(rest.blocks[0].hits.size(), whole.blocks[1].hits.size());
  // Not block-aligned: refused, naming the range.
  const Status unaligned = bakeTexelDirectRange(s.scene, rec, o, 10, 70, &first);
  EXPECT_EQ(unaligned.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(unaligned.message().find("[10, 70)"), std::string::npos) << unaligned.message();

  std::vector<float> b0;
  double e0 = 0.0;
  ASSERT_TRUE(texelFirstBounce(rec, o.transfer.order, whole.shadowed, &b0, &e0).isOk());
  TexelTexture texture;
  ASSERT_TRUE(scatterTexels(rec, atlases, b0, 3 * shCoeffCount(o.transfer.order), o.dilation, &texture).isOk());
  std::vector<HitBlock> blocks = whole.blocks;
  ASSERT_FALSE(blocks[1].hits.empty());
  std::vector<float> current;
  std::vector<double> energy;
  std::uint64_t unmapped = 0;
  PassStats stats;
  ASSERT_TRUE(gatherTexelBounceRange(s.scene, s.uv, atlases, rec, o, 1, 0, hitBlockViews(blocks), texture, &current,
                                     &energy, &unmapped, &stats)
                  .isOk());
  EXPECT_GT(energy[0] + energy[1], 0.0);
  blocks[1].hits[0].triangle = static_cast<std::uint32_t>(s.scene.indices.size() / 3);  // one past the triangles
  Status bad = gatherTexelBounceRange(s.scene, s.uv, atlases, rec, o, 1, 0, hitBlockViews(blocks), texture, &current,
                                      &energy, &unmapped, &stats);
  EXPECT_EQ(bad.code(), StatusCode::kCorrupt);
  EXPECT_NE(bad.message().find("texel block 1"), std::string::npos) << bad.message();
  blocks[1].hits[0] = whole.blocks[1].hits[0];
  blocks[1].hits[0].weight = std::nanf("");
  bad = gatherTexelBounceRange(s.scene, s.uv, atlases, rec, o, 1, 0, hitBlockViews(blocks), texture, &current, &energy,
                               &unmapped, &stats);
  EXPECT_EQ(bad.code(), StatusCode::kCorrupt);
}

TEST(TexelBake, RejectsBadInputWithAClearMessage) {
  AtlasScene s;
  addFloor(&s, 1.0f, 0.1f, 0.9f, {0.5f, 0.5f, 0.5f});
  const std::vector<TextureAtlas> good = {{16, 16, 0, 2}};
  TexelBakeResult r;
  r.sampledTexels = 7;  // untouched on error
  auto fails = [&](const std::vector<Uv>& uv, const std::vector<TextureAtlas>& atlases, const TexelBakeOptions& o,
                   const char* words) {
    const Status st = bakeTexelTransfer(s.scene, uv, atlases, o, &r);
    EXPECT_FALSE(st.isOk()) << words;
    EXPECT_NE(st.message().find(words), std::string::npos) << st.message();
    EXPECT_EQ(r.sampledTexels, 7u);
  };
  TexelBakeOptions o = quickOptions();
  o.transfer.samples = 64;
  TexelBakeOptions glossy = o;
  glossy.transfer.glossy = true;
  fails(s.uv, good, glossy, "glossy");
  TexelBakeOptions dilation = o;
  dilation.dilation = -1;
  fails(s.uv, good, dilation, "dilation");
  fails({s.uv.begin(), s.uv.end() - 1}, good, o, "UVs for");
  fails(s.uv, {}, o, "atlas count");
  fails(s.uv, {{16, 16, 0, 1}}, o, "hold 1 triangles");
  fails(s.uv, {{16, 16, 0, 1}, {16, 16, 0, 1}}, o, "atlas 1 starts at triangle 0, expected 1");
  fails(s.uv, {{0, 16, 0, 2}}, o, "atlas 0 is 0");
  std::vector<Uv> outside = s.uv;
  outside[2].u = 1.5f;
  fails(outside, good, o, "atlas 0");
  std::vector<Uv> nan = s.uv;
  nan[1].v = std::nanf("");
  fails(nan, good, o, "atlas 0");
  TexelBakeOptions order = o;
  order.transfer.order = 9;
  fails(s.uv, good, order, "order");
}

}  // namespace
}  // namespace prt::bake

namespace prt::bake {
namespace {

// TPFL (docs/transfer-textures.md, "Glossy by the triple product"): a texel's visibility
// vector at order 2n - 1, multiplied with the lighting through the Gaunt tensor, gives the
// glossy radiance that the transfer matrix of the same visibility gives (docs/glossy.md).
// The matrices come from the vertex bake's glossy pass, run on the texel samples' own
// positions and normals (added to the scene as extra vertices: same triangles, same rays).
TEST(TexelBake, TpflGlossyEqualsTheTransferMatrixOfTheSameVisibility) {
  AtlasScene s;
  addFloor(&s, 2.0f, 0.0f, 1.0f, {0.5f, 0.5f, 0.5f});
  addSphereChart(&s, {0.2f, 1.2f, -0.1f}, 0.9f, 0.0f, 1.0f, 0.0f, 1.0f, {0.5f, 0.5f, 0.5f});
  const std::vector<TextureAtlas> atlases = {{16, 16, 0, 2}, {32, 16, 2, triangleCount(s.scene) - 2}};
  TexelBakeOptions o = quickOptions();
  o.transfer.order = 5;
  o.transfer.samples = 1024;
  o.transfer.interreflection = false;
  o.visibilityOrder = 9;  // 2n - 1
  TexelBakeResult r;
  ASSERT_TRUE(bakeTexelTransfer(s.scene, s.uv, atlases, o, &r).isOk());
  ASSERT_EQ(r.visibilityOrder, 9);
  ASSERT_EQ(r.visibility.size(), r.texels * 81);

  AtlasSamples samples;
  ASSERT_TRUE(rasteriseAtlases(s.scene.positions, s.scene.normals, s.scene.albedo, s.scene.indices, s.uv, atlases,
                               &samples)
                  .isOk());
  Scene withReceivers = s.scene;
  const std::size_t first = withReceivers.positions.size(), count = samples.texels.size();
  std::vector<Vec3> positions, normals;
  std::vector<float> visibility;
  for (const AtlasTexel& t : samples.texels) {
    withReceivers.positions.push_back(t.position);
    withReceivers.normals.push_back(t.normal);
    withReceivers.albedo.push_back(t.albedo);
    positions.push_back(t.position);
    normals.push_back(t.normal);
    visibility.insert(visibility.end(), &r.visibility[t.index * 81], &r.visibility[t.index * 81] + 81);
  }
  BakeOptions g = o.transfer;
  g.glossy = true;
  g.glossyBounces = 0;
  BakeResult matrices;
  ASSERT_TRUE(bakeTransfer(withReceivers, g, &matrices).isOk());
  const MatrixPacking packing = matrixPackingFor(TransferKind::kShadowed, LightingModel::kDistant);
  const std::size_t entries = matrixEntryCount(5, packing);
  const std::span<const float> receiverMatrices(&matrices.glossyShadowed[first * entries], count * entries);

  // Coloured, lopsided lighting: two disc lights and a dim sky.
  std::vector<Rgb> light(25, Rgb{0, 0, 0});
  std::vector<float> zonal(5), placed(25);
  const struct { Vec3 axis; float zeta; Rgb colour; } lights[] = {
      {{0.4f, 1.0f, 0.3f}, 0.3f, {3.0f, 2.0f, 1.0f}}, {{-1.0f, 0.5f, -0.2f}, 0.6f, {0.2f, 0.5f, 1.5f}},
      {{0.0f, 1.0f, 0.0f}, 3.14159265f, {0.1f, 0.1f, 0.1f}}};
  for (const auto& l : lights) {
    ASSERT_TRUE(zonalCircularLight(5, l.zeta, 1.0f, zonal).isOk());
    ASSERT_TRUE(placeZonal(5, zonal, l.axis, placed).isOk());
    for (int i = 0; i < 25; ++i) light[i] = light[i] + Rgb{l.colour.r * placed[i], l.colour.g * placed[i], l.colour.b * placed[i]};
  }
  const std::vector<SpecularMaterial> material(count, SpecularMaterial{{0.9f, 0.6f, 0.3f}, 20.0f, 1.0f});
  const GlossyView view{{1.5f, 2.5f, 3.0f}, true};
  std::vector<float> byMatrix(3 * count), byTpfl(3 * count), byTruncated(3 * count);
  ASSERT_TRUE(glossyExitRadiance(receiverMatrices, 5, packing, 1, positions, normals, material, view, light, byMatrix).isOk());
  ShTripleProduct product;
  ASSERT_TRUE(ShTripleProduct::make(5, 9, &product).isOk());
  ASSERT_TRUE(tpflGlossyExitRadiance(product, visibility, positions, normals, material, view, light, byTpfl).isOk());
  // The usual economy, visibility truncated to n bands, is not exact: the test can tell.
  ShTripleProduct square;
  ASSERT_TRUE(ShTripleProduct::make(5, 5, &square).isOk());
  std::vector<float> truncated;
  for (std::size_t p = 0; p < count; ++p) truncated.insert(truncated.end(), &visibility[p * 81], &visibility[p * 81] + 25);
  ASSERT_TRUE(tpflGlossyExitRadiance(square, truncated, positions, normals, material, view, light, byTruncated).isOk());

  double largest = 0.0, worst = 0.0, worstTruncated = 0.0;
  for (float x : byMatrix) largest = std::max(largest, double{std::abs(x)});
  for (std::size_t i = 0; i < byMatrix.size(); ++i) {
    worst = std::max(worst, double{std::abs(byTpfl[i] - byMatrix[i])});
    worstTruncated = std::max(worstTruncated, double{std::abs(byTruncated[i] - byMatrix[i])});
  }
  std::printf("TPFL vs transfer matrix over %zu texels: worst %.3g of the largest radiance %.4g (%.2g relative); "
              "visibility truncated to 5 bands: %.3g relative\n",
              count, worst, largest, worst / largest, worstTruncated / largest);
  ASSERT_GT(largest, 0.1);
  EXPECT_LT(worst, 2e-5 * largest);           // float rounding of two different summation orders
  EXPECT_GT(worstTruncated, 1e-3 * largest);  // the n-band economy is visibly not exact

  // Local lighting remaps the light's basis per ray: no product form, refused by name.
  TexelBakeOptions local = o;
  local.transfer.lighting.model = LightingModel::kLocalSphere;
  local.transfer.lighting.center = {0, 1, 0};
  local.transfer.lighting.radius = 5.0f;
  TexelBakeResult unused;
  const Status refused = bakeTexelTransfer(s.scene, s.uv, atlases, local, &unused);
  EXPECT_NE(refused.message().find("distant lighting"), std::string::npos) << refused.message();
}

}  // namespace
}  // namespace prt::bake
