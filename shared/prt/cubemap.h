// Cube maps in the OpenGL convention (faces +X, -X, +Y, -Y, +Z, -Z; the GL spec's
// per-face (sc, tc, ma) table), with exact per-texel solid angles.
//
// A face is size x size RGB texels stored row-major; texel (i, j) (column i, row j; row 0
// first in memory, as glTexImage2D and readPixels see it) has face coordinates
// s = 2 (i + 1/2) / size - 1, t = 2 (j + 1/2) / size - 1.
#pragma once

#include <array>
#include <vector>

#include "prt/image.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

enum CubeFace : int { kCubePosX = 0, kCubeNegX, kCubePosY, kCubeNegY, kCubePosZ, kCubeNegZ };

struct CubeMap {
  int size = 0;
  std::array<std::vector<float>, 6> faces;  // each size*size*3 floats
};

// Direction (not normalised) through face coordinates (s, t) in [-1, 1] of `face`.
Vec3 cubeFaceDirection(int face, float s, float t);

// Exact solid angle (steradians) of texel (i, j) of a size x size face, identical on all
// six faces: with A(x, y) = atan2(x y, sqrt(x^2 + y^2 + 1)), the texel spanning
// [x0, x1] x [y0, y1] subtends A(x0,y0) - A(x0,y1) - A(x1,y0) + A(x1,y1).
// All 6 size^2 texels sum to 4pi. Unchecked indices.
double cubeTexelSolidAngle(int size, int i, int j);

// Ok when 1 <= size <= 8192, every face holds size*size*3 finite floats.
Status checkCubeMap(const CubeMap& cube);

// Cuts a cross layout into faces. Horizontal cross (width:height = 4:3):
//        [+Y]
//   [-X] [+Z] [+X] [-Z]
//        [-Y]
// vertical cross (3:4): the same top three rows and -Z below -Y, turned 180 degrees.
// Each face region is in GL face orientation (its top row is the face's row 0), which
// makes the cross seamless in the GL convention. Other aspect ratios are an error.
Status cubeMapFromCross(const RgbImage& cross, CubeMap* out);

}  // namespace prt
