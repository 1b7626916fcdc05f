// The UV atlas check and choice (baker/scene/uv_atlas_check.h, uv_atlas_choice.h) on
// hand-made layouts: a valid two-chart atlas passes; overlapping, mirrored or stacked charts,
// out-of-range, NaN, zero-area UVs and charts closer than the gutter are each reported,
// naming the UV set and a triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "baker/scene/uv_atlas_check.h"
#include "baker/scene/uv_atlas_choice.h"
#include "warning_lines.h"

namespace prt::bake {
namespace {

using test::anyContains;
using test::joined;

// Two unit squares in 3D (z = 0 and z = 1), two triangles each, so that they are two charts
// whatever their UVs; chartA/chartB give each square's UV rectangle (u0, v0, u1, v1).
struct TwoSquares {
  std::vector<Vec3> positions;
  std::vector<std::uint32_t> indices;
  std::vector<Uv> uvs;
};

TwoSquares twoSquares(const float a[4], const float b[4], bool mirrorB = false) {
  TwoSquares s;
  for (int k = 0; k < 2; ++k) {
    const float* r = k == 0 ? a : b;
    const float z = static_cast<float>(k);
    const auto base = static_cast<std::uint32_t>(s.positions.size());
    s.positions.insert(s.positions.end(), {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}});
    const bool mirror = k == 1 && mirrorB;
    // Mirroring swaps u: the square's left edge maps to the rectangle's right edge.
    const float u0 = mirror ? r[2] : r[0], u1 = mirror ? r[0] : r[2];
    s.uvs.insert(s.uvs.end(), {{u0, r[1]}, {u1, r[1]}, {u1, r[3]}, {u0, r[3]}});
    s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  return s;
}

UvAtlasReport check(const TwoSquares& s, UvAtlasTarget target = {64, 64, 2}) {
  UvAtlasReport r;
  const Status st = checkUvAtlas(s.positions, s.indices, s.uvs, target, "TEXCOORD_1", &r);
  EXPECT_TRUE(st.isOk()) << st.message();
  return r;
}

const float kLeft[4] = {0.05f, 0.05f, 0.45f, 0.45f};
const float kRight[4] = {0.55f, 0.05f, 0.95f, 0.45f};

TEST(UvAtlasCheck, ValidTwoChartAtlasPasses) {
  const UvAtlasReport r = check(twoSquares(kLeft, kRight));
  EXPECT_TRUE(r.valid()) << r.summary() << "\n" << joined(r.problems);
  EXPECT_EQ(r.triangles, 4u);
  EXPECT_EQ(r.charts, 2u);
  EXPECT_EQ(r.overlappingPairs, 0u) << "the diagonal each square's two triangles share is not an overlap";
  // Each rectangle is 25.6 texels wide at 64: 26 or 27 texels touched per side, conservatively.
  EXPECT_GE(r.usedTexels, 2u * 26 * 26);
  EXPECT_LE(r.usedTexels, 2u * 27 * 27);
  EXPECT_NEAR(r.usedTexelFraction, r.usedTexels / 4096.0, 1e-12);
  EXPECT_NE(r.summary().find("valid; 2 charts"), std::string::npos) << r.summary();
}

TEST(UvAtlasCheck, OverlappingChartsAreReported) {
  const float shifted[4] = {0.3f, 0.3f, 0.7f, 0.7f};
  const UvAtlasReport r = check(twoSquares(kLeft, shifted));
  EXPECT_FALSE(r.valid());
  EXPECT_GT(r.overlappingPairs, 0u);
  EXPECT_TRUE(anyContains(r.problems, "TEXCOORD_1: triangles ")) << joined(r.problems);
  EXPECT_TRUE(anyContains(r.problems, "overlap in UV space")) << joined(r.problems);
}

TEST(UvAtlasCheck, StackedAndMirroredChartsAreReported) {
  for (bool mirror : {false, true}) {
    SCOPED_TRACE(mirror ? "mirrored" : "stacked");
    const UvAtlasReport r = check(twoSquares(kLeft, kLeft, mirror));
    EXPECT_FALSE(r.valid());
    // Every triangle of one square lies on both triangles of the other (or on one, exactly
    // stacked, plus a half-overlap with the other): at least 2 pairs.
    EXPECT_GE(r.overlappingPairs, 2u) << r.summary();
    EXPECT_EQ(r.charts, 2u) << "the copy shares UVs but not positions: a chart of its own";
    // The rectangles are 25.6 texels wide: the worst pair overlaps by many texels.
    EXPECT_GT(r.deepestOverlapTexels, 5.0) << r.summary();
  }
}

TEST(UvAtlasCheck, ChartsCloserThanThePaddingAreReported) {
  // 0.1 texel apart at 64 texels (28.8 and 28.9): both touch texel column 28.
  const float near[4] = {28.9f / 64, 0.05f, 0.9f, 0.45f};
  EXPECT_GT(check(twoSquares(kLeft, near)).paddingConflicts, 0u);
  // 3 texels apart: fine without padding or with 2, not with 4.
  const float apart[4] = {0.45f + 3.0f / 64, 0.05f, 0.95f, 0.45f};
  EXPECT_TRUE(check(twoSquares(kLeft, apart), {64, 64, 0}).valid());
  EXPECT_TRUE(check(twoSquares(kLeft, apart), {64, 64, 2}).valid());
  const UvAtlasReport tight = check(twoSquares(kLeft, apart), {64, 64, 4});
  EXPECT_FALSE(tight.valid());
  EXPECT_GT(tight.paddingConflicts, 0u);
  EXPECT_TRUE(anyContains(tight.problems, "closer than 4 texels")) << joined(tight.problems);
  // The same layout at a coarser texture: 1.5 texels apart at 32, below a padding of 2.
  EXPECT_FALSE(check(twoSquares(kLeft, apart), {32, 32, 2}).valid());
}

TEST(UvAtlasCheck, OutOfRangeUvIsReported) {
  TwoSquares s = twoSquares(kLeft, kRight);
  s.uvs[6].u = 1.25f;  // a corner of both of the second square's triangles
  const UvAtlasReport r = check(s);
  EXPECT_FALSE(r.valid());
  EXPECT_EQ(r.outOfRange, 2u);
  EXPECT_TRUE(anyContains(r.problems, "TEXCOORD_1: triangle 2 has a UV outside [0, 1]")) << joined(r.problems);
  s.uvs[6].u = -0.01f;
  EXPECT_EQ(check(s).outOfRange, 2u);
  // Far outside: the grid and texel indices are clamped before any conversion to int.
  s.uvs[6] = {1e30f, -1e30f};
  EXPECT_EQ(check(s).outOfRange, 2u);
}

TEST(UvAtlasCheck, NonFiniteUvIsReported) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    TwoSquares s = twoSquares(kLeft, kRight);
    s.uvs[7].v = bad;  // only the second square's second triangle uses vertex 7
    const UvAtlasReport r = check(s);
    EXPECT_FALSE(r.valid());
    EXPECT_EQ(r.nonFinite, 1u);
    EXPECT_TRUE(anyContains(r.problems, "TEXCOORD_1: triangle 3 has a non-finite")) << joined(r.problems);
  }
}

