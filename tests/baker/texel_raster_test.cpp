// Texel rasterisation (baker/texture/texel_raster.h) against independent references: the
// covered texels of single triangles (slivers, sub-texel, grid-aligned, random) equal a
// double-precision clip of every texel square against the triangle; a two-triangle quad
// covers its rectangle's footprint once per texel; samples interpolate positions affinely
// inside and land on the triangle outside; normals are unit and interpolated; the nearest
// triangle owns a shared texel; bad input is an error.
#include "baker/texture/texel_raster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace prt::bake {
namespace {

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Uv> uvs;
  std::vector<std::uint32_t> indices;

  // Appends a triangle with its own three vertices; normals default to +z.
  void add(std::array<Uv, 3> uv, std::array<Vec3, 3> p,
           std::array<Vec3, 3> n = {Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}}) {
    for (int k = 0; k < 3; ++k) {
      indices.push_back(static_cast<std::uint32_t>(positions.size()));
      positions.push_back(p[static_cast<std::size_t>(k)]);
      normals.push_back(n[static_cast<std::size_t>(k)]);
      uvs.push_back(uv[static_cast<std::size_t>(k)]);
    }
  }
  // A triangle whose positions are its UVs on the z = 0 plane (the affine map is the identity).
  void addFlat(std::array<Uv, 3> uv) {
    add(uv, {Vec3{uv[0].u, uv[0].v, 0}, Vec3{uv[1].u, uv[1].v, 0}, Vec3{uv[2].u, uv[2].v, 0}});
  }
};

TexelRaster raster(const Mesh& m, int w, int h) {
  TexelRaster r;
  const Status s = rasteriseTexels(m.positions, m.normals, m.indices, m.uvs, w, h, &r);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return r;
}

// --- The reference: Sutherland-Hodgman clip of the texel square by the triangle. ---
struct P {
  double x, y;
};
double cross(P o, P a, P b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

double overlapArea(const std::array<P, 3>& tri, int x, int y) {
  std::vector<P> poly{{double(x), double(y)}, {x + 1.0, double(y)}, {x + 1.0, y + 1.0}, {double(x), y + 1.0}};
  const double side = cross(tri[0], tri[1], tri[2]) > 0 ? 1.0 : -1.0;
  for (int e = 0; e < 3 && !poly.empty(); ++e) {
    const P a = tri[static_cast<std::size_t>(e)], b = tri[static_cast<std::size_t>((e + 1) % 3)];
    std::vector<P> next;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const P p = poly[i], q = poly[(i + 1) % poly.size()];
      const double dp = side * cross(a, b, p), dq = side * cross(a, b, q);
      if (dp >= 0) next.push_back(p);
      if ((dp >= 0) != (dq >= 0)) {
        const double s = dp / (dp - dq);
        next.push_back({p.x + s * (q.x - p.x), p.y + s * (q.y - p.y)});
      }
    }
    poly = next;
  }
  double area = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P p = poly[i], q = poly[(i + 1) % poly.size()];
    area += p.x * q.y - q.x * p.y;
  }
  return std::abs(area) / 2;
}

// Texels of a w × h atlas that the triangle overlaps with positive area (up to rounding).
std::vector<std::uint32_t> referenceTexels(std::array<Uv, 3> uv, int w, int h) {
  std::array<P, 3> tri;
  for (std::size_t k = 0; k < 3; ++k) tri[k] = {double(uv[k].u) * w, double(uv[k].v) * h};
  std::vector<std::uint32_t> out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (overlapArea(tri, x, y) > 1e-12) out.push_back(static_cast<std::uint32_t>(y * w + x));
  return out;
}

std::vector<std::uint32_t> texelsOf(const TexelRaster& r) {
  std::vector<std::uint32_t> t;
  for (const TexelSample& s : r.samples) t.push_back(s.texel);
  return t;
}

