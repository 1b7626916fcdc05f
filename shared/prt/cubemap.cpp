#include "prt/cubemap.h"

#include <cmath>
#include <string>

namespace prt {

Vec3 cubeFaceDirection(int face, float s, float t) {
  switch (face) {
    case kCubePosX: return {1.0f, -t, -s};
    case kCubeNegX: return {-1.0f, -t, s};
    case kCubePosY: return {s, 1.0f, t};
    case kCubeNegY: return {s, -1.0f, -t};
    case kCubePosZ: return {s, -t, 1.0f};
    default: return {-s, -t, -1.0f};  // kCubeNegZ
  }
}

namespace {
double areaElement(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }
}  // namespace

double cubeTexelSolidAngle(int size, int i, int j) {
  const double inv = 2.0 / size;
  const double x0 = i * inv - 1.0, x1 = (i + 1) * inv - 1.0;
  const double y0 = j * inv - 1.0, y1 = (j + 1) * inv - 1.0;
  return areaElement(x0, y0) - areaElement(x0, y1) - areaElement(x1, y0) + areaElement(x1, y1);
}

Status checkCubeMap(const CubeMap& cube) {
  if (cube.size < 1 || cube.size > 8192) {
    return Status::error(StatusCode::kInvalidArgument,
                         "cube map face size " + std::to_string(cube.size) + " is outside [1, 8192]");
  }
  const std::size_t expected = static_cast<std::size_t>(cube.size) * static_cast<std::size_t>(cube.size) * 3;
  for (int f = 0; f < 6; ++f) {
    if (cube.faces[f].size() != expected) {
      return Status::error(StatusCode::kSizeMismatch, "cube map face " + std::to_string(f) + " has " +
                                                          std::to_string(cube.faces[f].size()) + " floats, " +
                                                          std::to_string(expected) + " expected");
    }
    for (float v : cube.faces[f]) {
      if (!std::isfinite(v)) {
        return Status::error(StatusCode::kNotFinite, "cube map face " + std::to_string(f) + " has a non-finite value");
      }
    }
  }
  return Status::ok();
}

Status cubeMapFromCross(const RgbImage& cross, CubeMap* out) {
  if (Status s = checkImage(cross, "cross image"); !s.isOk()) return s;
  const bool horizontal = cross.width * 3 == cross.height * 4;
  const bool vertical = cross.width * 4 == cross.height * 3;
  if (!horizontal && !vertical) {
    return Status::error(StatusCode::kInvalidArgument,
                         "cross image is " + std::to_string(cross.width) + "x" + std::to_string(cross.height) +
                             "; a horizontal cross is 4:3 and a vertical cross 3:4");
  }
  const int f = horizontal ? cross.width / 4 : cross.width / 3;
  struct Place { int col, row; bool rotated; };
  // Indexed by CubeFace: +X, -X, +Y, -Y, +Z, -Z.
  const Place place[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false}, {1, 2, false}, {1, 1, false},
                          horizontal ? Place{3, 1, false} : Place{1, 3, true}};
  out->size = f;
  for (int face = 0; face < 6; ++face) {
    std::vector<float>& dst = out->faces[face];
    dst.assign(static_cast<std::size_t>(f) * f * 3, 0.0f);
    for (int j = 0; j < f; ++j) {
      for (int i = 0; i < f; ++i) {
        const int si = place[face].rotated ? f - 1 - i : i;
        const int sj = place[face].rotated ? f - 1 - j : j;
        const Rgb c = cross.at(place[face].col * f + si, place[face].row * f + sj);
        float* p = &dst[(static_cast<std::size_t>(j) * f + i) * 3];
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
      }
    }
  }
  return Status::ok();
}

}  // namespace prt
