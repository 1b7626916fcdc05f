// Exact quadratures used as brute-force references in tests.
#pragma once

#include <vector>

#include "prt/vec3.h"

namespace prt::ref {

// Gauss-Legendre nodes and weights on [-1, 1] (Newton iteration on P_n), double precision.
void gaussLegendre(int n, std::vector<double>* nodes, std::vector<double>* weights);

struct WeightedDirection {
  Vec3 dir;
  double weight;  // steradians
};

// Product rule on the sphere: n Gauss-Legendre nodes in z = cos(theta) times 2n equispaced
// azimuths. Integrates polynomials of degree <= 2n-1 in (x, y, z) exactly; weights sum to 4pi.
std::vector<WeightedDirection> sphereQuadrature(int n);

}  // namespace prt::ref