// Samples are strictly ascending (so one per texel) and agree with the coverage mask.
void expectConsistent(const TexelRaster& r) {
  ASSERT_EQ(r.coverage.size(), static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
  for (std::size_t i = 1; i < r.samples.size(); ++i) ASSERT_LT(r.samples[i - 1].texel, r.samples[i].texel);
  std::size_t used = 0;
  for (std::uint8_t c : r.coverage) used += c ? 1 : 0;
  EXPECT_EQ(used, r.samples.size());
  for (const TexelSample& s : r.samples) {
    EXPECT_EQ(r.coverage[s.texel], 1);
    EXPECT_NEAR(s.bary[0] + s.bary[1] + s.bary[2], 1.0f, 1e-6f);
    for (float b : s.bary) EXPECT_GE(b, 0.0f);
  }
}

Uv texelUv(double x, double y, int w, int h) { return {static_cast<float>(x / w), static_cast<float>(y / h)}; }

TEST(TexelRaster, SingleTrianglesMatchTheClippingReference) {
  const int w = 32, h = 24;
  std::vector<std::array<Uv, 3>> tris{
      {Uv{0.10f, 0.12f}, Uv{0.83f, 0.31f}, Uv{0.37f, 0.91f}},                               // large, generic
      {Uv{0.02f, 0.03f}, Uv{0.97f, 0.95f}, Uv{0.9705f, 0.9496f}},                           // long diagonal sliver
      {texelUv(1.2, 3.3, w, h), texelUv(30.7, 3.3004, w, h), texelUv(15.0, 3.3011, w, h)},  // flat sliver
      {texelUv(4.2, 5.3, w, h), texelUv(4.6, 5.35, w, h), texelUv(4.4, 5.8, w, h)},         // inside one texel
      {texelUv(6.9, 7.9, w, h), texelUv(7.1, 7.92, w, h), texelUv(7.02, 8.1, w, h)},        // across a corner
      {texelUv(9.3, 9.95, w, h), texelUv(9.7, 9.97, w, h), texelUv(9.5, 10.02, w, h)},      // across an edge
      // On the grid, exactly (x / 32 and y / 24 for y a multiple of 3 are floats): edges along
      // texel lines and diagonals through texel corners; texels those only touch are not covered.
      {texelUv(2, 3, w, h), texelUv(8, 3, w, h), texelUv(2, 9, w, h)},
      {texelUv(10, 6, w, h), texelUv(10, 18, w, h), texelUv(16, 12, w, h)},
      // Touching the atlas border (u = 1, v = 0 and v = 1).
      {Uv{1.0f, 0.0f}, Uv{1.0f, 1.0f}, Uv{0.6f, 0.5f}},
      {Uv{0.0f, 0.0f}, Uv{0.01f, 0.0f}, Uv{0.0f, 0.015f}},  // smaller than a texel, in the corner
  };
  std::mt19937 rng(15);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), jitter(-0.02f, 0.02f);
  for (int i = 0; i < 40; ++i) {
    const Uv a{unit(rng), unit(rng)}, b{unit(rng), unit(rng)};
    // Every other one a sliver: its third corner close to the first edge's midpoint.
    const Uv c = i % 2 ? Uv{std::clamp((a.u + b.u) / 2 + jitter(rng), 0.0f, 1.0f),
                            std::clamp((a.v + b.v) / 2 + jitter(rng), 0.0f, 1.0f)}
                       : Uv{unit(rng), unit(rng)};
    tris.push_back({a, b, c});
  }
  for (std::size_t i = 0; i < tris.size(); ++i) {
    Mesh m;
    m.addFlat(tris[i]);
    const TexelRaster r = raster(m, w, h);
    SCOPED_TRACE("triangle " + std::to_string(i));
    expectConsistent(r);
    EXPECT_EQ(r.degenerateTriangles, 0u);
    EXPECT_EQ(texelsOf(r), referenceTexels(tris[i], w, h));
    EXPECT_GE(r.samples.size(), 1u) << "every triangle, however small, gets a sample";
  }
}