TEST(UvAtlasCheck, ZeroAreaUvTriangleIsReported) {
  TwoSquares s = twoSquares(kLeft, kRight);
  s.uvs[0] = s.uvs[1];  // triangle 0 collapses to an edge in UV; triangle 1 keeps its area
  const UvAtlasReport r = check(s);
  EXPECT_FALSE(r.valid());
  EXPECT_EQ(r.degenerate, 1u);
  EXPECT_TRUE(anyContains(r.problems, "TEXCOORD_1: triangle 0 has zero UV area")) << joined(r.problems);
}

TEST(UvAtlasCheck, ZeroAreaSurfaceTriangleNeedsNoUvArea) {
  TwoSquares s = twoSquares(kLeft, kRight);
  s.positions[0] = s.positions[1];  // triangle 0 has no surface either: nothing to bake there
  s.uvs[0] = s.uvs[1];
  EXPECT_EQ(check(s).degenerate, 0u);
}

TEST(UvAtlasCheck, UnusableArgumentsAreErrors) {
  const TwoSquares s = twoSquares(kLeft, kRight);
  UvAtlasReport r;
  std::vector<Uv> fewer(s.uvs.begin(), s.uvs.end() - 1);
  EXPECT_FALSE(checkUvAtlas(s.positions, s.indices, fewer, {}, "TEXCOORD_0", &r).isOk());
  std::vector<std::uint32_t> bad = s.indices;
  bad[4] = 99;
  const Status st = checkUvAtlas(s.positions, bad, s.uvs, {}, "TEXCOORD_0", &r);
  ASSERT_FALSE(st.isOk());
  EXPECT_NE(st.message().find("TEXCOORD_0"), std::string::npos) << st.message();
  EXPECT_FALSE(checkUvAtlas(s.positions, s.indices, s.uvs, {0, 64, 1}, "TEXCOORD_0", &r).isOk());
  EXPECT_FALSE(checkUvAtlas(s.positions, s.indices, s.uvs, {64, kMaxAtlasSize + 1, 1}, "TEXCOORD_0", &r).isOk());
  EXPECT_FALSE(checkUvAtlas(s.positions, s.indices, s.uvs, {64, 64, -1}, "TEXCOORD_0", &r).isOk());
}

