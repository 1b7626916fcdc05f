// Per-vertex SH transfer matrices (glossy PRT; docs/glossy.md, docs/asset-format.md):
// how an n^2 x n^2 matrix M (row i: transferred incident radiance coefficient, column j:
// source lighting coefficient) is packed into a flat array so that the first b^2 rows
// and columns, the order-b matrix, are a prefix of the array. That prefix rule is what
// lets a matrix pass stream band by band like a vector pass.
//
//   kSymmetric (M = M^T): the lower triangle row by row, (0,0), (1,0), (1,1), (2,0), ...
//       entry (i, j), j <= i, at i(i+1)/2 + j; an order-b prefix holds b^2(b^2+1)/2 entries.
//   kFull: coefficient k's "shell" after the order-k block: row k left of the diagonal,
//       then column k above it, then the diagonal: (k,0..k-1), (0..k-1,k), (k,k); entry
//       (i, j) at k^2 + {j if i == k > j; k + i if j == k > i; 2k if i == j == k}, k = max(i,j);
//       an order-b prefix holds b^4 entries.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "prt/status.h"

namespace prt {

enum class MatrixPacking : std::uint8_t {
  kSymmetric = 1,
  kFull = 2,
};

// "symmetric" | "full", or "unknown".
const char* matrixPackingName(MatrixPacking packing);

// Entries of an order-`order` matrix (order^2 rows) in `packing`.
constexpr std::size_t matrixEntryCount(int order, MatrixPacking packing) {
  const std::size_t n2 = static_cast<std::size_t>(order) * static_cast<std::size_t>(order);
  return packing == MatrixPacking::kSymmetric ? n2 * (n2 + 1) / 2 : n2 * n2;
}

// Index of entry (row, col) in `packing`; for kSymmetric the pair is swapped so row >= col.
constexpr std::size_t matrixEntryIndex(std::size_t row, std::size_t col, MatrixPacking packing) {
  if (packing == MatrixPacking::kSymmetric) {
    if (col > row) {
      const std::size_t t = row;
      row = col;
      col = t;
    }
    return row * (row + 1) / 2 + col;
  }
  const std::size_t k = row > col ? row : col;
  if (row == col) return k * k + 2 * k;
  return row == k ? k * k + col : k * k + k + row;
}

// out = M v for the leading `rows` rows and columns of a packed matrix of order `order`
// (rows <= order^2; v and out hold `rows` values; a leading block of an order-n matrix is
// the order-b matrix when rows = b^2). Float accumulation in column order. Trusted fast path.
void applyPackedMatrixUnchecked(const float* packed, MatrixPacking packing, std::size_t rows, const float* v,
                                float* out) noexcept;

// Checked form: packed.size() must be matrixEntryCount(order, packing), v and out order^2
// values. Safe on untrusted sizes.
Status applyPackedMatrix(std::span<const float> packed, int order, MatrixPacking packing, std::span<const float> v,
                         std::span<float> out);

// Copies the order-`bands` leading block of an order-`order` packed matrix: by the prefix
// rule, the first matrixEntryCount(bands, packing) entries.
inline std::span<const float> leadingMatrixBlock(std::span<const float> packed, int bands, MatrixPacking packing) {
  return packed.first(matrixEntryCount(bands, packing));
}

}  // namespace prt