TEST(TexelRaster, GridAlignedTriangleSkipsTexelsItOnlyTouches) {
  // Texel units (2, 2), (6, 2), (2, 6): the hypotenuse passes through texel corners, so
  // texels (2..5, 2) on the bottom row down to (2, 5) are covered: 4 + 3 + 2 + 1, no more.
  const int w = 16, h = 16;
  Mesh m;
  m.addFlat({texelUv(2, 2, w, h), texelUv(6, 2, w, h), texelUv(2, 6, w, h)});
  const TexelRaster r = raster(m, w, h);
  std::vector<std::uint32_t> expected;
  for (int y = 2; y < 6; ++y)
    for (int x = 2; x < 8 - y; ++x) expected.push_back(static_cast<std::uint32_t>(y * w + x));
  EXPECT_EQ(texelsOf(r), expected);
}

// A rectangle [u0, u1] × [v0, v1] as two triangles sharing its diagonal.
Mesh quad(float u0, float v0, float u1, float v1) {
  Mesh m;
  m.positions = {{u0, v0, 0}, {u1, v0, 0}, {u1, v1, 0}, {u0, v1, 0}};
  m.normals.assign(4, Vec3{0, 0, 1});
  m.uvs = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

void expectRectangleFootprint(const TexelRaster& r, int x0, int x1, int y0, int y1) {
  expectConsistent(r);
  std::vector<std::uint32_t> expected;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) expected.push_back(static_cast<std::uint32_t>(y * r.width + x));
  EXPECT_EQ(texelsOf(r), expected);
}

TEST(TexelRaster, QuadCoversItsRectangleOncePerTexel) {
  const int w = 40, h = 30;
  const float u0 = 0.13f, v0 = 0.21f, u1 = 0.71f, v1 = 0.64f;
  const TexelRaster r = raster(quad(u0, v0, u1, v1), w, h);
  expectRectangleFootprint(
      r, static_cast<int>(std::floor(double(u0) * w)), static_cast<int>(std::ceil(double(u1) * w)) - 1,
      static_cast<int>(std::floor(double(v0) * h)), static_cast<int>(std::ceil(double(v1) * h)) - 1);
  // Both triangles own texels: the diagonal is not given wholly to one of them.
  const auto owned0 =
      std::count_if(r.samples.begin(), r.samples.end(), [](const TexelSample& s) { return s.triangle == 0; });
  EXPECT_GT(owned0, 0);
  EXPECT_LT(static_cast<std::size_t>(owned0), r.samples.size());
}

TEST(TexelRaster, QuadOnTexelLinesCoversExactlyItsTexels) {
  // Texels 8 … 23 in x and 4 … 11 in y; the neighbours that only touch its edges stay empty.
  const int w = 64, h = 32;
  const TexelRaster r = raster(quad(8.0f / w, 4.0f / h, 24.0f / w, 12.0f / h), w, h);
  expectRectangleFootprint(r, 8, 23, 4, 11);
  // The diagonal from (8, 4) to (24, 12) would meet centre (x + 0.5, y + 0.5) only where
  // x = 2y + 0.5: never, so every centre is inside a triangle.
  for (const TexelSample& s : r.samples) EXPECT_EQ(s.uvDistance, 0.0f);
}

TEST(TexelRaster, CentreOnTheSharedEdgeGoesToTheLowerTriangle) {
  // A square of 16 × 16 texels: its diagonal passes through the centres of texels (x, x).
  const int w = 32, h = 32;
  const TexelRaster r = raster(quad(8.0f / w, 8.0f / h, 24.0f / w, 24.0f / h), w, h);
  expectRectangleFootprint(r, 8, 23, 8, 23);
  for (const TexelSample& s : r.samples) {
    const std::uint32_t x = s.texel % w, y = s.texel / w;
    EXPECT_EQ(s.uvDistance, 0.0f);
    // Triangle 0 is (u0, v0), (u1, v0), (u1, v1): the half with x > y, and the diagonal's
    // centres (x == y) are in both, so they go to it too.
    EXPECT_EQ(s.triangle, x >= y ? 0u : 1u) << "texel " << x << "," << y;
  }
}

