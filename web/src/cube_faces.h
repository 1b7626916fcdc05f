// The light cube map's geometry, GL-free (tested under Node): per-face projection matrices
// in the GL cube-map convention of shared/prt/cubemap.h, the 3x2 atlas the six faces are
// rendered into, which faces an emitter can touch, and turning the atlas's pixels (read back
// with readPixels) into a prt::CubeMap for the shared projection.
#pragma once

#include <cstdint>
#include <span>

#include "emitters.h"
#include "glm_types.h"
#include "prt/cubemap.h"
#include "prt/status.h"

namespace prt::web {

// Face f of a size x size cube occupies atlas columns [(f % 3) size, +size) and rows
// [(f / 3) size, +size) of a 3 size x 2 size texture; atlas row 0 is GL's bottom row (the
// first row readPixels returns), which is the face's row 0 in cubemap.h.
struct AtlasOrigin {
  int x = 0, y = 0;
};
inline AtlasOrigin cubeAtlasOrigin(int face, int size) { return {(face % 3) * size, (face / 3) * size}; }

// Clip-space matrix of face `face` seen from `center`: for a world point p with
// d = p - center, clip = (sc, tc, ma - 2 nearZ, ma) where cubeFaceDirection(face, sc/ma,
// tc/ma) points along d. So NDC (x, y) is the face coordinate (s, t), window pixel (i, j)
// is texel (i, j), and the far plane is at infinity. A 90-degree frustum, a proper
// rotation (front faces stay front faces).
glm::mat4 cubeFaceViewProjection(int face, Vec3 center, float nearZ);

// False only when `sphere` lies entirely outside the face's frustum (conservative).
bool sphereTouchesCubeFace(int face, Vec3 center, const BoundingSphere& sphere);

// Texels of a size x size face an emitter inside `sphere` can cover: an inclusive rectangle
// (face texel coordinates, cubemap.h), conservative by a texel. `empty` when the sphere
// cannot reach the face; the whole face when it reaches c's side of the face plane.
struct FaceRect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
};
FaceRect sphereFaceRect(int face, Vec3 center, const BoundingSphere& sphere, int size);
// The smallest rectangle holding both.
FaceRect unite(const FaceRect& a, const FaceRect& b);

// Decodes the atlas's RGBA pixels into six faces. `rgba` holds 3 size x 2 size texels,
// 4 floats each (readPixels RGBA/FLOAT); alpha is ignored.
Status cubeMapFromAtlas(int size, std::span<const float> rgba, CubeMap* out);

// The same from an RGBE8 atlas (readPixels RGBA/UNSIGNED_BYTE of what emitter.frag writes
// without float render targets): value = byte / 255 * 2^(alpha - 128) per channel.
Status cubeMapFromRgbeAtlas(int size, std::span<const std::uint8_t> rgbe, CubeMap* out);

// One RGBE8 texel decoded (see cubeMapFromRgbeAtlas).
Rgb decodeRgbe(const std::uint8_t* texel);

}  // namespace prt::web
