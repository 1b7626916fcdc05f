#include "prt/sh_polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "prt/sh_basis.h"
#include "prt/sh_planar_light.h"
#include "prt/sh_rotation.h"
#include "prt/sh_zonal.h"
#include "support/quadrature.h"

namespace prt {
namespace {

constexpr int kOrder = kMaxPolygonShOrder;
constexpr int kCoeffs = kOrder * kOrder;

Vec3 unit(Vec3 v) { return v * (1.0f / length(v)); }

// Direction at polar angle theta and azimuth phi about +z.
Vec3 polar(double theta, double phi) {
  return {static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::sin(theta) * std::sin(phi)),
          static_cast<float>(std::cos(theta))};
}

// Integral of y_k over the spherical triangle (a, b, c) (any orientation, smaller than a
// hemisphere): the flat triangle through a, b, c projected radially, dOmega =
// |q . ((b-a) x (c-a))| / |q|^3 ds dt, on a collapsed (Duffy) Gauss-Legendre rule. The
// integrand is smooth, so this converges fast; it shares nothing with the edge recurrence.
void addTriangle(Vec3 a, Vec3 b, Vec3 c, double sign, std::vector<double>& out) {
  std::vector<double> x, w;
  ref::gaussLegendre(40, &x, &w);
  const Vec3 e1 = b - a, e2 = c - a, nrm = cross(e1, e2);
  std::vector<float> y(kCoeffs);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double u = 0.5 * (x[i] + 1.0);
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double v = 0.5 * (x[j] + 1.0);
      const double s = u, t = v * (1.0 - u);
      const double qx = a.x + s * e1.x + t * e2.x, qy = a.y + s * e1.y + t * e2.y, qz = a.z + s * e1.z + t * e2.z;
      const double q2 = qx * qx + qy * qy + qz * qz, ql = std::sqrt(q2);
      const double jac = std::fabs(qx * nrm.x + qy * nrm.y + qz * nrm.z) / (q2 * ql) * (1.0 - u) * 0.25 * w[i] * w[j];
      evalShBasisUnchecked(kOrder, Vec3{static_cast<float>(qx / ql), static_cast<float>(qy / ql), static_cast<float>(qz / ql)}, y.data());
      for (int k = 0; k < kCoeffs; ++k) out[k] += sign * jac * y[k];
    }
  }
}

// A polygon star-shaped about `centre`: the union of the fan triangles (centre, v_i, v_{i+1}).
std::vector<double> fanReference(Vec3 centre, const std::vector<Vec3>& poly) {
  std::vector<double> ref(kCoeffs, 0.0);
  for (std::size_t i = 0; i < poly.size(); ++i) addTriangle(centre, poly[i], poly[(i + 1) % poly.size()], 1.0, ref);
  return ref;
}

bool inTriangle(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  // Convex spherical triangle counter-clockwise from outside: inside all three edge planes.
  return dot(cross(a, b), d) >= 0 && dot(cross(b, c), d) >= 0 && dot(cross(c, a), d) >= 0;
}

double maxAbsDiff(std::span<const float> a, std::span<const double> b, int count) {
  double m = 0.0;
  for (int k = 0; k < count; ++k) m = std::max(m, std::fabs(a[k] - b[k]));
  return m;
}

std::vector<float> project(int order, const std::vector<Vec3>& poly) {
  PolygonShProjector p;
  EXPECT_TRUE(PolygonShProjector::make(order, &p).isOk());
  std::vector<float> out(shCoeffCount(order), -1.0f);
  const Status s = p.projectSpherical(poly, out);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return out;
}

// Every order 1..8 against the order-8 reference (a lower order's coefficients are a prefix).
void expectAllOrders(const std::vector<Vec3>& poly, const std::vector<double>& ref, double tol) {
  for (int order = 1; order <= kOrder; ++order) {
    const std::vector<float> got = project(order, poly);
    EXPECT_LE(maxAbsDiff(got, ref, shCoeffCount(order)), tol) << "order " << order;
  }
}

std::vector<Vec3> regularAround(int n, double theta, double phase = 0.0) {
  std::vector<Vec3> v;
  for (int k = 0; k < n; ++k) v.push_back(polar(theta, phase + 2.0 * kPi * k / n));
  return v;
}