TEST(TexelRaster, TieGoesToTheLowerIndexWhateverTheVisitingOrder) {
  // A shared horizontal edge at y = 5.5 through the centres of texels (2 … 11, 5). Triangle 1
  // (above it) starts rows earlier than triangle 0 (below), so it is reached first; the tie on
  // those centres still goes to triangle 0.
  const int w = 16, h = 16;
  Mesh m;
  m.addFlat({texelUv(2, 5.5, w, h), texelUv(12, 5.5, w, h), texelUv(7, 12, w, h)});
  m.addFlat({texelUv(2, 5.5, w, h), texelUv(12, 5.5, w, h), texelUv(7, 1, w, h)});
  const TexelRaster r = raster(m, w, h);
  expectConsistent(r);
  int onEdge = 0;
  for (const TexelSample& s : r.samples) {
    if (s.texel / w != 5 || s.texel % w < 2 || s.texel % w > 11) continue;
    ++onEdge;
    EXPECT_EQ(s.triangle, 0u) << "texel " << s.texel % w;
    EXPECT_EQ(s.uvDistance, 0.0f);
  }
  EXPECT_EQ(onEdge, 10);
}

TEST(TexelRaster, NearestTriangleOwnsATexelWhoseCentreIsOutsideBoth) {
  // Texel (5, 5), centre (5.5, 5.5). Triangle "near" reaches x = 5.3 (0.2 from the centre),
  // "far" starts at x = 5.9 (0.4 away); neither contains the centre. Whatever the index order,
  // the near one owns it.
  const int w = 16, h = 16;
  const std::array<Uv, 3> nearTri{texelUv(2, 2, w, h), texelUv(5.3, 2, w, h), texelUv(5.3, 9, w, h)};
  const std::array<Uv, 3> farTri{texelUv(5.9, 2, w, h), texelUv(9, 2, w, h), texelUv(5.9, 9, w, h)};
  for (int nearFirst = 0; nearFirst < 2; ++nearFirst) {
    Mesh m;
    m.addFlat(nearFirst ? nearTri : farTri);
    m.addFlat(nearFirst ? farTri : nearTri);
    const TexelRaster r = raster(m, w, h);
    expectConsistent(r);
    const auto it =
        std::find_if(r.samples.begin(), r.samples.end(), [&](const TexelSample& s) { return s.texel == 5u * w + 5u; });
    ASSERT_NE(it, r.samples.end());
    EXPECT_EQ(it->triangle, nearFirst ? 0u : 1u);
    EXPECT_NEAR(it->uvDistance, 0.2f, 1e-5f);
    // The sample is the centre moved onto the near edge: x = 5.3 texels, y = 5.5 texels.
    EXPECT_NEAR(it->position.x * w, 5.3f, 1e-4f);
    EXPECT_NEAR(it->position.y * h, 5.5f, 1e-4f);
  }
}

// A triangle in general 3D position with UVs over much of a 48 × 40 atlas.
Mesh slantedTriangle() {
  Mesh m;
  m.add({Uv{0.11f, 0.07f}, Uv{0.93f, 0.28f}, Uv{0.42f, 0.89f}},
        {Vec3{1.0f, 2.0f, -0.5f}, Vec3{3.5f, 2.7f, 0.25f}, Vec3{0.3f, 4.1f, 1.9f}},
        {Vec3{0, 0, 2}, Vec3{3, 0, 3}, Vec3{0, 0.5f, 0.5f}});  // not unit, on purpose
  return m;
}

