#include "bi_scale_texture.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "prt/sh_rotation.h"
#include "transfer_texture.h"

namespace prt::web {
namespace {

const char kComponent[4] = {'x', 'y', 'z', 'w'};

// Writes "t3.y": component i % 4 of texel i / 4 of the vectors named `name`. (A stream: GCC 12
// warns falsely about string concatenations of this shape, -Wrestrict.)
void element(std::ostringstream& out, char name, int i) { out << name << i / 4 << '.' << kComponent[i % 4]; }

}  // namespace

int biScaleRotationEntries(int bands) {
  int entries = 0;
  for (int l = 1; l < bands; ++l) entries += (2 * l + 1) * (2 * l + 1);
  return entries;
}

Status packBiScaleRotations(std::span<const Vec3> normals, std::span<const Vec3> tangents, int bands, BiScaleRotations* out) {
  if (bands < 1 || bands > 8 || normals.size() != tangents.size()) {
    return Status::error(StatusCode::kInvalidArgument, "bi-scale rotations: bands 1..8 and one tangent per normal");
  }
  const int texels = std::max(1, biScaleRotationTexels(bands));
  BiScaleRotations r;
  r.bands = bands;
  r.texelsPerVertex = texels;
  r.values.assign(normals.size() * static_cast<std::size_t>(texels) * 4, 0.0f);
  for (std::size_t v = 0; v < normals.size(); ++v) {
    // The asset's frames are orthonormal to 1e-3; made exact here, as ShRotation wants.
    const float nl = length(normals[v]);
    const Vec3 n = normals[v] * (1.0f / nl);
    const Vec3 t0 = tangents[v] - n * dot(tangents[v], n);
    const float tl = std::sqrt(dot(t0, t0));
    if (!(nl > 0.0f) || !std::isfinite(nl) || !(tl > 1e-6f) || !std::isfinite(tl)) {
      return Status::error(StatusCode::kInvalidArgument, "bi-scale rotations: vertex " + std::to_string(v) +
                                                             "'s tangent is parallel to its normal or not finite");
    }
    const Vec3 t = t0 * (1.0f / tl);
    const Vec3 b = cross(n, t);
    Mat3 toLocal;  // rows: tangent, bitangent, normal (prt::biScaleExitRadiance's frame)
    const Vec3 rows[3] = {t, b, n};
    for (int i = 0; i < 3; ++i) toLocal.m[i][0] = rows[i].x, toLocal.m[i][1] = rows[i].y, toLocal.m[i][2] = rows[i].z;
    ShRotation rotation;
    if (Status s = ShRotation::make(bands, toLocal, &rotation); !s.isOk()) {
      return Status::error(StatusCode::kInvalidArgument, "bi-scale rotations: vertex " + std::to_string(v) + ": " + s.message());
    }
    float* dst = &r.values[v * static_cast<std::size_t>(texels) * 4];
    for (int l = 1; l < bands; ++l)
      for (int m = -l; m <= l; ++m)
        for (int k = -l; k <= l; ++k) *dst++ = rotation.at(l, m, k);
  }
  *out = std::move(r);
  return Status::ok();
}

std::string biScaleRotateMain(int bands, int rowTexels) {
  const int rotationTexels = biScaleRotationTexels(bands);
  std::ostringstream s;
  s << "void main() {\n  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n";
  s << "  int row = (uChannel * uVertices + gl_VertexID) * " << rowTexels << ";\n";
  for (int t = 0; t < texelsForOrder(bands); ++t) s << "  vec4 t" << t << " = transferTexel(row + " << t << ");\n";
  s << "  int base = gl_VertexID * " << std::max(1, rotationTexels) << ";\n";
  for (int t = 0; t < rotationTexels; ++t) s << "  vec4 r" << t << " = rotationTexel(base + " << t << ");\n";
  // Output coefficient i: band 0 as it is; band l's entry m the row of its block times band l's
  // coefficients; beyond bands^2, 0.
  std::vector<std::string> out(static_cast<std::size_t>(rowTexels) * 4, "0.0");
  {
    std::ostringstream e;
    element(e, 't', 0);
    out[0] = e.str();
  }
  int entry = 0;
  for (int l = 1; l < bands; ++l) {
    const int first = l * l, width = 2 * l + 1;
    for (int m = 0; m < width; ++m) {
      std::ostringstream sum;
      for (int k = 0; k < width; ++k) {
        if (k) sum << " + ";
        element(sum, 'r', entry++);
        sum << " * ";
        element(sum, 't', first + k);
      }
      out[static_cast<std::size_t>(first + m)] = sum.str();
    }
  }
  for (int t = 0; t < rowTexels; ++t) {
    s << "  vR" << t << " = vec4(";
    for (int k = 0; k < 4; ++k) s << (k ? ",\n    " : "") << out[static_cast<std::size_t>(4 * t + k)];
    s << ");\n";
  }
  s << "}\n";
  return s.str();
}

void biScaleRotateCpu(const BiScaleRotations& rotations, std::span<const float> transfer, int vertices, int rowTexels,
                      std::span<float> out) {
  const std::size_t stride = static_cast<std::size_t>(rowTexels) * 4;
  std::fill(out.begin(), out.end(), 0.0f);
  for (int c = 0; c < 3; ++c)
    for (int v = 0; v < vertices; ++v) {
      const float* t = &transfer[(static_cast<std::size_t>(c) * static_cast<std::size_t>(vertices) + static_cast<std::size_t>(v)) * stride];
      float* o = &out[(static_cast<std::size_t>(c) * static_cast<std::size_t>(vertices) + static_cast<std::size_t>(v)) * stride];
      const float* r = &rotations.values[static_cast<std::size_t>(v) * static_cast<std::size_t>(rotations.texelsPerVertex) * 4];
      o[0] = t[0];
      for (int l = 1; l < rotations.bands; ++l) {
        const int first = l * l, width = 2 * l + 1;
        for (int m = 0; m < width; ++m) {
          float sum = 0.0f;
          for (int k = 0; k < width; ++k) sum += *r++ * t[first + k];
          o[first + m] = sum;
        }
      }
    }
}

Status packBiScaleCorners(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const Vec3> tangents,
                          std::span<const float> patchUv, std::span<const float> atlasUv,
                          std::span<const std::uint16_t> trianglePlacements, std::span<const std::uint32_t> indices,
                          std::vector<std::uint32_t>* out) {
  const std::size_t n = positions.size();
  const auto pairs = [n](std::span<const float> uv) { return uv.empty() || uv.size() == 2 * n; };
  if (normals.size() != n || tangents.size() != n || !pairs(patchUv) || !pairs(atlasUv) || indices.size() % 3 != 0 ||
      !(trianglePlacements.empty() || trianglePlacements.size() == indices.size() / 3)) {
    return Status::error(StatusCode::kInvalidArgument, "bi-scale corners: per-vertex arrays disagree with the vertex count");
  }
  std::vector<std::uint32_t> words(indices.size() * kBiScaleCornerWords);
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const std::size_t triangle = i / 3 * 3;
    for (std::size_t k = 0; k < 3; ++k) {
      if (indices[triangle + k] >= n) {
        return Status::error(StatusCode::kInvalidArgument, "bi-scale corners: index " + std::to_string(triangle + k) + " out of range");
      }
    }
    const std::uint32_t v = indices[i];
    std::uint32_t* w = &words[i * kBiScaleCornerWords];
    const auto at = [v](std::span<const float> uv, int k) { return uv.empty() ? 0.0f : uv[2 * v + static_cast<std::size_t>(k)]; };
    const float f[13] = {positions[v].x, positions[v].y, positions[v].z, normals[v].x,    normals[v].y,    normals[v].z, tangents[v].x,
                         tangents[v].y,  tangents[v].z,  at(patchUv, 0), at(patchUv, 1), at(atlasUv, 0), at(atlasUv, 1)};
    std::memcpy(w, f, sizeof f);  // float bits in the buffer (std::bit_cast: not in Emscripten 3.1.6's libc++)
    for (int k = 0; k < 3; ++k) w[13 + k] = indices[triangle + static_cast<std::size_t>(k)];
    w[16] = trianglePlacements.empty() ? kNoPlacement : trianglePlacements[i / 3];
  }
  *out = std::move(words);
  return Status::ok();
}

std::vector<float> packPatchPlacements(std::span<const PatchPlacement> placements) {
  std::vector<float> out;
  out.reserve(placements.size() * 12);
  for (const PatchPlacement& p : placements) {
    for (const Vec3& v : {p.origin, p.axisU, p.axisV}) out.insert(out.end(), {v.x, v.y, v.z, 0.0f});
  }
  return out;
}

}  // namespace prt::web