TEST(PolygonSh, TrianglesMatchQuadrature) {
  const std::vector<std::vector<Vec3>> triangles = {
      {unit({0.1f, 0.2f, 1}), unit({0.5f, -0.1f, 1}), unit({0.2f, 0.6f, 1})},     // small, ~0.1 sr
      {unit({1, 0, 0.2f}), unit({0, 1, 0.2f}), unit({-1, -1, 0.3f})},             // nearly a hemisphere
      {unit({0.3f, -0.9f, -0.2f}), unit({0.9f, 0.1f, -0.4f}), unit({0.2f, 0.1f, -1})},  // away from the pole
  };
  for (std::vector<Vec3> tri : triangles) {
    if (dot(cross(tri[1] - tri[0], tri[2] - tri[1]), tri[0]) < 0) std::swap(tri[1], tri[2]);
    std::vector<double> ref(kCoeffs, 0.0);
    addTriangle(tri[0], tri[1], tri[2], 1.0, ref);
    expectAllOrders(tri, ref, 2e-6);
  }
}

TEST(PolygonSh, QuadsMatchQuadrature) {
  // A rectangle seen off-centre from a point and a thin sliver, both convex.
  const std::vector<std::vector<Vec3>> quads = {
      {unit({-0.4f, -0.2f, 1}), unit({0.6f, -0.2f, 1}), unit({0.6f, 0.5f, 1}), unit({-0.4f, 0.5f, 1})},
      {unit({1, 0, 0}), unit({0.98f, 0.2f, 0.05f}), unit({0.2f, 0.98f, 0.05f}), unit({0, 1, 0})},
  };
  for (std::vector<Vec3> q : quads) {
    if (dot(cross(q[1] - q[0], q[2] - q[1]), q[0]) < 0) std::reverse(q.begin(), q.end());
    std::vector<double> ref(kCoeffs, 0.0);
    addTriangle(q[0], q[1], q[2], 1.0, ref);
    addTriangle(q[0], q[2], q[3], 1.0, ref);
    expectAllOrders(q, ref, 2e-6);
  }
}

TEST(PolygonSh, ConcaveStarMatchesQuadrature) {
  std::vector<Vec3> star;
  for (int k = 0; k < 10; ++k) star.push_back(polar(k % 2 ? 0.25 : 0.7, 2.0 * kPi * k / 10 + 0.3));
  expectAllOrders(star, fanReference({0, 0, 1}, star), 4e-6);
}

TEST(PolygonSh, LargerThanAHemisphereMatchesQuadrature) {
  // A hexagon 120 degrees from the pole (3.2 pi sr) and the complement of a small triangle.
  const std::vector<Vec3> hexagon = regularAround(6, 2.1, 0.2);
  const std::vector<double> ref = fanReference({0, 0, 1}, hexagon);
  EXPECT_GT(ref[0] / 0.28209479177387814, 2.0 * kPi + 1.0);
  expectAllOrders(hexagon, ref, 4e-6);

  const std::vector<Vec3> small = {unit({0.1f, 0.2f, 1}), unit({0.5f, -0.1f, 1}), unit({0.2f, 0.6f, 1})};
  std::vector<double> full(kCoeffs, 0.0);
  full[0] = 4.0 * kPi * 0.28209479177387814;
  addTriangle(small[0], small[1], small[2], -1.0, full);
  expectAllOrders({small[0], small[2], small[1]}, full, 4e-6);  // clockwise from outside: the rest of the sphere
}

TEST(PolygonSh, IndicatorSamplingAgrees) {
  // The literal brute force: a 600 x 1200 product rule summing y_k where the polygon's
  // indicator is 1. Independent of the triangle quadrature above; its error is the
  // boundary's sampling, about 1e-4 here.
  std::vector<Vec3> star;
  for (int k = 0; k < 10; ++k) star.push_back(polar(k % 2 ? 0.25 : 0.7, 2.0 * kPi * k / 10 + 0.3));
  const std::vector<Vec3> hexagon = regularAround(6, 2.1, 0.2);
  const std::vector<ref::WeightedDirection> quad = ref::sphereQuadrature(600);
  for (const std::vector<Vec3>* poly : std::vector<const std::vector<Vec3>*>{&star, &hexagon}) {
    std::vector<double> ref(kCoeffs, 0.0);
    std::vector<float> y(kCoeffs);
    const Vec3 pole{0, 0, 1};
    for (const ref::WeightedDirection& d : quad) {
      bool inside = false;
      for (std::size_t i = 0; i < poly->size() && !inside; ++i) inside = inTriangle(pole, (*poly)[i], (*poly)[(i + 1) % poly->size()], d.dir);
      if (!inside) continue;
      evalShBasisUnchecked(kOrder, d.dir, y.data());
      for (int k = 0; k < kCoeffs; ++k) ref[k] += d.weight * y[k];
    }
    EXPECT_LE(maxAbsDiff(project(kOrder, *poly), ref, kCoeffs), 1e-3);
  }
}

