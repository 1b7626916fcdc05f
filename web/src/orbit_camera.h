// The client's orbit camera (GL-free): a target point seen from yaw / pitch / distance about
// it with a fixed vertical field of view, orbit / pan / zoom from the page's input, framing
// of a scene's bounding sphere, and each frame's view and projection matrices (GLM, OpenGL
// clip space) with what tests and picking need from them: where a world point lands and
// the ray through a screen point.
#pragma once

#include "glm_types.h"

namespace prt::web {

class OrbitCamera {
 public:
  inline static constexpr float kFovY = 0.8f;          // vertical field of view, radians
  inline static constexpr float kFrameMargin = 1.05f;  // framed distance over the tightest fit
  inline static constexpr float kFramedPitch = 0.35f;  // radians above the horizon after frame()
  inline static constexpr float kMaxPitch = 1.5f;      // |pitch| limit, short of the poles

  // Aims at the sphere (`center`, `radius`, at least 1e-3) from yaw 0 (looking along -z),
  // pitch kFramedPitch, at fitDistance() for a viewport of `aspect` (width / height): the
  // sphere fits in both width and height, kFrameMargin to spare in the narrower one.
  void frame(glm::vec3 center, float radius, float aspect);
  // The viewport's aspect for the next frame. The distance is scaled by the change of
  // fitDistance(), so a framed scene stays fitted (and a zoomed one keeps its zoom relative
  // to the fit) when the canvas turns from landscape to portrait; between two landscape
  // aspects nothing changes, the height being the binding side for both.
  void setAspect(float aspect);
  float aspect() const { return aspect_; }
  // radius / sin(min(fovX, fovY) / 2) * kFrameMargin at aspect(): the sphere's tangent cone
  // from there is as wide as the narrower field of view (fovX = 2 atan(aspect tan(fovY / 2))).
  float fitDistance() const;

  void orbit(float dxRadians, float dyRadians);  // yaw and pitch (clamped to kMaxPitch)
  void pan(float dx, float dy);                  // moves the target; units of half the distance
  void zoom(float factor);                       // distance * factor (> 1 moves away), 0.05..50 radii

  // The camera's free parameters: what a permalink stores to put the camera back.
  struct Pose {
    glm::vec3 target;
    float yaw, pitch, distance;  // radians, radians, world units
  };
  Pose pose() const { return {target_, yaw_, pitch_, distance_}; }
  // Puts the camera at `p`, pitch clamped to kMaxPitch and distance to zoom()'s range of the
  // framed sphere; returns false, changing nothing, when a value is not finite.
  bool setPose(const Pose& p);

  // The sphere given to the last frame() (radius 1 about the origin before any).
  glm::vec3 sceneCenter() const { return center_; }
  float sceneRadius() const { return radius_; }
  glm::vec3 target() const { return target_; }
  float distance() const { return distance_; }
  glm::vec3 eyePosition() const;  // where the camera is now (before or after update())
  // Depth range holding the framed sphere from the current distance: {near, far}.
  glm::vec2 sceneDepthRange() const;

  // Builds the frame's matrices for depth range [nearZ, farZ] at aspect(); everything below
  // describes the last update (all-zero matrices before the first).
  void update(float nearZ, float farZ);
  const glm::mat4& view() const { return view_; }
  const glm::mat4& projection() const { return projection_; }
  const glm::mat4& viewProjection() const { return viewProjection_; }
  glm::vec3 eye() const { return eye_; }
  // Where world point p landed: (ndcX, ndcY, depth), NDC in [-1, 1] with +y up; (0, 0, 2)
  // when it has no projection (w = 0).
  glm::vec3 project(glm::vec3 p) const;
  // The unit direction of the ray from eye() through NDC point (x, y); (0, 0, -1) when the
  // matrices are degenerate.
  glm::vec3 rayDirection(float ndcX, float ndcY) const;

 private:
  glm::vec3 center_{0.0f}, target_{0.0f};
  float radius_ = 1.0f, distance_ = 3.0f, yaw_ = 0.0f, pitch_ = kFramedPitch, aspect_ = 1.0f;
  glm::mat4 view_{0.0f}, projection_{0.0f}, viewProjection_{0.0f};
  glm::vec3 eye_{0.0f};
};

}  // namespace prt::web
