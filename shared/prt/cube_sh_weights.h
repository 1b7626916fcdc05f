// Exact SH projection weights of cube-map texels: w_k(texel) = y_k(dir) * solid angle, so
// that the projection of a cube map is c_k = sum over texels of w_k(texel) * value(texel),
// exactly what projectCubeMap accumulates. A client that projects cube maps on the GPU
// computes this table once per (size, order) and reduces value * weight there.
#pragma once

#include <span>

#include "prt/status.h"

namespace prt {

// Weights of rows [firstRow, firstRow + rowCount) of `face` (CubeFace, GL convention of
// cubemap.h) of a size x size cube map at SH order `order` (n = order^2 coefficients):
// out[((j - firstRow) * size + i) * n + k] = y_k(unit dir of texel centre (i, j)) *
// cubeTexelSolidAngle(size, i, j), the direction computed as projectCubeMap computes it.
// Errors (kInvalidArgument, kSizeMismatch): order outside [1, kMaxShOrder], size outside
// [1, 8192], face outside [0, 5], a row range outside [0, size), out too small.
Status cubeShWeightRows(int order, int size, int face, int firstRow, int rowCount, std::span<float> out);

}  // namespace prt
