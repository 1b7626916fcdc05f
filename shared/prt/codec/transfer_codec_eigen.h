// Eigen-decomposition of small symmetric matrices (CPCA's covariance matrices, at most
// 3 * 31 = 93 rows) by the cyclic Jacobi method, in double precision.
#pragma once

#include <vector>

namespace prt::transfer_codec {

struct SymmetricEigen {
  std::vector<double> values;   // n eigenvalues, descending
  std::vector<double> vectors;  // n unit eigenvectors, row j belongs to values[j] ([j][i])
};

// Decomposes the symmetric n x n matrix `a` (row-major; only its symmetric part is used).
// Each eigenvector's sign is fixed so that its largest-magnitude component (the first of
// equals) is positive, which makes the result a function of the matrix alone.
SymmetricEigen symmetricEigen(int n, std::vector<double> a);

}  // namespace prt::transfer_codec
