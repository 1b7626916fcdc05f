#include "prt/cube_sh_weights.h"

#include <string>
#include <vector>

#include "prt/cubemap.h"
#include "prt/sh_basis.h"

namespace prt {

Status cubeShWeightRows(int order, int size, int face, int firstRow, int rowCount, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (size < 1 || size > 8192) {
    return Status::error(StatusCode::kInvalidArgument, "cube map face size " + std::to_string(size) + " is outside [1, 8192]");
  }
  if (face < 0 || face > 5) {
    return Status::error(StatusCode::kInvalidArgument, "cube face " + std::to_string(face) + " is outside [0, 5]");
  }
  if (firstRow < 0 || rowCount < 0 || firstRow > size || rowCount > size - firstRow) {
    return Status::error(StatusCode::kInvalidArgument, "rows [" + std::to_string(firstRow) + ", +" + std::to_string(rowCount) +
                                                           ") are outside a face of " + std::to_string(size) + " rows");
  }
  const std::size_t n = static_cast<std::size_t>(shCoeffCount(order));
  const std::size_t needed = static_cast<std::size_t>(rowCount) * static_cast<std::size_t>(size) * n;
  if (out.size() < needed) {
    return Status::error(StatusCode::kSizeMismatch, "weight table needs " + std::to_string(needed) + " floats, got " +
                                                        std::to_string(out.size()));
  }
  std::vector<float> basis(n);
  for (int j = firstRow; j < firstRow + rowCount; ++j) {
    // Same float arithmetic as projectCubeMap, so both paths weigh the same directions.
    const float t = 2.0f * (j + 0.5f) / size - 1.0f;
    for (int i = 0; i < size; ++i) {
      const float s = 2.0f * (i + 0.5f) / size - 1.0f;
      Vec3 d = cubeFaceDirection(face, s, t);
      d = d * (1.0f / length(d));
      evalShBasisUnchecked(order, d, basis.data());
      const double solidAngle = cubeTexelSolidAngle(size, i, j);
      float* dst = out.data() + (static_cast<std::size_t>(j - firstRow) * size + i) * n;
      for (std::size_t k = 0; k < n; ++k) dst[k] = static_cast<float>(basis[k] * solidAngle);
    }
  }
  return Status::ok();
}

}  // namespace prt
