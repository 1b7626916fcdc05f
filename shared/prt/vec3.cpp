#include "prt/vec3.h"

namespace prt {

Mat3 rotationAxisAngle(Vec3 axis, float angle) {
  const float len = length(axis);
  if (len > 0.0f) axis = axis * (1.0f / len);
  const float c = std::cos(angle), s = std::sin(angle), t = 1.0f - c;
  const float x = axis.x, y = axis.y, z = axis.z;
  Mat3 r;
  r.m[0][0] = t * x * x + c;     r.m[0][1] = t * x * y - s * z; r.m[0][2] = t * x * z + s * y;
  r.m[1][0] = t * x * y + s * z; r.m[1][1] = t * y * y + c;     r.m[1][2] = t * y * z - s * x;
  r.m[2][0] = t * x * z - s * y; r.m[2][1] = t * y * z + s * x; r.m[2][2] = t * z * z + c;
  return r;
}

}  // namespace prt
