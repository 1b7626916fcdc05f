// The light cube map: the emitters alone (not the scene: the baked transfer already holds
// its visibility) rendered from the lighting centre into six 90-degree faces of a 3x2 atlas
// (cube_faces.h), RGBA32F with depth, or RGBE8 where float render targets are missing.
#pragma once

#include <GLES3/gl3.h>

#include <span>

#include "emitter_renderer.h"
#include "prt/cubemap.h"
#include "prt/status.h"

namespace prt::web {

class LightCube {
 public:
  // (Re)allocates the atlas for `size` x `size` faces; `floatTexels` picks RGBA32F (needs
  // EXT_color_buffer_float) or RGBE8. Errors when the framebuffer is incomplete.
  Status resize(int size, bool floatTexels);
  // Renders `emitters` (bounds[k] holds emitter k) seen from `center`; faces an emitter
  // cannot touch are skipped. Leaves the default framebuffer bound.
  void render(EmitterRenderer& renderer, std::span<const Emitter> emitters, std::span<const BoundingSphere> bounds,
              Vec3 center, float nearZ);
  // Reads the atlas back (synchronous readPixels) into six faces.
  Status read(CubeMap* out);

  GLuint texture() const { return color_; }
  int size() const { return size_; }
  bool floatTexels() const { return float_; }

 private:
  void release();
  GLuint framebuffer_ = 0, color_ = 0, depth_ = 0;
  int size_ = 0;
  bool float_ = true;
};

}  // namespace prt::web
