#include "baker/texture/texel_seams.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <new>

#include "baker/texture/texel_filter.h"

namespace prt::bake {
namespace {

// A triangle edge keyed by its two 3D endpoints (bit patterns, the smaller first), so that
// triangles of different charts sharing the edge in space find each other.
struct EdgeEntry {
  std::array<std::uint32_t, 6> key;
  std::uint32_t triangle;
};

std::array<std::uint32_t, 6> edgeKey(Vec3 a, Vec3 b) {
  std::array<std::uint32_t, 3> ka = {std::bit_cast<std::uint32_t>(a.x), std::bit_cast<std::uint32_t>(a.y),
                                     std::bit_cast<std::uint32_t>(a.z)};
  std::array<std::uint32_t, 3> kb = {std::bit_cast<std::uint32_t>(b.x), std::bit_cast<std::uint32_t>(b.y),
                                     std::bit_cast<std::uint32_t>(b.z)};
  if (kb < ka) std::swap(ka, kb);
  return {ka[0], ka[1], ka[2], kb[0], kb[1], kb[2]};
}

bool samePosition(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// Barycentrics of q in the UV triangle (a, b, c), extrapolated outside it; false when degenerate.
bool uvBarycentrics(Uv a, Uv b, Uv c, double qu, double qv, double out[3]) {
  const double d = (static_cast<double>(b.u) - a.u) * (static_cast<double>(c.v) - a.v) -
                   (static_cast<double>(c.u) - a.u) * (static_cast<double>(b.v) - a.v);
  if (d == 0.0 || !std::isfinite(d)) return false;
  out[1] = ((qu - a.u) * (static_cast<double>(c.v) - a.v) - (static_cast<double>(c.u) - a.u) * (qv - a.v)) / d;
  out[2] = ((static_cast<double>(b.u) - a.u) * (qv - a.v) - (qu - a.u) * (static_cast<double>(b.v) - a.v)) / d;
  out[0] = 1.0 - out[1] - out[2];
  return true;
}

// Barycentrics of q (near the plane) in the 3D triangle (a, b, c), clamped onto it.
bool clampedBarycentrics(Vec3 a, Vec3 b, Vec3 c, Vec3 q, double out[3]) {
  const Vec3 e1 = b - a, e2 = c - a, r = q - a;
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), r1 = dot(r, e1), r2 = dot(r, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return false;
  out[1] = (d22 * r1 - d12 * r2) / det;
  out[2] = (d11 * r2 - d12 * r1) / det;
  out[0] = 1.0 - out[1] - out[2];
  double total = 0.0;
  for (int k = 0; k < 3; ++k) total += out[k] = std::max(0.0, out[k]);
  for (int k = 0; k < 3; ++k) out[k] /= total;
  return total > 0.0;
}

// Whether the vertex normals of triangles a and b (3 indices each) at their corner at `p`
// agree within kSeamCreaseTolerance: the interpolated shading normal is continuous there.
bool smoothAcross(std::span<const Vec3> positions, std::span<const Vec3> normals, const std::uint32_t* a,
                  const std::uint32_t* b, Vec3 p) {
  Vec3 na{0, 0, 0}, nb{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    if (samePosition(positions[a[k]], p)) na = normals[a[k]];
    if (samePosition(positions[b[k]], p)) nb = normals[b[k]];
  }
  return 1.0 - dot(na, nb) <= kSeamCreaseTolerance;
}

}  // namespace

Status findSeamTexels(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const std::uint32_t> indices,
                      std::span<const Uv> uvs, std::span<const TextureAtlas> atlases, const AtlasSamples& samples,
                      std::vector<SeamTexel>* out) {
  out->clear();
  try {
    const std::size_t triangles = indices.size() / 3;
    std::vector<EdgeEntry> edges;
    edges.reserve(3 * triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
      for (int k = 0; k < 3; ++k) {
        edges.push_back({edgeKey(positions[indices[3 * t + k]], positions[indices[3 * t + (k + 1) % 3]]),
                         static_cast<std::uint32_t>(t)});
      }
    }
    std::sort(edges.begin(), edges.end(), [](const EdgeEntry& a, const EdgeEntry& b) {
      return a.key != b.key ? a.key < b.key : a.triangle < b.triangle;
    });
    auto ownerOf = [&](std::uint64_t texel) -> const AtlasTexel* {
      const auto it = std::lower_bound(samples.texels.begin(), samples.texels.end(), texel,
                                       [](const AtlasTexel& s, std::uint64_t i) { return s.index < i; });
      return it != samples.texels.end() && it->index == texel ? &*it : nullptr;
    };
    for (std::size_t a = 0; a < atlases.size(); ++a) {
      const int w = static_cast<int>(atlases[a].width), h = static_cast<int>(atlases[a].height);
      const std::uint64_t first = samples.firstTexel[a];
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const std::uint64_t texel = first + static_cast<std::uint64_t>(y) * atlases[a].width + x;
          if (samples.sampled[texel]) continue;
          const AtlasTexel* owner = nullptr;
          const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
          for (int k = 0; k < 4 && !owner; ++k) {
            if (nx[k] < 0 || nx[k] >= w || ny[k] < 0 || ny[k] >= h) continue;
            owner = ownerOf(first + static_cast<std::uint64_t>(ny[k]) * atlases[a].width + nx[k]);
          }
          if (!owner) continue;
          const std::uint32_t* tc = &indices[3 * std::size_t{owner->triangle}];
          double b[3];
          if (!uvBarycentrics(uvs[tc[0]], uvs[tc[1]], uvs[tc[2]], (x + 0.5) / w, (y + 0.5) / h, b)) continue;
          int outsideCorner = -1, negatives = 0;
          for (int k = 0; k < 3; ++k) {
            if (b[k] < 0.0) {
              ++negatives;
              outsideCorner = k;
            }
          }
          if (negatives != 1) continue;  // inside (a sliver) or past a corner: dilation fills it
          const Vec3 p0 = positions[tc[(outsideCorner + 1) % 3]], p1 = positions[tc[(outsideCorner + 2) % 3]];
          const Uv uv0 = uvs[tc[(outsideCorner + 1) % 3]], uv1 = uvs[tc[(outsideCorner + 2) % 3]];
          const auto key = edgeKey(p0, p1);
          auto it = std::lower_bound(edges.begin(), edges.end(), key,
                                     [](const EdgeEntry& e, const std::array<std::uint32_t, 6>& k) { return e.key < k; });
          const std::uint32_t* nc = nullptr;
          std::uint32_t neighbour = 0;
          for (; it != edges.end() && it->key == key; ++it) {
            if (it->triangle == owner->triangle) continue;
            const std::uint32_t* c = &indices[3 * std::size_t{it->triangle}];
            // The same chart continuing (equal UVs at the shared corners) is not a seam.
            bool sameUv = true;
            for (int k = 0; k < 3; ++k) {
              const Uv u = uvs[c[k]];
              if (samePosition(positions[c[k]], p0)) sameUv = sameUv && u.u == uv0.u && u.v == uv0.v;
              if (samePosition(positions[c[k]], p1)) sameUv = sameUv && u.u == uv1.u && u.v == uv1.v;
            }
            if (sameUv) continue;
            if (!smoothAcross(positions, normals, tc, c, p0) || !smoothAcross(positions, normals, tc, c, p1)) continue;
            nc = c;
            neighbour = it->triangle;
            break;
          }
          if (!nc) continue;
          // The centre in 3D, extrapolated in the owner's plane, then its distance past the
          // edge turned about the edge into the neighbour's plane.
          Vec3 p{0, 0, 0};
          for (int k = 0; k < 3; ++k) p = p + positions[tc[k]] * static_cast<float>(b[k]);
          const Vec3 edge = p1 - p0;
          const double len2 = dot(edge, edge);
          if (!(len2 > 0.0)) continue;
          const float s = static_cast<float>(std::clamp(dot(p - p0, edge) / len2, 0.0, 1.0));
          const Vec3 onEdge = p0 + edge * s;
          const float past = length(p - onEdge);
          Vec3 third{0, 0, 0};
          for (int k = 0; k < 3; ++k) {
            if (!samePosition(positions[nc[k]], p0) && !samePosition(positions[nc[k]], p1)) third = positions[nc[k]];
          }
          Vec3 into = (third - p0) - edge * static_cast<float>(dot(third - p0, edge) / len2);
          const float intoLength = length(into);
          if (!(intoLength > 0.0f)) continue;
          const Vec3 q = onEdge + into * (past / intoLength);
          double bn[3];
          if (!clampedBarycentrics(positions[nc[0]], positions[nc[1]], positions[nc[2]], q, bn)) continue;
          Uv uv{0, 0};
          for (int k = 0; k < 3; ++k) {
            uv.u += static_cast<float>(bn[k]) * uvs[nc[k]].u;
            uv.v += static_cast<float>(bn[k]) * uvs[nc[k]].v;
          }
          out->push_back({texel, samples.triangleAtlas[neighbour], uv});
        }
      }
    }
  } catch (const std::bad_alloc&) {
    out->clear();
    return Status::error(StatusCode::kResourceExhausted, "out of memory finding the atlas seams");
  }
  return Status::ok();
}

void stitchSeams(std::span<const SeamTexel> seams, std::span<const TextureAtlas> atlases,
                 std::span<const std::uint64_t> firstTexel, std::span<const std::uint8_t> filled,
                 std::span<float> texture, std::size_t stride) {
  std::vector<float> values(seams.size() * stride, 0.0f);
  for (std::size_t s = 0; s < seams.size(); ++s) {
    TexelTap taps[4];
    const int count = bilinearTaps(seams[s].uv, atlases[seams[s].atlas], firstTexel[seams[s].atlas], filled, taps);
    float* dst = &values[s * stride];
    if (count == 0) std::copy_n(&texture[seams[s].texel * stride], stride, dst);  // nothing across: keep it
    for (int t = 0; t < count; ++t) {
      const float* src = &texture[taps[t].texel * stride];
      for (std::size_t i = 0; i < stride; ++i) dst[i] += taps[t].weight * src[i];
    }
  }
  for (std::size_t s = 0; s < seams.size(); ++s) {
    std::copy_n(&values[s * stride], stride, &texture[seams[s].texel * stride]);
  }
}

}  // namespace prt::bake
