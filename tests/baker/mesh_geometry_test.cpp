// The loader's building blocks on their own: computed normals (weighting and fallbacks),
// triangle clean-up and vertex compaction, sRGB decoding and bilinear texture sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "baker/scene/gltf_texture.h"
#include "baker/scene/mesh_cleanup.h"
#include "baker/scene/mesh_normals.h"
#include "baker/scene/mesh_order.h"
#include "baker/scene/uv_atlas_sets.h"

namespace prt::bake {
namespace {

void expectVec(Vec3 actual, Vec3 expected, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(MeshNormals, WeightIsAreaTimesCornerAngle) {
  // Vertex 0 is shared by a triangle facing +z (area 1/2, angle 90°) and one facing +x
  // (area 2, angle 45°): weights π/4 and π/2, so the normal is (2, 0, 1)/√5. Area alone
  // would give (4, 0, 1)/√17, angle alone (1, 0, 2)/√5.
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 2, 0}, {0, 2, 2}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 3, 4};
  std::vector<Vec3> n;
  EXPECT_EQ(computeVertexNormals(p, idx, {}, &n), 0u);
  ASSERT_EQ(n.size(), 5u);
  expectVec(n[0], Vec3{2, 0, 1} * (1.0f / std::sqrt(5.0f)));
  expectVec(n[1], {0, 0, 1});
  expectVec(n[4], {1, 0, 0});
}

TEST(MeshNormals, OnlyRequestedVerticesChange) {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2};
  std::vector<Vec3> n = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
  const std::vector<std::uint8_t> only1 = {0, 1, 0};
  computeVertexNormals(p, idx, only1, &n);
  expectVec(n[0], {1, 0, 0});
  expectVec(n[1], {0, 0, 1});
  expectVec(n[2], {1, 0, 0});
}

TEST(MeshNormals, FallbacksForIsolatedAndCancellingVertices) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Vertices 0-2: a two-sided triangle (both windings share the vertices), so contributions
  // cancel. Vertex 3: no triangle. Vertex 4: only in a triangle with a NaN corner.
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {1, 1, 1}, {nan, 0, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 1, 4, 5, 0, 7, 8, 9};
  std::vector<Vec3> n;
  EXPECT_EQ(computeVertexNormals(p, idx, {}, &n), 6u);
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(std::abs(n[static_cast<std::size_t>(v)].z), 1.0f, 1e-6f);
  expectVec(n[3], kFallbackNormal);
  expectVec(n[4], kFallbackNormal);
}

TEST(MeshCleanup, RemovesBadTrianglesAndKeepsOrder) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {inf, 0, 0}, {1e-9f, 1e-9f, 0}};
  std::vector<std::uint32_t> idx = {0, 1, 2,  // good
                                    0, 1, 3,  // collinear
                                    0, 0, 2,  // repeated index
                                    0, 4, 2,  // infinite corner
                                    0, 1, 9,  // out of range
                                    2, 1, 0,  // good (other side)
                                    0, 5, 1,  // sliver far below float resolution of its 1 m edge
                                    1, 2};    // partial
  const TriangleCleanupStats stats = removeBadTriangles(p, &idx);
  EXPECT_EQ(idx, (std::vector<std::uint32_t>{0, 1, 2, 2, 1, 0}));
  EXPECT_EQ(stats.zeroArea, 3u);
  EXPECT_EQ(stats.nonFinite, 1u);
  EXPECT_EQ(stats.outOfRange, 1u);
}

TEST(MeshCleanup, SmallButProperTrianglesStay) {
  // A 1 mm triangle 1 km from the origin is small, not degenerate.
  const std::vector<Vec3> p = {{1000, 0, 0}, {1000.001f, 0, 0}, {1000, 0.001f, 0}};
  std::vector<std::uint32_t> idx = {0, 1, 2};
  removeBadTriangles(p, &idx);
  EXPECT_EQ(idx.size(), 3u);
}

TEST(MeshCleanup, RemovesUnreferencedVerticesAndRenumbers) {
  Scene s;
  for (int v = 0; v < 5; ++v) {
    s.positions.push_back({static_cast<float>(v), 0, 0});
    s.normals.push_back({0, 1, 0});
    s.albedo.push_back({0.1f * v, 0, 0});
  }
  s.indices = {4, 2, 0};
  EXPECT_EQ(removeUnreferencedVertices(&s), 2u);
  ASSERT_EQ(s.positions.size(), 3u);
  EXPECT_EQ(s.indices, (std::vector<std::uint32_t>{2, 1, 0}));
  EXPECT_EQ(s.positions[2].x, 4.0f);
  EXPECT_FLOAT_EQ(s.albedo[1].r, 0.2f);
}

// A strip of 2 x 8 quads whose triangles alternate between objects 0 and 1 (a hostile order
// for grouping), each triangle's object recoverable from its centroid's x.
Scene interleavedStrip() {
  Scene s;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 1; ++j) {
      s.positions.push_back({static_cast<float>(i), 0.0f, static_cast<float>(j)});
      s.normals.push_back({0, 1, 0});
      s.albedo.push_back({0.5f, 0.5f, 0.5f});
    }
  }
  for (std::uint32_t i = 0; i < 8; ++i) {
    const std::uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
    s.indices.insert(s.indices.end(), {a, b, d, a, d, c});
    s.triangleObject.insert(s.triangleObject.end(), {i % 2, i % 2});  // quad i: object i mod 2
  }
  s.objectNames = {"even", "odd"};
  return s;
}

std::uint32_t objectOfCentroid(const Scene& s, std::size_t t) {
  const double x = (s.positions[s.indices[3 * t]].x + s.positions[s.indices[3 * t + 1]].x + s.positions[s.indices[3 * t + 2]].x) / 3;
  return static_cast<std::uint32_t>(static_cast<int>(std::floor(x)) % 2);
}

