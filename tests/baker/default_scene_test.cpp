// The built-in default scene: well-formed (unit normals, indices in range, winding
// consistent with normals, albedo below 1), room-sized, varied, and with normals facing into
// the room and out of the objects.
#include "baker/scene/default_scene.h"
#include "baker/scene/uv_atlas_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace prt::bake {
namespace {

TEST(DefaultScene, IsWellFormed) {
  const Scene s = makeDefaultScene();
  ASSERT_FALSE(s.positions.empty());
  EXPECT_FALSE(s.name.empty());
  EXPECT_EQ(s.normals.size(), s.positions.size());
  EXPECT_EQ(s.albedo.size(), s.positions.size());
  ASSERT_EQ(s.indices.size() % 3, 0u);
  EXPECT_GE(s.positions.size(), 15000u);
  EXPECT_LE(s.positions.size(), 30000u);
  for (std::uint32_t i : s.indices) ASSERT_LT(i, s.positions.size());
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    ASSERT_TRUE(isFinite(s.positions[v]));
    ASSERT_NEAR(length(s.normals[v]), 1.0f, 1e-5f) << "vertex " << v;
    for (float c : {s.albedo[v].r, s.albedo[v].g, s.albedo[v].b}) {
      ASSERT_GE(c, 0.0f);
      ASSERT_LT(c, 1.0f);
    }
  }
  // Every vertex is used, and no triangle is degenerate.
  std::vector<bool> used(s.positions.size(), false);
  for (std::uint32_t i : s.indices) used[i] = true;
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
}

TEST(DefaultScene, WindingAgreesWithNormals) {
  const Scene s = makeDefaultScene();
  for (std::size_t t = 0; t < s.indices.size() / 3; ++t) {
    const Vec3 a = s.positions[s.indices[3 * t]], b = s.positions[s.indices[3 * t + 1]],
               c = s.positions[s.indices[3 * t + 2]];
    const Vec3 n = cross(b - a, c - a);
    ASSERT_GT(length(n), 1e-7f) << "triangle " << t;
    const Vec3 f = n * (1.0f / length(n));
    for (int k = 0; k < 3; ++k) ASSERT_GT(dot(f, s.normals[s.indices[3 * t + k]]), 0.5f) << "triangle " << t;
  }
}