TEST(PolygonSh, RotatingThePolygonRotatesTheProjection) {
  std::vector<Vec3> star;
  for (int k = 0; k < 10; ++k) star.push_back(polar(k % 2 ? 0.3 : 0.8, 2.0 * kPi * k / 10));
  const Mat3 r = rotationAxisAngle(unit({0.3f, -0.5f, 0.8f}), 1.234f) * rotationAxisAngle({1, 0, 0}, 2.0f);
  std::vector<Vec3> rotated;
  for (Vec3 v : star) rotated.push_back(r * v);
  for (int order : {2, 5, 8}) {
    ShRotation rot;
    ASSERT_TRUE(ShRotation::make(order, r, &rot).isOk());
    const std::vector<float> base = project(order, star);
    std::vector<float> expected(base.size());
    ASSERT_TRUE(rot.apply(base, expected).isOk());
    const std::vector<float> got = project(order, rotated);
    for (std::size_t k = 0; k < got.size(); ++k) EXPECT_NEAR(got[k], expected[k], 3e-6) << "order " << order << " k " << k;
  }
}

// Max |polygon - cap| over the coefficients of an n-gon inscribed in the cap of half-angle
// zeta about `axis`.
double capError(int n, double zeta, Vec3 axis) {
  const Mat3 r = rotationAxisAngle(unit(cross({0, 0, 1}, axis)), std::acos(axis.z));
  std::vector<Vec3> poly;
  for (Vec3 v : regularAround(n, zeta)) poly.push_back(r * v);
  std::vector<float> zonal(kOrder), cap(kCoeffs);
  EXPECT_TRUE(zonalCircularLight(kOrder, static_cast<float>(zeta), 1.0f, zonal).isOk());
  EXPECT_TRUE(placeZonal(kOrder, zonal, axis, cap).isOk());
  const std::vector<float> got = project(kOrder, poly);
  double m = 0.0;
  for (int k = 0; k < kCoeffs; ++k) m = std::max(m, static_cast<double>(std::fabs(got[k] - cap[k])));
  return m;
}

TEST(PolygonSh, Regular256GonConvergesToTheCap) {
  const Vec3 axis = unit({0.3f, 0.4f, 0.6f});
  for (double zeta : {0.3, 1.0, 2.0}) {
    const double e64 = capError(64, zeta, axis), e256 = capError(256, zeta, axis);
    // The inscribed polygon misses (2pi/n)^2/6 of the cap's area near its rim: 1.0e-4 at 256.
    const double capL0 = 2.0 * kPi * (1.0 - std::cos(zeta)) * 0.28209479177387814;
    EXPECT_LE(e256, 1.5e-4 * capL0 + 2e-6) << "zeta " << zeta;
    EXPECT_LT(e256, e64 / 8.0) << "zeta " << zeta << ": second-order convergence";
  }
}

TEST(PolygonSh, VerticesOnTheEquatorBoundAHemisphere) {
  // Not degenerate: counter-clockwise about +z along the equator encloses the northern half.
  const std::vector<Vec3> equator = {{1, 0, 0}, {0, 1, 0}, {-1, 0.1f, 0}, {0, -1, 0}};
  std::vector<float> zonal(kOrder), cap(kCoeffs);
  ASSERT_TRUE(zonalCircularLight(kOrder, static_cast<float>(kPi / 2), 1.0f, zonal).isOk());
  ASSERT_TRUE(placeZonal(kOrder, zonal, {0, 0, 1}, cap).isOk());
  const std::vector<float> got = project(kOrder, equator);
  for (int k = 0; k < kCoeffs; ++k) EXPECT_NEAR(got[k], cap[k], 2e-6) << k;
}

TEST(PolygonSh, PlanarRectangleOnAxisHasTheClosedFormSolidAngle) {
  PolygonShProjector p;
  ASSERT_TRUE(PolygonShProjector::make(5, &p).isOk());
  const double a = 0.25, b = 0.4, d = 1.2f;  // half-sides, distance (as the float input holds it)
  // Emits toward -z (counter-clockwise seen from below), seen from the origin.
  const std::vector<Vec3> rect = {{-0.25f, -0.4f, 1.2f}, {-0.25f, 0.4f, 1.2f}, {0.25f, 0.4f, 1.2f}, {0.25f, -0.4f, 1.2f}};
  std::vector<double> out(25, 0.0);
  const Status s = accumulatePlanarPolygon(p, rect, {0, 0, 0}, 2.0, out);
  ASSERT_TRUE(s.isOk()) << s.toString();
  const double omega = 4.0 * std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d)));
  EXPECT_NEAR(out[0], 2.0 * omega * 0.28209479177387814, 1e-7);
  // Symmetric about the z axis in x and y: no odd-in-x or odd-in-y terms.
  EXPECT_NEAR(out[shIndex(1, 1)], 0.0, 1e-7);
  EXPECT_NEAR(out[shIndex(1, -1)], 0.0, 1e-7);
  EXPECT_GT(out[shIndex(1, 0)], 0.0);  // the light is toward +z and y_10 = 0.49 z
}

