// The loader's building blocks on their own: computed normals (weighting and fallbacks),
// triangle clean-up and vertex compaction, sRGB decoding and bilinear texture sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "baker/scene/gltf_texture.h"
#include "baker/scene/mesh_cleanup.h"
#include "baker/scene/mesh_normals.h"

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