TEST(DefaultScene, BoundsAreARoomOfAboutFourMetres) {
  const Scene s = makeDefaultScene();
  Vec3 lo = s.positions[0], hi = s.positions[0];
  for (const Vec3& p : s.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  EXPECT_FLOAT_EQ(lo.y, 0.0f);  // floor at y = 0, +y up
  EXPECT_NEAR(lo.x, -2.0f, 1e-5f);
  EXPECT_NEAR(hi.x, 2.0f, 1e-5f);
  EXPECT_NEAR(lo.z, -2.0f, 1e-5f);
  EXPECT_NEAR(hi.z, 2.0f, 1e-5f);
  EXPECT_GT(hi.y, 2.0f);
  EXPECT_LT(hi.y, 4.0f);
}

TEST(DefaultScene, HasAtLeastFiveDistinctAlbedos) {
  const Scene s = makeDefaultScene();
  std::set<std::tuple<float, float, float>> colours;
  for (const Rgb& a : s.albedo) colours.insert({a.r, a.g, a.b});
  EXPECT_GE(colours.size(), 5u);
  // A red-ish and a green-ish wall for colour bleeding.
  EXPECT_TRUE(std::any_of(colours.begin(), colours.end(), [](auto c) { return std::get<0>(c) > 3 * std::get<1>(c); }));
  EXPECT_TRUE(std::any_of(colours.begin(), colours.end(), [](auto c) { return std::get<1>(c) > 3 * std::get<0>(c); }));
}

using AlbedoKey = std::tuple<float, float, float>;

// Vertices grouped by albedo: every surface of the default scene has its own.
std::map<AlbedoKey, std::vector<std::size_t>> verticesByAlbedo(const Scene& s) {
  std::map<AlbedoKey, std::vector<std::size_t>> groups;
  for (std::size_t v = 0; v < s.positions.size(); ++v)
    groups[{s.albedo[v].r, s.albedo[v].g, s.albedo[v].b}].push_back(v);
  return groups;
}

// A flat surface (wall, floor): all normals equal.
bool isFlat(const Scene& s, const std::vector<std::size_t>& group) {
  return std::all_of(group.begin(), group.end(),
                     [&](std::size_t v) { return dot(s.normals[v], s.normals[group[0]]) > 0.9999f; });
}

TEST(DefaultScene, WallAndFloorNormalsPointIntoTheRoom) {
  // A step along a wall's or the floor's normal stays inside the room's air: x, z in
  // [-2, 2], y >= 0. (Objects are checked below: near the floor, their normals may
  // rightly point down.)
  const Scene s = makeDefaultScene();
  int flatSurfaces = 0;
  for (const auto& [albedo, group] : verticesByAlbedo(s)) {
    if (!isFlat(s, group)) continue;
    ++flatSurfaces;
    for (std::size_t v : group) {
      const Vec3 q = s.positions[v] + s.normals[v] * 0.01f;
      ASSERT_TRUE(q.y >= 0 && q.x >= -2 && q.x <= 2 && q.z >= -2) << "vertex " << v;
    }
  }
  EXPECT_EQ(flatSurfaces, 4);  // floor, back, left and right walls
}

// Each object (one albedo each) is closed except for faces lying on the floor, so with
// outward normals ∫ x n_x dA = ∫ y n_y dA = ∫ z n_z dA = its volume > 0 (divergence
// theorem; faces on y = 0 or with n_x = 0 add nothing). Flat surfaces (walls, floor) are
// skipped: all their normals are equal.
TEST(DefaultScene, ObjectNormalsPointOutwards) {
  const Scene s = makeDefaultScene();
  struct Sums {
    double x = 0, y = 0, z = 0;
  };
  std::map<AlbedoKey, Sums> sums;
  for (std::size_t t = 0; t < s.indices.size() / 3; ++t) {
    const std::uint32_t i0 = s.indices[3 * t];
    const Vec3 a = s.positions[i0], b = s.positions[s.indices[3 * t + 1]], c = s.positions[s.indices[3 * t + 2]];
    const Vec3 areaNormal = cross(b - a, c - a) * 0.5f;  // n dA
    const Vec3 centroid = (a + b + c) * (1.0f / 3.0f);
    Sums& sum = sums[{s.albedo[i0].r, s.albedo[i0].g, s.albedo[i0].b}];
    sum.x += double{centroid.x} * areaNormal.x;
    sum.y += double{centroid.y} * areaNormal.y;
    sum.z += double{centroid.z} * areaNormal.z;
  }
  int objects = 0;
  for (const auto& [albedo, group] : verticesByAlbedo(s)) {
    if (isFlat(s, group)) continue;
    ++objects;
    const Sums& sum = sums[albedo];
    EXPECT_GT(sum.y, 0.01);
    EXPECT_NEAR(sum.x / sum.y, 1.0, 0.02);
    EXPECT_NEAR(sum.z / sum.y, 1.0, 0.02);
  }
  EXPECT_EQ(objects, 4);  // sphere, cube, tall box, torus
}

TEST(DefaultScene, IsDeterministic) {
  const Scene a = makeDefaultScene(), b = makeDefaultScene();
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(a.indices, b.indices);
  for (std::size_t v = 0; v < a.positions.size(); ++v) {
    ASSERT_EQ(a.positions[v].x, b.positions[v].x);
    ASSERT_EQ(a.positions[v].y, b.positions[v].y);
    ASSERT_EQ(a.positions[v].z, b.positions[v].z);
  }
}

// The built-in lightmap atlas passes the same check a glTF's TEXCOORD_1 must pass, at the
// sizes the demo and the tests bake at, and spends its texels on the surface: one chart per
// grid (4 room surfaces, 5 + 5 box faces, sphere, torus) and most of the square used.
TEST(DefaultScene, Texcoord1IsAValidLightmapAtlas) {
  const Scene s = makeDefaultScene();
  ASSERT_EQ(s.texcoord[1].size(), s.positions.size());
  EXPECT_TRUE(s.texcoord[0].empty());
  EXPECT_FALSE(s.texcoordAbsent[0].empty());
  for (int size : {512, 1024, 2048}) {
    UvAtlasTarget target;
    target.width = target.height = size;
    target.padding = 2;
    UvAtlasReport r;
    ASSERT_TRUE(checkUvAtlas(s.positions, s.indices, s.texcoord[1], target, "TEXCOORD_1", &r).isOk());
    EXPECT_TRUE(r.valid()) << size << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_EQ(r.charts, 16u) << size;
    EXPECT_GT(r.usedTexelFraction, 0.6) << size;
  }
  // Asked for a smaller side (the CLI passes --texture-size and --atlas-padding), the gutters
  // widen so the atlas is valid there too; from 512 up the UVs are the same as the default's.
  for (int size : {64, 128, 256}) {
    const Scene small = makeDefaultScene(size, 2);
    UvAtlasTarget target;
    target.width = target.height = size;
    target.padding = 2;
    UvAtlasReport r;
    ASSERT_TRUE(checkUvAtlas(small.positions, small.indices, small.texcoord[1], target, "TEXCOORD_1", &r).isOk());
    EXPECT_TRUE(r.valid()) << size << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_EQ(r.charts, 16u) << size;
    EXPECT_GT(r.usedTexelFraction, 0.3) << size;
    const Scene wider = makeDefaultScene(size, 4);
    target.padding = 4;
    ASSERT_TRUE(checkUvAtlas(wider.positions, wider.indices, wider.texcoord[1], target, "TEXCOORD_1", &r).isOk());
    EXPECT_TRUE(r.valid()) << size << " at padding 4: " << (r.problems.empty() ? "" : r.problems[0]);
  }
  for (int size : {512, 1024, 4096}) {
    const Scene same = makeDefaultScene(size, 2);
    for (std::size_t v = 0; v < s.positions.size(); ++v) {
      ASSERT_EQ(same.texcoord[1][v].u, s.texcoord[1][v].u) << size;
      ASSERT_EQ(same.texcoord[1][v].v, s.texcoord[1][v].v) << size;
    }
  }
  // Texel density is uniform across charts: UV area over surface area is the same for the
  // floor (first chart) and the cube's top, within the rounding of the grids.
  auto density = [&](std::size_t firstTriangle, std::size_t count) {
    double uvArea = 0, area = 0;
    for (std::size_t t = firstTriangle; t < firstTriangle + count; ++t) {
      const std::uint32_t a = s.indices[3 * t], b = s.indices[3 * t + 1], c = s.indices[3 * t + 2];
      area += 0.5 * length(cross(s.positions[b] - s.positions[a], s.positions[c] - s.positions[a]));
      const Uv ua = s.texcoord[1][a], ub = s.texcoord[1][b], uc = s.texcoord[1][c];
      uvArea += 0.5 * std::abs((ub.u - ua.u) * (uc.v - ua.v) - (ub.v - ua.v) * (uc.u - ua.u));
    }
    return uvArea / area;
  };
  const std::size_t floorTriangles = 2 * 64 * 64;  // 4 m at 16 cells per metre
  EXPECT_NEAR(density(0, floorTriangles) / density(floorTriangles, 2 * 64 * 48), 1.0, 1e-3);
}

}  // namespace
}  // namespace prt::bake