TEST(PolygonSh, PlanarPolygonEqualsItsSphericalProjection) {
  PolygonShProjector p;
  ASSERT_TRUE(PolygonShProjector::make(kOrder, &p).isOk());
  // A concave L in the plane x = 2 emitting toward -x, seen from (0.1, 0.2, -0.3).
  const std::vector<Vec3> ell = {{2, 0, 0}, {2, 0, 1}, {2, 0.3f, 1}, {2, 0.3f, 0.3f}, {2, 1, 0.3f}, {2, 1, 0}};
  // Counter-clockwise seen from -x: check with the area vector, reverse if not.
  Vec3 area{};
  for (std::size_t i = 0; i < ell.size(); ++i) area = area + cross(ell[i], ell[(i + 1) % ell.size()]);
  std::vector<Vec3> poly = ell;
  if (area.x > 0) std::reverse(poly.begin(), poly.end());
  const Vec3 eye{0.1f, 0.2f, -0.3f};
  std::vector<double> planar(kCoeffs, 0.0);
  ASSERT_TRUE(accumulatePlanarPolygon(p, poly, eye, 1.0, planar).isOk());
  std::vector<Vec3> dirs;
  for (auto it = poly.rbegin(); it != poly.rend(); ++it) dirs.push_back(*it - eye);
  std::vector<float> spherical(kCoeffs);
  ASSERT_TRUE(p.projectSpherical(dirs, spherical).isOk());
  EXPECT_LE(maxAbsDiff(spherical, planar, kCoeffs), 1e-6);
  EXPECT_GT(planar[0], 0.0);
}

// Discs: max coefficient error of an `edges`-gon of equal area against the cap (on axis,
// exact: a disc of radius r at distance d on its axis is the cap tan(zeta) = r/d) and against
// a 1024-gon (off axis), relative to L_0.
double discError(int edges, Vec3 eye) {
  PolygonShProjector p;
  EXPECT_TRUE(PolygonShProjector::make(kOrder, &p).isOk());
  const Vec3 centre{0, 0, 1}, normal{0, 0, -1};
  std::vector<double> got(kCoeffs, 0.0), ref(kCoeffs, 0.0);
  EXPECT_TRUE(accumulateDisc(p, centre, normal, 0.5f, eye, edges, 1.0, got).isOk());
  EXPECT_TRUE(accumulateDisc(p, centre, normal, 0.5f, eye, kMaxDiscEdges, 1.0, ref).isOk());
  double m = 0.0;
  for (int k = 0; k < kCoeffs; ++k) m = std::max(m, std::fabs(got[k] - ref[k]));
  return m / ref[0];
}

TEST(PolygonSh, DiscOnAxisIsTheCap) {
  PolygonShProjector p;
  ASSERT_TRUE(PolygonShProjector::make(kOrder, &p).isOk());
  const double r = 0.5, d = 0.8;
  std::vector<double> got(kCoeffs, 0.0);
  ASSERT_TRUE(accumulateDisc(p, {0, 0, static_cast<float>(d)}, {0, 0, -1}, static_cast<float>(r), {0, 0, 0}, kMaxDiscEdges, 1.0, got).isOk());
  std::vector<float> zonal(kOrder), cap(kCoeffs);
  ASSERT_TRUE(zonalCircularLight(kOrder, static_cast<float>(std::atan(r / d)), 1.0f, zonal).isOk());
  ASSERT_TRUE(placeZonal(kOrder, zonal, {0, 0, 1}, cap).isOk());
  // The 1024-gon's residual shape error (about 2e-6 of L_0 at l = 7) and the float cap.
  for (int k = 0; k < kCoeffs; ++k) EXPECT_NEAR(got[k], cap[k], 1e-5 * cap[0]) << k;
}

