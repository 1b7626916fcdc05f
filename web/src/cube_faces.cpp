#include "cube_faces.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace prt::web {
namespace {

// The face's axes: cubeFaceDirection(face, s, t) = s * sAxis + t * tAxis + mAxis, each a
// signed unit axis, so (sc, tc, ma) = (sAxis . d, tAxis . d, mAxis . d).
struct FaceAxes {
  Vec3 s, t, m;
};
FaceAxes faceAxes(int face) {
  const Vec3 m = cubeFaceDirection(face, 0.0f, 0.0f);
  return {cubeFaceDirection(face, 1.0f, 0.0f) - m, cubeFaceDirection(face, 0.0f, 1.0f) - m, m};
}

}  // namespace

glm::mat4 cubeFaceViewProjection(int face, Vec3 c, float nearZ) {
  const FaceAxes a = faceAxes(face);
  // One column per argument line (m[col][row]); rows are sc, tc, ma - 2 near, ma.
  return {a.s.x, a.t.x, a.m.x, a.m.x,
          a.s.y, a.t.y, a.m.y, a.m.y,
          a.s.z, a.t.z, a.m.z, a.m.z,
          -dot(a.s, c), -dot(a.t, c), -dot(a.m, c) - 2.0f * nearZ, -dot(a.m, c)};
}

bool sphereTouchesCubeFace(int face, Vec3 c, const BoundingSphere& sphere) {
  const FaceAxes a = faceAxes(face);
  const Vec3 d = sphere.center - c;
  // The frustum is |sc| <= ma and |tc| <= ma: four planes through c with normals
  // (+-sAxis - mAxis) / sqrt(2) and (+-tAxis - mAxis) / sqrt(2) pointing out.
  const float ma = dot(a.m, d), sc = dot(a.s, d), tc = dot(a.t, d);
  const float reach = sphere.radius * 1.41421356f * 1.0001f + 1e-7f;
  return sc - ma <= reach && -sc - ma <= reach && tc - ma <= reach && -tc - ma <= reach;
}

namespace {
// Range of x / m over a disc of radius r centred at (x, m) with m > r: the tangents from
// the origin, at angles phi -+ beta from the m axis.
void ratioRange(float x, float m, float r, float* lo, float* hi) {
  const double phi = std::atan2(static_cast<double>(x), static_cast<double>(m));
  const double beta = std::asin(std::min(1.0, r / std::sqrt(static_cast<double>(x) * x + static_cast<double>(m) * m)));
  *lo = static_cast<float>(std::tan(phi - beta));
  *hi = static_cast<float>(std::tan(phi + beta));
}
// Texels whose centres 2 (i + 1/2) / size - 1 lie in [lo, hi], one texel of margin.
void texelRange(float lo, float hi, int size, int* first, int* last) {
  *first = std::max(0, static_cast<int>(std::floor((lo + 1.0f) * 0.5f * size - 0.5f)) - 1);
  *last = std::min(size - 1, static_cast<int>(std::ceil((hi + 1.0f) * 0.5f * size - 0.5f)) + 1);
}
}  // namespace

FaceRect sphereFaceRect(int face, Vec3 c, const BoundingSphere& sphere, int size) {
  if (!sphereTouchesCubeFace(face, c, sphere)) return {};
  const FaceAxes a = faceAxes(face);
  const Vec3 d = sphere.center - c;
  const float ma = dot(a.m, d), sc = dot(a.s, d), tc = dot(a.t, d);
  const float r = sphere.radius * 1.0001f + 1e-7f;
  if (!(ma > r * 1.001f)) return {0, 0, size - 1, size - 1};  // reaches the plane through c
  float s0, s1, t0, t1;
  ratioRange(sc, ma, r, &s0, &s1);
  ratioRange(tc, ma, r, &t0, &t1);
  FaceRect rect;
  texelRange(s0, s1, size, &rect.x0, &rect.x1);
  texelRange(t0, t1, size, &rect.y0, &rect.y1);
  return rect;
}

FaceRect unite(const FaceRect& a, const FaceRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

namespace {

// The six faces of a 3 x 2 atlas of 4-component texels (float RGBA or byte RGBE), each
// texel turned into RGB by `texelRgb`; `unit` names the element type in errors.
template <typename T, typename TexelRgb>
Status cubeMapFromAtlasTexels(int size, std::span<const T> atlas, const char* unit, TexelRgb texelRgb, CubeMap* out) {
  if (size < 1 || size > 4096) return Status::error(StatusCode::kInvalidArgument, "cube size " + std::to_string(size) + " is outside [1, 4096]");
  const std::size_t width = static_cast<std::size_t>(3 * size);
  if (atlas.size() != width * static_cast<std::size_t>(2 * size) * 4) {
    return Status::error(StatusCode::kSizeMismatch, "cube atlas has " + std::to_string(atlas.size()) + " " + unit + ", " +
                                                        std::to_string(width * 2 * size * 4) + " expected");
  }
  out->size = size;
  for (int f = 0; f < 6; ++f) {
    const AtlasOrigin o = cubeAtlasOrigin(f, size);
    std::vector<float>& face = out->faces[static_cast<std::size_t>(f)];
    face.resize(static_cast<std::size_t>(size) * size * 3);
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const Rgb c = texelRgb(&atlas[((static_cast<std::size_t>(o.y + j)) * width + static_cast<std::size_t>(o.x + i)) * 4]);
        float* dst = &face[(static_cast<std::size_t>(j) * size + i) * 3];
        dst[0] = c.r;
        dst[1] = c.g;
        dst[2] = c.b;
      }
  }
  return Status::ok();
}

}  // namespace

Status cubeMapFromAtlas(int size, std::span<const float> rgba, CubeMap* out) {
  return cubeMapFromAtlasTexels(size, rgba, "floats", [](const float* t) { return Rgb{t[0], t[1], t[2]}; }, out);
}

Rgb decodeRgbe(const std::uint8_t* texel) {
  const float scale = std::ldexp(1.0f / 255.0f, static_cast<int>(texel[3]) - 128);
  return {texel[0] * scale, texel[1] * scale, texel[2] * scale};
}

Status cubeMapFromRgbeAtlas(int size, std::span<const std::uint8_t> rgbe, CubeMap* out) {
  return cubeMapFromAtlasTexels(size, rgbe, "bytes", decodeRgbe, out);
}

}  // namespace prt::web
