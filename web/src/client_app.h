// The client's state and per-frame work, driven from JavaScript through embind
// (client_bindings.cpp): the decoded scene on the GPU, the lighting (an environment's SH
// or a constant "white furnace"), its live rotation by the shared SH rotation, and an
// orbit camera.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gl_renderer.h"
#include "prt/asset.h"
#include "prt/vec3.h"

namespace prt::web {

class ClientApp {
 public:
  // Creates a WebGL2 context on the canvas matching `selector` ("#canvas"). On failure
  // error() says why (WebGL2 missing) and every other call is a no-op.
  explicit ClientApp(const std::string& selector);
  const std::string& error() const { return error_; }

  // Memory JS streams the asset into (no extra copy): call with the byte count, fill it,
  // then loadAsset(). Returns nullptr when `bytes` cannot be allocated.
  std::uint8_t* reserveAsset(std::size_t bytes);
  // Decodes the reserved bytes with the shared reader and uploads them. Returns "" or the
  // error (named by the reader: truncated, checksum mismatch, ...). Frames the camera.
  std::string loadAsset();

  // Environment lighting: radiance SH, flat [r,g,b] per coefficient, order 1..16 (the first
  // 8 bands are kept). Returns "" or the error.
  std::string setEnvironment(const std::vector<float>& flatRgb, int order);
  // Constant radiance `intensity` from every direction (the white furnace).
  void setWhiteFurnace(float intensity);
  void setEnvRotation(float yawRadians, float pitchRadians);
  void setLightColor(float r, float g, float b);  // multiplies the lighting
  void setMode(int mode);                          // ShadingMode
  void setDisplayOrder(int order);                 // clamped to [1, baked order]
  void setExposure(float ev);                      // exposure value, 2^ev
  void setBackground(bool on) { background_ = on; }

  void orbit(float dxRadians, float dyRadians);
  void pan(float dx, float dy);  // in units of the framed radius
  void zoom(float factor);       // > 1 moves away
  void frameScene();

  // Updates the lighting (rotation, colour, truncation) and draws one frame.
  void render(int width, int height);

  // Where world point (x, y, z) landed in the last frame: [ndcX, ndcY, depth], NDC in
  // [-1, 1] with +y up. Lets tests find scene features on screen without guessing.
  std::vector<float> project(float x, float y, float z) const;

  // The lighting of the last frame at the display order, flat [r,g,b] per coefficient.
  std::vector<float> lightSH() const;

  std::size_t vertexCount() const { return asset_.positions.size(); }
  std::size_t triangleCount() const { return asset_.indices.size() / 3; }
  int bakedOrder() const { return asset_.shOrder; }
  int displayOrder() const { return displayOrder_; }
  int mode() const { return static_cast<int>(mode_); }
  bool hasPass(int mode) const { return ok() && renderer_.hasPass(static_cast<ShadingMode>(mode)); }

 private:
  bool ok() const { return error_.empty(); }
  void updateLighting();

  std::string error_;
  int context_ = 0;
  GlRenderer renderer_;
  std::vector<std::uint8_t> pending_;
  BakedAsset asset_;
  Vec3 boundsMin_{}, boundsMax_{};

  std::vector<Rgb> environment_;  // unrotated
  int environmentOrder_ = 1;
  float yaw_ = 0, pitch_ = 0;
  Rgb color_{1, 1, 1};
  std::vector<Rgb> lighting_;  // rotated and coloured, at environmentOrder_
  float packed_[3 * 64] = {};

  ShadingMode mode_ = ShadingMode::kInterreflected;
  int displayOrder_ = 8;
  float exposure_ = 1.0f;
  bool background_ = true;

  Vec3 target_{};
  float radius_ = 1.0f, distance_ = 3.0f, camYaw_ = 0.0f, camPitch_ = 0.35f;
  Mat4 viewProjection_{};
};

}  // namespace prt::web
