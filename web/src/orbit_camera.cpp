#include "orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace prt::web {

void OrbitCamera::frame(glm::vec3 center, float radius, float aspect) {
  setAspect(aspect);
  center_ = center;
  target_ = center;
  radius_ = std::max(1e-3f, radius);
  distance_ = fitDistance();
  yaw_ = 0.0f;
  pitch_ = kFramedPitch;
}

float OrbitCamera::fitDistance() const {
  // Half the narrower field of view: the vertical one unless the viewport is portrait.
  const float halfY = 0.5f * kFovY;
  const float half = aspect_ >= 1.0f ? halfY : std::atan(aspect_ * std::tan(halfY));
  return radius_ / std::sin(half) * kFrameMargin;
}

void OrbitCamera::setAspect(float aspect) {
  if (!(aspect > 0.0f && std::isfinite(aspect)) || aspect == aspect_) return;
  const float before = fitDistance();
  aspect_ = aspect;
  distance_ *= fitDistance() / before;
}

void OrbitCamera::orbit(float dx, float dy) {
  yaw_ += dx;
  pitch_ = std::clamp(pitch_ + dy, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dx, float dy) {
  const glm::vec3 forward{-std::sin(yaw_) * std::cos(pitch_), -std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
  glm::vec3 right = glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f));
  right = right * (1.0f / std::max(1e-6f, glm::length(right)));
  const glm::vec3 up = glm::cross(right, forward);
  target_ = target_ + (right * dx + up * dy) * (distance_ * 0.5f);
}

void OrbitCamera::zoom(float factor) { distance_ = std::clamp(distance_ * factor, radius_ * 0.05f, radius_ * 50.0f); }

bool OrbitCamera::setPose(const Pose& p) {
  const float values[] = {p.target.x, p.target.y, p.target.z, p.yaw, p.pitch, p.distance};
  if (!std::all_of(std::begin(values), std::end(values), [](float v) { return std::isfinite(v); })) return false;
  target_ = p.target;
  yaw_ = p.yaw;
  pitch_ = std::clamp(p.pitch, -kMaxPitch, kMaxPitch);
  distance_ = std::clamp(p.distance, radius_ * 0.05f, radius_ * 50.0f);
  return true;
}

glm::vec3 OrbitCamera::eyePosition() const {
  return target_ + glm::vec3{std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), std::cos(yaw_) * std::cos(pitch_)} * distance_;
}

glm::vec2 OrbitCamera::sceneDepthRange() const {
  return {std::max(distance_ - 2.0f * radius_, distance_ * 0.01f), distance_ + 2.0f * radius_};
}

void OrbitCamera::update(float nearZ, float farZ) {
  eye_ = eyePosition();
  view_ = glm::lookAt(eye_, target_, glm::vec3(0.0f, 1.0f, 0.0f));
  projection_ = glm::perspective(kFovY, aspect_, nearZ, farZ);
  viewProjection_ = projection_ * view_;
}

glm::vec3 OrbitCamera::project(glm::vec3 p) const {
  const glm::vec4 clip = viewProjection_ * glm::vec4(p, 1.0f);
  if (!(std::fabs(clip.w) > 1e-12f)) return {0.0f, 0.0f, 2.0f};
  return glm::vec3(clip) / clip.w;
}

glm::vec3 OrbitCamera::rayDirection(float ndcX, float ndcY) const {
  const glm::mat4 inv = inverseOrIdentity(viewProjection_);
  auto unproject = [&](float z) {
    const glm::vec4 p = inv * glm::vec4(ndcX, ndcY, z, 1.0f);
    return glm::vec3(p) / p.w;
  };
  const glm::vec3 d = unproject(1.0f) - unproject(-1.0f);
  const float len = glm::length(d);
  return len > 0.0f && std::isfinite(len) ? d * (1.0f / len) : glm::vec3(0.0f, 0.0f, -1.0f);
}

}  // namespace prt::web