TEST(TexelRaster, CentresInsideInterpolatePositionsAffinely) {
  const int w = 48, h = 40;
  const Mesh m = slantedTriangle();
  const TexelRaster r = raster(m, w, h);
  expectConsistent(r);
  // The affine map UV -> position, by solving for (s, t) with uv = uv0 + s e1 + t e2.
  const double e1u = double(m.uvs[1].u) - m.uvs[0].u, e1v = double(m.uvs[1].v) - m.uvs[0].v;
  const double e2u = double(m.uvs[2].u) - m.uvs[0].u, e2v = double(m.uvs[2].v) - m.uvs[0].v;
  const double det = e1u * e2v - e1v * e2u;
  int inside = 0;
  for (const TexelSample& s : r.samples) {
    if (s.uvDistance != 0.0f) continue;
    ++inside;
    const double cu = (s.texel % w + 0.5) / w - m.uvs[0].u, cv = (s.texel / w + 0.5) / h - m.uvs[0].v;
    const double a = (cu * e2v - cv * e2u) / det, b = (e1u * cv - e1v * cu) / det;
    EXPECT_NEAR(s.bary[1], a, 1e-6);
    EXPECT_NEAR(s.bary[2], b, 1e-6);
    const Vec3 p0 = m.positions[0], p1 = m.positions[1], p2 = m.positions[2];
    EXPECT_NEAR(s.position.x, p0.x + a * (p1.x - p0.x) + b * (p2.x - p0.x), 1e-5);
    EXPECT_NEAR(s.position.y, p0.y + a * (p1.y - p0.y) + b * (p2.y - p0.y), 1e-5);
    EXPECT_NEAR(s.position.z, p0.z + a * (p1.z - p0.z) + b * (p2.z - p0.z), 1e-5);
  }
  EXPECT_GT(inside, 100);
}

TEST(TexelRaster, CentresOutsideLandOnTheTriangle) {
  const int w = 48, h = 40;
  const Mesh m = slantedTriangle();
  const TexelRaster r = raster(m, w, h);
  const Vec3 p0 = m.positions[0], p1 = m.positions[1], p2 = m.positions[2];
  const Vec3 n = cross(p1 - p0, p2 - p0);
  const float area2 = dot(n, n);
  int outside = 0;
  for (const TexelSample& s : r.samples) {
    if (s.uvDistance == 0.0f) continue;
    ++outside;
    EXPECT_LE(s.uvDistance, std::sqrt(0.5f) + 1e-5f) << "the owner touches the texel, so it is within half a diagonal";
    // On the plane...
    EXPECT_NEAR(dot(s.position - p0, n) / length(n), 0.0f, 1e-5f);
    // ... and within the edges: the 3D barycentrics of the position are all >= 0.
    const float b0 = dot(cross(p1 - s.position, p2 - s.position), n) / area2;
    const float b1 = dot(cross(p2 - s.position, p0 - s.position), n) / area2;
    const float b2 = dot(cross(p0 - s.position, p1 - s.position), n) / area2;
    EXPECT_GE(b0, -1e-5f);
    EXPECT_GE(b1, -1e-5f);
    EXPECT_GE(b2, -1e-5f);
    // On an edge (one weight 0) and at uvDistance from the centre, in texels.
    EXPECT_EQ(std::min({s.bary[0], s.bary[1], s.bary[2]}), 0.0f);
    double su = 0, sv = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      su += double(s.bary[k]) * m.uvs[k].u * w;
      sv += double(s.bary[k]) * m.uvs[k].v * h;
    }
    EXPECT_NEAR(std::hypot(su - (s.texel % w + 0.5), sv - (s.texel / w + 0.5)), s.uvDistance, 1e-4);
  }
  EXPECT_GT(outside, 20);
}

TEST(TexelRaster, NormalsAreUnitAndInterpolated) {
  const int w = 48, h = 40;
  const Mesh m = slantedTriangle();
  const TexelRaster r = raster(m, w, h);
  ASSERT_FALSE(r.samples.empty());
  EXPECT_EQ(r.normalFallbacks, 0u);
  std::array<Vec3, 3> unit;
  for (std::size_t k = 0; k < 3; ++k) unit[k] = m.normals[k] * (1.0f / length(m.normals[k]));
  for (const TexelSample& s : r.samples) {
    EXPECT_NEAR(length(s.normal), 1.0f, 1e-6f);
    const Vec3 mix = unit[0] * s.bary[0] + unit[1] * s.bary[1] + unit[2] * s.bary[2];
    const Vec3 expected = mix * (1.0f / length(mix));
    EXPECT_NEAR(s.normal.x, expected.x, 1e-5f);
    EXPECT_NEAR(s.normal.y, expected.y, 1e-5f);
    EXPECT_NEAR(s.normal.z, expected.z, 1e-5f);
  }
  // Not all equal: the normal does vary across the triangle.
  const auto [lo, hi] =
      std::minmax_element(r.samples.begin(), r.samples.end(),
                          [](const TexelSample& a, const TexelSample& b) { return a.normal.x < b.normal.x; });
  EXPECT_GT(hi->normal.x - lo->normal.x, 0.3f);
}

