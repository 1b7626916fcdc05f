#include "prt/sh_polygon.h"

#include <cmath>
#include <string>

#include "prt/sh_basis.h"

namespace prt {
namespace {

struct D3 {
  double x, y, z;
};
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 scale(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(D3 a) { return std::sqrt(dot(a, a)); }

// Lobe directions: a golden-ratio sequence in z and azimuth, so every prefix of 2l+1
// directions is spread over the sphere (no two close, none antipodal) and the band-l
// lobe matrix built from the prefix is well conditioned for every l < 8.
D3 lobeDirection(int j) {
  const double golden = 0.6180339887498949;
  const double f = std::fmod((j + 0.5) * golden, 1.0);
  const double z = 1.0 - 2.0 * f;
  const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
  const double phi = 2.399963229728653 * j;  // golden angle
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// In-place inverse of the n x n row-major matrix a (Gauss-Jordan, partial pivoting).
// False when singular.
bool invert(int n, std::vector<double>& a) {
  std::vector<double> inv(static_cast<std::size_t>(n * n), 0.0);
  for (int i = 0; i < n; ++i) inv[i * n + i] = 1.0;
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::fabs(a[r * n + col]) > std::fabs(a[pivot * n + col])) pivot = r;
    if (std::fabs(a[pivot * n + col]) < 1e-12) return false;
    for (int k = 0; k < n; ++k) {
      std::swap(a[col * n + k], a[pivot * n + k]);
      std::swap(inv[col * n + k], inv[pivot * n + k]);
    }
    const double d = 1.0 / a[col * n + col];
    for (int k = 0; k < n; ++k) {
      a[col * n + k] *= d;
      inv[col * n + k] *= d;
    }
    for (int r = 0; r < n; ++r) {
      if (r == col) continue;
      const double f = a[r * n + col];
      if (f == 0.0) continue;
      for (int k = 0; k < n; ++k) {
        a[r * n + k] -= f * a[col * n + k];
        inv[r * n + k] -= f * inv[col * n + k];
      }
    }
  }
  a = std::move(inv);
  return true;
}

Status invalid(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

}  // namespace

Status PolygonShProjector::make(int order, PolygonShProjector* out) {
  if (order < 1 || order > kMaxPolygonShOrder) {
    return invalid("polygon SH order " + std::to_string(order) + " is outside [1, " + std::to_string(kMaxPolygonShOrder) + "]");
  }
  PolygonShProjector p;
  p.order_ = order;
  p.lobeCount_ = 2 * order - 1;
  for (int j = 0; j < p.lobeCount_; ++j) {
    const D3 w = lobeDirection(j);
    p.lobes_.insert(p.lobes_.end(), {w.x, w.y, w.z});
  }
  // Band l: y_lm(u) = sum_j A_mj P_l(w_j . u). By the addition theorem P_l(w . u) =
  // 4pi/(2l+1) sum_m y_lm(w) y_lm(u), so with Y_mj = y_lm(w_j): A Y^T = (2l+1)/4pi I.
  std::vector<float> y(static_cast<std::size_t>(order * order));
  std::vector<std::vector<float>> basis;
  for (int j = 0; j < p.lobeCount_; ++j) {
    const D3 w = lobeDirection(j);
    evalShBasisUnchecked(order, Vec3{static_cast<float>(w.x), static_cast<float>(w.y), static_cast<float>(w.z)}, y.data());
    basis.push_back(y);
  }
  for (int l = 0; l < order; ++l) {
    const int n = 2 * l + 1;
    std::vector<double> yt(static_cast<std::size_t>(n * n));  // Y^T: row j, column m
    for (int j = 0; j < n; ++j)
      for (int m = 0; m < n; ++m) yt[j * n + m] = basis[j][shIndex(l, m - l)];
    if (!invert(n, yt)) return Status::error(StatusCode::kInternal, "polygon SH lobe matrix of band " + std::to_string(l) + " is singular");
    const double k = (2.0 * l + 1.0) / (4.0 * kPi);
    for (int m = 0; m < n; ++m)
      for (int j = 0; j < n; ++j) p.lobeToSh_.push_back(k * yt[m * n + j]);  // (Y^T)^-1 = row m, column j
  }
  // Power coefficients of P_l (Bonnet: l P_l = (2l-1) x P_{l-1} - (l-1) P_{l-2}), then
  // differentiated.
  std::vector<std::vector<double>> legendre(static_cast<std::size_t>(order + 1), std::vector<double>(order + 1, 0.0));
  legendre[0][0] = 1.0;
  if (order >= 1) legendre[1][1] = 1.0;
  for (int l = 2; l <= order; ++l)
    for (int k = 0; k <= l; ++k)
      legendre[l][k] = ((k > 0 ? (2.0 * l - 1.0) * legendre[l - 1][k - 1] : 0.0) - (l - 1.0) * legendre[l - 2][k]) / l;
  p.dLegendre_.assign(static_cast<std::size_t>(order * order), 0.0);
  for (int l = 1; l < order; ++l)
    for (int k = 0; k < l; ++k) p.dLegendre_[l * order + k] = (k + 1) * legendre[l][k + 1];
  *out = std::move(p);
  return Status::ok();
}

void PolygonShProjector::accumulateUnchecked(std::span<const double> v, double scaleBy, double* out) const {
  const int n = static_cast<int>(v.size() / 3);
  const int order = order_;
  const int lobes = lobeCount_;
  // s[j * order + l]: sum over edges of (w_j . n_e) int_edge P_l'(w_j . u) ds.
  double s[(2 * kMaxPolygonShOrder - 1) * kMaxPolygonShOrder] = {};
  double moments[kMaxPolygonShOrder];
  double turning = 0.0;
  auto vertex = [&](int i) { return D3{v[3 * i], v[3 * i + 1], v[3 * i + 2]}; };
  // Tangent at the end of the previous edge, for the turning angle at each vertex.
  D3 tPrev{};
  {
    const D3 a = vertex(n - 1), c = vertex(0);
    const D3 e = cross(a, c);
    tPrev = cross(scale(e, 1.0 / norm(e)), c);
  }
  for (int i = 0; i < n; ++i) {
    // Edge a -> c on the great circle with unit normal nh (interior on its + side):
    // u(phi) = a cos phi + b sin phi, phi in [0, theta]; t1 = du/dphi at c.
    const D3 a = vertex(i), c = vertex(i + 1 == n ? 0 : i + 1);
    const D3 e = cross(a, c);
    const double sinTheta = norm(e);
    const double theta = std::atan2(sinTheta, dot(a, c));
    const D3 nh = scale(e, 1.0 / sinTheta);
    const D3 b = cross(nh, a), t1 = cross(nh, c);
    turning += std::atan2(dot(cross(tPrev, b), a), dot(tPrev, b));
    tPrev = t1;
    if (order < 2) continue;
    for (int j = 0; j < lobes; ++j) {
      const D3 w{lobes_[3 * j], lobes_[3 * j + 1], lobes_[3 * j + 2]};
      // x(phi) = w.u = A cos phi + B sin phi, y = dx/dphi; M_k = int_0^theta x^k dphi obeys
      // k M_k = (k-1)(A^2+B^2) M_{k-2} - [x^{k-1} y]_0^theta.
      const double A = dot(w, a), B = dot(w, b), x1 = dot(w, c), y1 = dot(w, t1);
      const double c2 = A * A + B * B;
      moments[0] = theta;
      if (order > 2) moments[1] = B - y1;
      double p0 = 1.0, p1 = 1.0;  // A^{k-1}, x1^{k-1}
      for (int k = 2; k < order - 1; ++k) {
        p0 *= A;
        p1 *= x1;
        moments[k] = ((k - 1) * c2 * moments[k - 2] - (p1 * y1 - p0 * B)) / k;
      }
      const double wn = dot(w, nh);
      double* sj = s + j * order;
      for (int l = 1; l < order; ++l) {
        const double* q = &dLegendre_[l * order];
        double d = 0.0;
        for (int k = 0; k < l; ++k) d += q[k] * moments[k];
        sj[l] += wn * d;
      }
    }
  }
  // Gauss-Bonnet: the solid angle is 2pi minus the total turning of the boundary.
  const double solidAngle = 2.0 * kPi - turning;
  out[0] += scaleBy * solidAngle * 0.28209479177387814;  // y_00 = 1 / (2 sqrt(pi))
  const double* a = lobeToSh_.data();
  for (int l = 1; l < order; ++l) {
    const int m2 = 2 * l + 1;
    a += (2 * l - 1) * (2 * l - 1);
    const double f = scaleBy / (l * (l + 1.0));
    double* o = out + l * l;
    for (int m = 0; m < m2; ++m) {
      double sum = 0.0;
      for (int j = 0; j < m2; ++j) sum += a[m * m2 + j] * s[j * order + l];
      o[m] += f * sum;
    }
  }
}

Status PolygonShProjector::projectSpherical(std::span<const Vec3> vertices, std::span<float> out) const {
  if (order_ == 0) return Status::error(StatusCode::kInvalidArgument, "the polygon projector was not made (PolygonShProjector::make)");
  const std::size_t count = vertices.size();
  if (count < 3) return invalid("a spherical polygon needs at least 3 vertices, got " + std::to_string(count));
  if (count > static_cast<std::size_t>(kMaxPolygonVertices)) {
    return invalid("a spherical polygon has at most " + std::to_string(kMaxPolygonVertices) + " vertices, got " + std::to_string(count));
  }
  const std::size_t need = static_cast<std::size_t>(order_ * order_);
  if (out.size() < need) {
    return Status::error(StatusCode::kSizeMismatch, "output holds " + std::to_string(out.size()) + " values, " + std::to_string(need) + " needed");
  }
  std::vector<double> unit(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 p = vertices[i];
    if (!isFinite(p)) return Status::error(StatusCode::kNotFinite, "polygon vertex " + std::to_string(i) + " is not finite");
    const D3 d{p.x, p.y, p.z};
    const double len = norm(d);
    if (!(len > 0.0)) return invalid("polygon vertex " + std::to_string(i) + " is the zero vector (no direction)");
    unit[3 * i] = d.x / len;
    unit[3 * i + 1] = d.y / len;
    unit[3 * i + 2] = d.z / len;
  }
  auto at = [&](std::size_t i) { return D3{unit[3 * i], unit[3 * i + 1], unit[3 * i + 2]}; };
  // About 2e-4 degrees: below this an edge's great circle is not determined in float input.
  const double kMinSin = 3e-6;
  for (std::size_t i = 0; i < count; ++i) {
    const D3 a = at(i), c = at((i + 1) % count), next = at((i + 2) % count);
    const D3 e = cross(a, c);
    const double s = norm(e);
    if (s < kMinSin) {
      const std::string which = "polygon vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % count);
      return invalid(which + (dot(a, c) > 0.0 ? " coincide (a zero-length edge)" : " are antipodal (the edge's great circle is undetermined)"));
    }
    const D3 nh = scale(e, 1.0 / s);
    // The next edge doubling back along this one: the turning angle at c is +-pi.
    const D3 e2 = cross(c, next);
    if (norm(e2) >= kMinSin && dot(scale(e2, 1.0 / norm(e2)), nh) < -1.0 + 1e-12 && dot(sub(next, c), sub(a, c)) > 0.0) {
      return invalid("polygon edge " + std::to_string((i + 1) % count) + " doubles back along edge " + std::to_string(i));
    }
  }
  std::vector<double> acc(need, 0.0);
  accumulateUnchecked(unit, 1.0, acc.data());
  for (std::size_t i = 0; i < need; ++i) out[i] = static_cast<float>(acc[i]);
  return Status::ok();
}

}  // namespace prt
