// GLM for the client's matrices and camera vectors (Debian's header-only libglm-dev; the
// build puts an include directory holding only GLM on the path: web/CMakeLists.txt). GLM's
// defaults are the ones the client needs: glm::mat4 is column-major, m[col][row], the layout
// glUniformMatrix4fv takes (glm::value_ptr), and perspective / lookAt are right-handed with
// OpenGL's clip depth in [-1, 1]. shared/ has no GLM: toGlm / toVec3 convert prt::Vec3.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>               // dot, cross, normalize, length
#include <glm/gtc/matrix_transform.hpp>  // perspective, lookAt
#include <glm/gtc/type_ptr.hpp>          // value_ptr
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>                  // inverse
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "prt/vec3.h"

#if defined(GLM_FORCE_DEPTH_ZERO_TO_ONE) || defined(GLM_FORCE_LEFT_HANDED)
#error "the client's matrices assume GLM's defaults: right-handed, clip depth in [-1, 1]"
#endif

namespace prt::web {

inline glm::vec3 toGlm(Vec3 v) { return {v.x, v.y, v.z}; }
inline Vec3 toVec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// glm::inverse, or the identity for a singular (or non-finite) matrix, where glm::inverse
// divides by a zero determinant: the camera's matrix before the first frame is all zeros.
inline glm::mat4 inverseOrIdentity(const glm::mat4& m) {
  const float det = glm::determinant(m);
  if (det == 0.0f || !std::isfinite(det)) return glm::mat4(1.0f);
  return glm::inverse(m);
}

}  // namespace prt::web