TEST(MeshOrder, ObjectIdsFollowTheTrianglesAndGroupsBecomeRuns) {
  Scene plain = interleavedStrip();
  optimizeMeshOrder(&plain);
  ASSERT_EQ(plain.triangleObject.size(), 16u);
  for (std::size_t t = 0; t < 16; ++t) EXPECT_EQ(plain.triangleObject[t], objectOfCentroid(plain, t)) << t;

  Scene grouped = interleavedStrip();
  std::vector<std::uint32_t> group = grouped.triangleObject;
  optimizeMeshOrder(&grouped, &group);
  for (std::size_t t = 0; t < 16; ++t) {
    EXPECT_EQ(group[t], t < 8 ? 0u : 1u) << t;  // one run per group, in ascending order
    EXPECT_EQ(grouped.triangleObject[t], objectOfCentroid(grouped, t)) << t;
    EXPECT_EQ(grouped.triangleObject[t], group[t]) << t;
  }
  // One group is exactly the ungrouped order.
  Scene a = interleavedStrip(), b = interleavedStrip();
  std::vector<std::uint32_t> one(16, 7u);
  optimizeMeshOrder(&a);
  optimizeMeshOrder(&b, &one);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.positions.size(), b.positions.size());
}

TEST(MeshCleanup, RemovedTrianglesTakeTheirObjectIds) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  std::vector<std::uint32_t> idx = {0, 1, 2, 0, 1, 3, 1, 2, 0};  // the middle one is collinear
  std::vector<std::uint32_t> objects = {4, 5, 6};
  removeBadTriangles(p, &idx, &objects);
  EXPECT_EQ(objects, (std::vector<std::uint32_t>{4, 6}));
}

TEST(SceneParts, CutAndReassembledObjectsKeepEveryTriangle) {
  const Scene s = interleavedStrip();
  const SceneObjects objects = sceneObjects(s);
  ASSERT_EQ(objects.triangles.size(), 2u);
  EXPECT_EQ(objects.names[1], "odd");
  Scene joined;
  for (const std::vector<std::uint32_t>& tris : objects.triangles) appendScenePart(&joined, scenePart(s, tris));
  ASSERT_EQ(joined.indices.size(), s.indices.size());
  // Vertices on the border between quads of two objects are copied into each object.
  EXPECT_GT(joined.positions.size(), s.positions.size());
  EXPECT_NEAR(surfaceArea(joined), surfaceArea(s), 1e-9);
  for (std::size_t t = 0; t < 16; ++t) EXPECT_EQ(joined.triangleObject[t], t < 8 ? 0u : 1u);
}

TEST(Texture, SrgbDecoding) {
  EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.04f), 0.04f / 12.92f, 1e-7f);
}

TEST(Texture, BilinearSamplingAndWrapModes) {
  // 2 × 1 texture (already linear): black, white.
  LinearTexture t;
  const std::vector<unsigned char> px = {0, 0, 0, 255, 255, 255};
  ASSERT_TRUE(linearTextureFromSrgb8(2, 1, 3, px, &t).isOk());
  auto r = [&](float u, WrapMode m) { return sampleBilinear(t, u, 0.5f, m, WrapMode::kRepeat).r; };
  EXPECT_NEAR(r(0.25f, WrapMode::kRepeat), 0.0f, 1e-6f);
  EXPECT_NEAR(r(0.75f, WrapMode::kRepeat), 1.0f, 1e-6f);
  EXPECT_NEAR(r(0.5f, WrapMode::kRepeat), 0.5f, 1e-6f);
  // At u = 0 the filter straddles the edge: REPEAT blends with the far texel, CLAMP does not.
  EXPECT_NEAR(r(0.0f, WrapMode::kRepeat), 0.5f, 1e-6f);
  EXPECT_NEAR(r(0.0f, WrapMode::kClampToEdge), 0.0f, 1e-6f);
  EXPECT_NEAR(r(0.0f, WrapMode::kMirroredRepeat), 0.0f, 1e-6f);
  EXPECT_NEAR(r(-0.25f, WrapMode::kRepeat), 1.0f, 1e-6f);
  EXPECT_NEAR(r(-0.25f, WrapMode::kMirroredRepeat), 0.0f, 1e-6f);
  EXPECT_NEAR(r(1.25f, WrapMode::kMirroredRepeat), 1.0f, 1e-6f);
  EXPECT_NEAR(r(7.0f, WrapMode::kClampToEdge), 1.0f, 1e-6f);
  // Huge and non-finite coordinates stay in range.
  EXPECT_TRUE(std::isfinite(r(3e9f, WrapMode::kRepeat)));
  EXPECT_TRUE(std::isfinite(r(-3e38f, WrapMode::kMirroredRepeat)));
  EXPECT_TRUE(std::isfinite(r(std::numeric_limits<float>::quiet_NaN(), WrapMode::kClampToEdge)));
}

TEST(Texture, RejectsMismatchedPixelData) {
  LinearTexture t;
  const std::vector<unsigned char> px(5, 0);
  EXPECT_FALSE(linearTextureFromSrgb8(2, 1, 3, px, &t).isOk());
  EXPECT_FALSE(linearTextureFromSrgb8(0, 1, 3, {}, &t).isOk());
  // Empty textures sample as black rather than crash.
  EXPECT_EQ(sampleBilinear(LinearTexture(), 0.5f, 0.5f, WrapMode::kRepeat, WrapMode::kRepeat).r, 0.0f);
}

}  // namespace
}  // namespace prt::bake
