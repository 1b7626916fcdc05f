// Column-major 4x4 matrices for the client's camera (the layout glUniformMatrix4fv takes).
#pragma once

#include <array>

#include "prt/vec3.h"

namespace prt::web {

using Mat4 = std::array<float, 16>;  // m[col * 4 + row]

Mat4 multiply(const Mat4& a, const Mat4& b);
// Right-handed view matrix looking from `eye` at `target`, +y up.
Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up);
// OpenGL clip space (z in [-1, 1]); fovY in radians.
Mat4 perspective(float fovY, float aspect, float nearZ, float farZ);
// General inverse (cofactors); returns identity for a singular matrix.
Mat4 inverse(const Mat4& m);

}  // namespace prt::web