TEST(UvAtlasCheck, FullyStackedLayoutStopsCounting) {
  // 200 copies of one chart at the same place: 2 × 200 triangles, ~80 000 overlapping pairs.
  TwoSquares s;
  for (int copy = 0; copy < 200; ++copy) {
    const TwoSquares one = twoSquares(kLeft, kLeft);
    const auto base = static_cast<std::uint32_t>(s.positions.size());
    for (int v = 0; v < 4; ++v) {
      s.positions.push_back({one.positions[v].x, one.positions[v].y, static_cast<float>(copy)});
      s.uvs.push_back(one.uvs[v]);
    }
    for (int i = 0; i < 6; ++i) s.indices.push_back(base + one.indices[i]);
  }
  const UvAtlasReport r = check(s);
  EXPECT_TRUE(r.overlapCountCapped);
  EXPECT_EQ(r.overlappingPairs, kMaxOverlapsCounted);
  EXPECT_NE(r.summary().find("at least"), std::string::npos) << r.summary();
}

TEST(UvAtlasCheck, ManyFullSquareTrianglesStayWithinBudget) {
  // 20 000 triangles each covering half of [0, 1]²: without the grid and texel budgets this
  // is 4·10^8 grid entries and 8·10^7 texel tests.
  TwoSquares s;
  for (int t = 0; t < 20000; ++t) {
    const auto base = static_cast<std::uint32_t>(s.positions.size());
    const float z = static_cast<float>(t);
    s.positions.insert(s.positions.end(), {{0, 0, z}, {1, 0, z}, {0, 1, z}});
    s.uvs.insert(s.uvs.end(), {{0, 0}, {1, 0}, {0, 1}});
    s.indices.insert(s.indices.end(), {base, base + 1, base + 2});
  }
  const UvAtlasReport r = check(s);
  EXPECT_TRUE(r.overlapCountCapped);
  EXPECT_TRUE(r.rasterIncomplete);
  EXPECT_FALSE(r.valid());
  EXPECT_NE(r.summary().find("texel statistics incomplete"), std::string::npos) << r.summary();
}

Scene sceneOf(const TwoSquares& s) {
  Scene scene;
  scene.positions = s.positions;
  scene.indices = s.indices;
  return scene;
}

TEST(UvAtlasChoice, PrefersTexcoord1) {
  Scene scene = sceneOf(twoSquares(kLeft, kRight));
  scene.texcoord[0] = twoSquares(kLeft, kRight).uvs;
  scene.texcoord[1] = twoSquares(kRight, kLeft).uvs;
  UvAtlasChoice c;
  ASSERT_TRUE(chooseUvAtlas(scene, {64, 64, 2}, &c).isOk());
  EXPECT_EQ(c.texcoord, 1);
  EXPECT_TRUE(c.rejected.empty()) << joined(c.rejected);
  EXPECT_EQ(c.report.charts, 2u);
}

TEST(UvAtlasChoice, FallsBackToTexcoord0WithTheReason) {
  Scene scene = sceneOf(twoSquares(kLeft, kRight));
  scene.texcoord[0] = twoSquares(kLeft, kRight).uvs;
  scene.texcoord[1] = twoSquares(kLeft, kLeft, true).uvs;  // mirrored onto itself
  UvAtlasChoice c;
  ASSERT_TRUE(chooseUvAtlas(scene, {64, 64, 2}, &c).isOk());
  EXPECT_EQ(c.texcoord, 0);
  ASSERT_EQ(c.rejected.size(), 1u);
  EXPECT_NE(c.rejected[0].find("TEXCOORD_1: "), std::string::npos) << c.rejected[0];
  EXPECT_NE(c.rejected[0].find("overlapping triangle pairs"), std::string::npos) << c.rejected[0];
}

TEST(UvAtlasChoice, NeedsGenerationWhenNeitherIsValid) {
  Scene scene = sceneOf(twoSquares(kLeft, kRight));
  scene.texcoordAbsent[1] = "mesh 0 primitive 0: no TEXCOORD_1";
  TwoSquares tiled = twoSquares(kLeft, kRight);
  for (Uv& uv : tiled.uvs) uv.u *= 4.0f;  // a tiling material UV set
  scene.texcoord[0] = tiled.uvs;
  UvAtlasChoice c;
  ASSERT_TRUE(chooseUvAtlas(scene, {64, 64, 2}, &c).isOk());
  EXPECT_EQ(c.texcoord, -1);
  ASSERT_EQ(c.rejected.size(), 2u);
  EXPECT_EQ(c.rejected[0], "TEXCOORD_1: absent (mesh 0 primitive 0: no TEXCOORD_1)");
  EXPECT_NE(c.rejected[1].find("TEXCOORD_0: "), std::string::npos) << c.rejected[1];
  EXPECT_NE(c.rejected[1].find("outside [0, 1]"), std::string::npos) << c.rejected[1];
}

TEST(UvAtlasChoice, BadTargetIsAnError) {
  Scene scene = sceneOf(twoSquares(kLeft, kRight));
  scene.texcoord[1] = twoSquares(kLeft, kRight).uvs;
  UvAtlasChoice c;
  EXPECT_FALSE(chooseUvAtlas(scene, {64, 64, 1000}, &c).isOk());
}

}  // namespace
}  // namespace prt::bake