TEST(TexelRaster, CancellingNormalsFallBackToTheFaceNormal) {
  // Corner normals 120° apart in the xy-plane sum to zero at the centroid, which is the centre
  // of texel (1, 1); that sample takes the face normal (+z for this winding) instead.
  const int w = 8, h = 8;
  Mesh m;
  m.add({texelUv(0.5, 0.5, w, h), texelUv(3.5, 0.5, w, h), texelUv(0.5, 3.5, w, h)},
        {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
        {Vec3{1, 0, 0}, Vec3{-0.5f, std::sqrt(3.0f) / 2, 0}, Vec3{-0.5f, -std::sqrt(3.0f) / 2, 0}});
  const TexelRaster r = raster(m, w, h);
  const auto it =
      std::find_if(r.samples.begin(), r.samples.end(), [&](const TexelSample& s) { return s.texel == 1u * w + 1u; });
  ASSERT_NE(it, r.samples.end());
  EXPECT_GE(r.normalFallbacks, 1u);
  EXPECT_NEAR(it->normal.z, 1.0f, 1e-6f);
  for (const TexelSample& s : r.samples) EXPECT_NEAR(length(s.normal), 1.0f, 1e-6f);
}

TEST(TexelRaster, DegenerateUvTrianglesAreSkippedAndCounted) {
  Mesh m;
  m.addFlat({Uv{0.1f, 0.1f}, Uv{0.5f, 0.5f}, Uv{0.9f, 0.9f}});  // collinear
  m.add({Uv{0.3f, 0.3f}, Uv{0.3f, 0.3f}, Uv{0.6f, 0.2f}},
        {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}});  // repeated corner
  m.addFlat({Uv{0.2f, 0.6f}, Uv{0.4f, 0.6f}, Uv{0.2f, 0.9f}});
  const TexelRaster r = raster(m, 16, 16);
  EXPECT_EQ(r.degenerateTriangles, 2u);
  ASSERT_FALSE(r.samples.empty());
  for (const TexelSample& s : r.samples) EXPECT_EQ(s.triangle, 2u);
}

TEST(TexelRaster, SameInputSameSamples) {
  Mesh m = slantedTriangle();
  m.addFlat({Uv{0.5f, 0.5f}, Uv{0.95f, 0.6f}, Uv{0.7f, 0.98f}});  // overlaps the first: shared texels
  const TexelRaster a = raster(m, 48, 40), b = raster(m, 48, 40);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].texel, b.samples[i].texel);
    EXPECT_EQ(a.samples[i].triangle, b.samples[i].triangle);
    EXPECT_EQ(std::memcmp(&a.samples[i].position, &b.samples[i].position, sizeof(Vec3)), 0);
  }
  expectConsistent(a);
}

TEST(TexelRaster, LargeAtlasIsProcessedInBands) {
  // 4096 wide: bands of 256 rows, so a triangle spans several bands and rows meet at band edges.
  const int w = 4096, h = 1024;
  const std::array<Uv, 3> t{Uv{0.001f, 0.02f}, Uv{0.004f, 0.97f}, Uv{0.0025f, 0.5f}};
  Mesh m;
  m.addFlat(t);
  const TexelRaster r = raster(m, w, h);
  expectConsistent(r);
  // The reference over the triangle's columns only (x < 17), for time.
  std::array<P, 3> tri;
  for (std::size_t k = 0; k < 3; ++k) tri[k] = {double(t[k].u) * w, double(t[k].v) * h};
  std::vector<std::uint32_t> expected;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 17; ++x)
      if (overlapArea(tri, x, y) > 1e-12) expected.push_back(static_cast<std::uint32_t>(y * w + x));
  EXPECT_EQ(texelsOf(r), expected);
}

