#include "prt/sh_planar_light.h"

#include <cmath>
#include <string>
#include <vector>

namespace prt {
namespace {

Status invalid(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

struct D3 {
  double x, y, z;
};
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 toD3(Vec3 v) { return {v.x, v.y, v.z}; }

// The polygon's vertices as unit directions from `point`, in reverse order: counter-clockwise
// seen from the front (where the point is) is clockwise seen from beyond the polygon, and
// the spherical projection wants counter-clockwise from outside the sphere.
Status directionsFrom(std::span<const D3> vertices, D3 point, std::vector<double>* unit) {
  const std::size_t n = vertices.size();
  unit->resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const D3 d = sub(vertices[n - 1 - i], point);
    const double len = std::sqrt(dot(d, d));
    if (!(len > 0.0)) return invalid("the point coincides with polygon vertex " + std::to_string(n - 1 - i));
    (*unit)[3 * i] = d.x / len;
    (*unit)[3 * i + 1] = d.y / len;
    (*unit)[3 * i + 2] = d.z / len;
  }
  return Status::ok();
}

Status checkOutput(const PolygonShProjector& projector, std::span<double> out) {
  if (projector.order() == 0) return invalid("the polygon projector was not made (PolygonShProjector::make)");
  const std::size_t need = static_cast<std::size_t>(projector.order() * projector.order());
  if (out.size() < need) {
    return Status::error(StatusCode::kSizeMismatch, "output holds " + std::to_string(out.size()) + " values, " + std::to_string(need) + " needed");
  }
  return Status::ok();
}

// Which side of the plane through `origin` with unit normal `n` the point lies on, relative to `size`.
Status checkFacing(D3 n, D3 origin, D3 point, double size, const char* what) {
  const double h = dot(n, sub(point, origin));
  if (std::fabs(h) <= 1e-6 * size) return invalid(std::string("the point lies in the ") + what + "'s plane (it subtends no solid angle)");
  if (h < 0.0) {
    return invalid(std::string("the point is behind the ") + what + " (it emits toward its normal (" + std::to_string(n.x) + ", " +
                   std::to_string(n.y) + ", " + std::to_string(n.z) + ") only)");
  }
  return Status::ok();
}

}  // namespace

Status accumulatePlanarPolygon(const PolygonShProjector& projector, std::span<const Vec3> vertices, Vec3 point, double scale,
                               std::span<double> out) {
  PRT_RETURN_IF_ERROR(checkOutput(projector, out));
  const std::size_t n = vertices.size();
  if (n < 3) return invalid("a planar polygon needs at least 3 vertices, got " + std::to_string(n));
  if (n > static_cast<std::size_t>(kMaxPolygonVertices)) {
    return invalid("a planar polygon has at most " + std::to_string(kMaxPolygonVertices) + " vertices, got " + std::to_string(n));
  }
  if (!isFinite(point) || !std::isfinite(scale)) return Status::error(StatusCode::kNotFinite, "the point or scale is not finite");
  std::vector<D3> p(n);
  D3 centroid{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    if (!isFinite(vertices[i])) return Status::error(StatusCode::kNotFinite, "polygon vertex " + std::to_string(i) + " is not finite");
    p[i] = toD3(vertices[i]);
    centroid = {centroid.x + p[i].x / n, centroid.y + p[i].y / n, centroid.z + p[i].z / n};
  }
  // Newell's area vector, about the centroid for precision: twice the area times the normal.
  D3 area{0, 0, 0};
  double size = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const D3 a = sub(p[i], centroid), b = sub(p[(i + 1) % n], centroid);
    const D3 c = cross(a, b);
    area = {area.x + c.x, area.y + c.y, area.z + c.z};
    size = std::fmax(size, std::sqrt(dot(a, a)));
  }
  const double twiceArea = std::sqrt(dot(area, area));
  if (!(twiceArea > 1e-10 * size * size) || !(size > 0.0)) return invalid("the polygon has zero area (degenerate)");
  const D3 normal{area.x / twiceArea, area.y / twiceArea, area.z / twiceArea};
  for (std::size_t i = 0; i < n; ++i) {
    const double off = dot(normal, sub(p[i], centroid));
    if (std::fabs(off) > 1e-4 * size) {
      return invalid("polygon vertex " + std::to_string(i) + " is " + std::to_string(off) + " off the polygon's plane (non-planar; size " +
                     std::to_string(size) + ")");
    }
  }
  PRT_RETURN_IF_ERROR(checkFacing(normal, centroid, toD3(point), size, "polygon"));
  std::vector<double> unit;
  PRT_RETURN_IF_ERROR(directionsFrom(p, toD3(point), &unit));
  projector.accumulateUnchecked(unit, scale, out.data());
  return Status::ok();
}

Status accumulateDisc(const PolygonShProjector& projector, Vec3 centre, Vec3 normal, float radius, Vec3 point, int edges,
                      double scale, std::span<double> out) {
  PRT_RETURN_IF_ERROR(checkOutput(projector, out));
  if (!isFinite(centre) || !isFinite(normal) || !std::isfinite(radius) || !isFinite(point) || !std::isfinite(scale)) {
    return Status::error(StatusCode::kNotFinite, "a disc parameter is not finite");
  }
  if (!(radius > 0.0f)) return invalid("the disc radius must be > 0, got " + std::to_string(radius));
  if (edges < 3 || edges > kMaxDiscEdges) {
    return invalid("a disc is a polygon of 3.." + std::to_string(kMaxDiscEdges) + " edges, got " + std::to_string(edges));
  }
  D3 nd = toD3(normal);
  const double len = std::sqrt(dot(nd, nd));
  if (!(len > 0.0)) return invalid("the disc normal is the zero vector");
  nd = {nd.x / len, nd.y / len, nd.z / len};
  const D3 c = toD3(centre), q = toD3(point);
  PRT_RETURN_IF_ERROR(checkFacing(nd, c, q, radius, "disc"));
  // In-plane frame u x v = n, so increasing angle runs counter-clockwise seen from the front.
  D3 u = std::fabs(nd.x) < 0.9 ? cross(D3{1, 0, 0}, nd) : cross(D3{0, 1, 0}, nd);
  const double ul = std::sqrt(dot(u, u));
  u = {u.x / ul, u.y / ul, u.z / ul};
  const D3 v = cross(nd, u);
  // Equal area: K/2 R^2 sin(2pi/K) = pi r^2 keeps L_0's leading error term at zero.
  const double step = 2.0 * kPi / edges;
  const double rr = radius * std::sqrt(2.0 * kPi / (edges * std::sin(step)));
  // Directions from the point, clockwise seen from the front (see directionsFrom).
  std::vector<double> unit(3 * static_cast<std::size_t>(edges));
  const D3 rel = sub(c, q);
  const double cs = std::cos(step), sn = std::sin(step);
  double ca = 1.0, sa = 0.0;  // cos, sin of -k step by rotation, one sin/cos in all
  for (int k = 0; k < edges; ++k) {
    const D3 d{rel.x + rr * (ca * u.x + sa * v.x), rel.y + rr * (ca * u.y + sa * v.y), rel.z + rr * (ca * u.z + sa * v.z)};
    const double dl = std::sqrt(dot(d, d));
    unit[3 * k] = d.x / dl;
    unit[3 * k + 1] = d.y / dl;
    unit[3 * k + 2] = d.z / dl;
    const double nc = ca * cs + sa * sn, ns = sa * cs - ca * sn;
    ca = nc;
    sa = ns;
  }
  projector.accumulateUnchecked(unit, scale, out.data());
  return Status::ok();
}

}  // namespace prt