TEST(PolygonSh, DefaultDiscEdgesMeetTheStatedError) {
  // docs/analytic-lights.md states < 1e-4 of L_0 for kDefaultDiscEdges when the point is at
  // least half a radius from the rim (near, far, off axis, grazing), < 5e-3 at 0.1 radii.
  for (Vec3 eye : {Vec3{0, 0, 0}, Vec3{0, 0, 0.9f}, Vec3{0.6f, 0.2f, 0.7f}, Vec3{3, 0, 0.5f}, Vec3{0.3f, -0.2f, -4}}) {
    const double e = discError(kDefaultDiscEdges, eye);
    EXPECT_LT(e, 1e-4) << eye.x << " " << eye.y << " " << eye.z;
    EXPECT_LT(discError(2 * kDefaultDiscEdges, eye), e / 4) << "second-order convergence in the edge count";
  }
  EXPECT_LT(discError(kDefaultDiscEdges, {0.45f, 0, 0.95f}), 5e-3);
}

TEST(PolygonSh, RejectsBadInput) {
  PolygonShProjector p;
  EXPECT_FALSE(PolygonShProjector::make(0, &p).isOk());
  EXPECT_FALSE(PolygonShProjector::make(9, &p).isOk());
  std::vector<float> out(kCoeffs);
  EXPECT_FALSE(p.projectSpherical({{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}}, out).isOk()) << "not made";
  ASSERT_TRUE(PolygonShProjector::make(kOrder, &p).isOk());
  auto message = [&](std::vector<Vec3> poly) {
    const Status s = p.projectSpherical(poly, out);
    EXPECT_FALSE(s.isOk());
    return s.message();
  };
  const float nan = std::nanf("");
  EXPECT_NE(message({{1, 0, 0}, {0, 1, 0}}).find("at least 3"), std::string::npos);
  EXPECT_NE(message({{1, 0, 0}, {0, 1, 0}, {nan, 0, 1}}).find("not finite"), std::string::npos);
  EXPECT_NE(message({{1, 0, 0}, {0, 1, 0}, {0, 0, 0}}).find("zero vector"), std::string::npos);
  EXPECT_NE(message({{1, 0, 0}, {2, 0, 0}, {0, 0, 1}}).find("coincide"), std::string::npos);
  EXPECT_NE(message({{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}}).find("antipodal"), std::string::npos);
  EXPECT_NE(message({{1, 0, 0}, {0, 1, 0}, {0.5f, 0.5f, 0}, {0, 0, 1}}).find("doubles back"), std::string::npos);
  std::vector<float> small(3);
  EXPECT_EQ(p.projectSpherical({{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}}, small).code(), StatusCode::kSizeMismatch);

  std::vector<double> acc(kCoeffs, 0.0);
  auto planar = [&](std::vector<Vec3> poly, Vec3 eye) {
    const Status s = accumulatePlanarPolygon(p, poly, eye, 1.0, acc);
    EXPECT_FALSE(s.isOk());
    return s.message();
  };
  const std::vector<Vec3> square = {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};  // emits toward -z
  EXPECT_NE(planar({{0, 0, 1}, {1, 1, 1}, {2, 2, 1}}, {0, 0, 0}).find("zero area"), std::string::npos);
  EXPECT_NE(planar({{0, 0, 1}, {0, 1, 1}, {1, 1, 1.2f}, {1, 0, 1}}, {0, 0, 0}).find("non-planar"), std::string::npos);
  EXPECT_NE(planar(square, {0.5f, 0.5f, 2}).find("behind"), std::string::npos);
  EXPECT_NE(planar(square, {3, 0.5f, 1}).find("in the polygon's plane"), std::string::npos);
  EXPECT_TRUE(accumulatePlanarPolygon(p, square, {0.5f, 0.5f, 0}, 1.0, acc).isOk());
  for (double v : acc) EXPECT_TRUE(std::isfinite(v));

  auto disc = [&](Vec3 normal, float radius, Vec3 eye, int edges) {
    const Status s = accumulateDisc(p, {0, 0, 1}, normal, radius, eye, edges, 1.0, acc);
    EXPECT_FALSE(s.isOk());
    return s.message();
  };
  EXPECT_NE(disc({0, 0, -1}, 0.0f, {0, 0, 0}, 32).find("radius"), std::string::npos);
  EXPECT_NE(disc({0, 0, 0}, 0.5f, {0, 0, 0}, 32).find("zero vector"), std::string::npos);
  EXPECT_NE(disc({0, 0, -1}, 0.5f, {0, 0, 0}, 2).find("edges"), std::string::npos);
  EXPECT_NE(disc({0, 0, 1}, 0.5f, {0, 0, 0}, 32).find("behind"), std::string::npos);
  EXPECT_NE(disc({0, 0, -1}, 0.5f, {2, 0, 1}, 32).find("plane"), std::string::npos);
}

}  // namespace
}  // namespace prt