TEST(TexelRaster, InvalidInputIsAnError) {
  const Mesh good = quad(0.1f, 0.1f, 0.9f, 0.9f);
  auto status = [](const Mesh& m, int w = 16, int h = 16) {
    TexelRaster r;
    r.samples.resize(3);
    const Status s = rasteriseTexels(m.positions, m.normals, m.indices, m.uvs, w, h, &r);
    if (!s.isOk()) {
      EXPECT_TRUE(r.samples.empty() && r.coverage.empty()) << "an error leaves the output empty";
      EXPECT_NE(s.message().find("texel rasterisation"), std::string::npos) << s.message();
    }
    return s.code();
  };
  EXPECT_EQ(status(good), StatusCode::kOk);
  Mesh m = good;
  m.uvs[2].u = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(status(m), StatusCode::kNotFinite);
  m = good;
  m.uvs[1].v = std::numeric_limits<float>::infinity();
  EXPECT_EQ(status(m), StatusCode::kNotFinite);
  m = good;
  m.uvs[1].u = 1.0001f;
  EXPECT_EQ(status(m), StatusCode::kInvalidArgument);
  m = good;
  m.uvs[3].v = -0.25f;
  EXPECT_EQ(status(m), StatusCode::kInvalidArgument);
  m = good;
  m.indices[4] = 4;
  EXPECT_EQ(status(m), StatusCode::kInvalidArgument);
  m = good;
  m.indices.pop_back();
  EXPECT_EQ(status(m), StatusCode::kInvalidArgument);
  m = good;
  m.normals.pop_back();
  EXPECT_EQ(status(m), StatusCode::kSizeMismatch);
  m = good;
  m.uvs.push_back({0, 0});
  EXPECT_EQ(status(m), StatusCode::kSizeMismatch);
  m = good;
  m.positions[0].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(status(m), StatusCode::kNotFinite);
  m = good;
  m.normals[2] = {0, 0, 0};
  EXPECT_EQ(status(m), StatusCode::kInvalidArgument);
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{0, 16}, {16, 0}, {-3, 16}, {16385, 16}, {16, 16385}})
    EXPECT_EQ(status(good, w, h), StatusCode::kInvalidArgument) << w << "x" << h;
  EXPECT_EQ(status(good, 1, 1), StatusCode::kOk);
  EXPECT_EQ(rasteriseTexels(good.positions, good.normals, good.indices, good.uvs, 16, 16, nullptr).code(),
            StatusCode::kInvalidArgument);
  // A vertex no triangle references is not read, garbage or not.
  m = good;
  m.positions.push_back({NAN, 0, 0});
  m.normals.push_back({0, 0, 0});
  m.uvs.push_back({5, NAN});
  EXPECT_EQ(status(m), StatusCode::kOk);
}

TEST(TexelRaster, StackedLayoutStopsAtTheBudget) {
  // 400 copies of a full-square triangle touch ~136 texels each at 16 × 16: 54 000 visits,
  // over 64 × 256 + 64 × 400 = 41 984.
  Mesh m;
  for (int i = 0; i < 400; ++i) m.addFlat({Uv{0, 0}, Uv{1, 0}, Uv{0, 1}});
  TexelRaster r;
  const Status s = rasteriseTexels(m.positions, m.normals, m.indices, m.uvs, 16, 16, &r);
  EXPECT_EQ(s.code(), StatusCode::kResourceExhausted) << s.toString();
  EXPECT_TRUE(r.samples.empty());
  // 100 copies stay within it (13 600 < 22 784), and the lowest index owns every texel.
  Mesh fewer;
  for (int i = 0; i < 100; ++i) fewer.addFlat({Uv{0, 0}, Uv{1, 0}, Uv{0, 1}});
  const TexelRaster ok = raster(fewer, 16, 16);
  ASSERT_FALSE(ok.samples.empty());
  for (const TexelSample& t : ok.samples) EXPECT_EQ(t.triangle, 0u);
}

}  // namespace
}  // namespace prt::bake
