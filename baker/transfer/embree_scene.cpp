#include "baker/transfer/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace prt::bake {

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

Status EmbreeScene::build(const Scene& scene, EmbreeScene* out, bool robust) {
  if (scene.indices.empty() || scene.indices.size() % 3 != 0) {
    return Status::error(StatusCode::kInvalidArgument, "scene has no triangles");
  }
  out->device_ = rtcNewDevice(nullptr);
  if (!out->device_) {
    return Status::error(StatusCode::kInternal,
                         "Embree device creation failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  }
  out->scene_ = rtcNewScene(out->device_);
  rtcSetSceneBuildQuality(out->scene_, RTC_BUILD_QUALITY_HIGH);
  if (robust) rtcSetSceneFlags(out->scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(out->device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  const std::size_t vertexCount = scene.positions.size();
  const std::size_t triangleCount = scene.indices.size() / 3;
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangleCount));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geom);
    return Status::error(StatusCode::kResourceExhausted, "Embree could not allocate geometry buffers");
  }
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const Vec3 p = scene.positions[v];
    vertices[3 * v] = p.x;
    vertices[3 * v + 1] = p.y;
    vertices[3 * v + 2] = p.z;
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  std::memcpy(indices, scene.indices.data(), scene.indices.size() * sizeof(unsigned));
  rtcCommitGeometry(geom);
  rtcAttachGeometry(out->scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(out->scene_);
  const RTCError err = rtcGetDeviceError(out->device_);
  if (err != RTC_ERROR_NONE) {
    return Status::error(err == RTC_ERROR_OUT_OF_MEMORY ? StatusCode::kResourceExhausted : StatusCode::kInternal,
                         "Embree scene build failed (error " + std::to_string(err) + ")");
  }
  out->diagonal_ = length(hi - lo);
  return Status::ok();
}

}  // namespace prt::bake
