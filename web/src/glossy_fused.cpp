#include "glossy_fused.h"

#include <algorithm>
#include <numeric>
#include <sstream>

#include "transfer_texture.h"

namespace prt::web {

int glossyGroupSize(std::size_t vertices, std::size_t clusters, int vectors, int rowTexels) {
  const std::size_t dotsPerMember = static_cast<std::size_t>(1 + std::max(vectors, 0)) * 3 * static_cast<std::size_t>(std::max(rowTexels, 1));
  int size = 1;
  while (size < kMaxGlossyGroup && static_cast<std::size_t>(2 * size) * clusters <= vertices &&
         static_cast<std::size_t>(2 * size) * dotsPerMember <= static_cast<std::size_t>(kMaxGlossyFusedDots)) {
    size *= 2;
  }
  return size;
}

Status groupGlossyVertices(std::span<const std::uint16_t> clusterOf, int clusters, int size, GlossyGroups* out) {
  if (size < 1 || size > kMaxGlossyGroup || clusters < 1) {
    return Status::error(StatusCode::kInvalidArgument, "glossy groups: size " + std::to_string(size) + " outside 1 .. " +
                                                           std::to_string(kMaxGlossyGroup) + ", or no clusters");
  }
  const std::size_t V = clusterOf.size(), K = static_cast<std::size_t>(clusters);
  // Counting sort by cluster: stable, so a cluster's vertices keep their order.
  std::vector<std::size_t> start(K + 1, 0);
  for (std::uint16_t k : clusterOf) {
    if (k >= K) return Status::error(StatusCode::kInvalidArgument, "glossy groups: cluster id " + std::to_string(k) + " out of range");
    ++start[k + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> order(V);
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (std::size_t v = 0; v < V; ++v) order[next[clusterOf[v]]++] = static_cast<std::uint32_t>(v);

  GlossyGroups g;
  g.size = size;
  g.slot.assign(V, 0);
  const std::size_t S = static_cast<std::size_t>(size);
  for (std::size_t k = 0; k < K; ++k) {
    for (std::size_t first = start[k]; first < start[k + 1]; first += S) {
      const std::size_t group = g.cluster.size();
      g.cluster.push_back(static_cast<std::uint32_t>(k));
      g.members.resize(g.members.size() + kMaxGlossyGroup, -1);
      for (std::size_t i = 0; i < S && first + i < start[k + 1]; ++i) {
        const std::uint32_t v = order[first + i];
        g.members[group * kMaxGlossyGroup + i] = static_cast<std::int32_t>(v);
        g.slot[v] = static_cast<std::uint32_t>(group * S + i);
      }
    }
  }
  *out = std::move(g);
  return Status::ok();
}

std::vector<float> packGlossyVertexData(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                        std::span<const float> specular) {
  const std::size_t V = positions.size();
  if (normals.size() != V || specular.size() != V * kGlossySpecularFloats) return {};
  std::vector<float> out(12 * V, 0.0f);
  for (std::size_t v = 0; v < V; ++v) {
    const float* s = &specular[kGlossySpecularFloats * v];
    float* d = &out[12 * v];
    d[0] = positions[v].x, d[1] = positions[v].y, d[2] = positions[v].z, d[3] = s[4];
    d[4] = normals[v].x, d[5] = normals[v].y, d[6] = normals[v].z, d[7] = s[3];
    d[8] = s[0], d[9] = s[1], d[10] = s[2];
  }
  return out;
}

std::string glossyFusedMain(int size, int bands, int rowTexels, int vectors) {
  const int active = texelsForOrder(bands);
  static const char* const kChannel[3] = {"r", "g", "b"};
  static const char* const kComponent[4] = {"x", "y", "z", "w"};
  std::ostringstream s;
  for (int i = 0; i < size; ++i) s << "out vec4 vG" << i << ";\n";
  s << "vec4 tableTexel(int i) { return texelFetch(uTable, texelCoord(i), 0); }\n"
    << "vec4 vertexTexel(int i) { return texelFetch(uVertexData, texelCoord(i), 0); }\n"
    << "void main() {\n  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n"
    << "  int base = int(aCluster) * " << (1 + vectors) * 3 * rowTexels << ";\n"
    << "  vec4 a, b, f;\n";
  for (int i = 0; i < size; ++i) {
    const std::string member = std::string(i < 4 ? "aMembers0." : "aMembers1.") + kComponent[i % 4];
    // A slot past its cluster's last vertex (-1) is computed for vertex 0 and written as 0: no
    // branch around the member, whose lanes then stay in step.
    s << "  int v" << i << " = max(" << member << ", 0);\n"
      << "  a = vertexTexel(3 * v" << i << "); b = vertexTexel(3 * v" << i << " + 1); f = vertexTexel(3 * v" << i << " + 2);\n"
      << "  vec4 gy" << i << "[16];\n  vec3 ks" << i << ";\n"
      << "  bool on" << i << " = lobeTowardEye(a.xyz, b.xyz, vec4(f.rgb, b.w), a.w, gy" << i << ", ks" << i << ") && " << member
      << " >= 0;\n"
      << "  int w" << i << " = v" << i << " * uWeightTexels;\n"
      << "  float s" << i << "r = 0.0, s" << i << "g = 0.0, s" << i << "b = 0.0;\n"
      << "  vec4 q" << i << ";\n";
  }
  s << "  vec4";
  for (int t = 0; t < active; ++t) s << (t ? ", t" : " t") << t;
  s << ";\n";
  for (int m = 0; m <= vectors; ++m) {
    if (m >= 1 && (m - 1) % 4 == 0) {
      // Levels of basis matrices m .. m + 3, 4 to a weight texel.
      for (int i = 0; i < size; ++i) s << "  q" << i << " = vec4(texelFetch(uWeights, texelCoord(w" << i << " + " << (m - 1) / 4 << "), 0));\n";
    }
    for (int c = 0; c < 3; ++c) {
      const int row = (m * 3 + c) * rowTexels;
      for (int t = 0; t < active; ++t) s << "  t" << t << " = tableTexel(base + " << row + t << ");\n";
      for (int i = 0; i < size; ++i) {
        s << "  s" << i << kChannel[c] << " += ";
        if (m > 0) s << "q" << i << "." << kComponent[(m - 1) % 4] << " * ";
        s << "(";
        for (int t = 0; t < active; ++t) s << (t ? " + " : "") << "dot(t" << t << ", gy" << i << "[" << t << "])";
        s << ");\n";
      }
    }
  }
  for (int i = 0; i < size; ++i) {
    s << "  vG" << i << " = on" << i << " ? vec4(ks" << i << " * vec3(s" << i << "r, s" << i << "g, s" << i << "b), 0.0) : vec4(0.0);\n";
  }
  s << "}\n";
  return s.str();
}

std::vector<float> glossyFusedCpu(const GlossyTextures& p, const GlossyGroups& groups, const std::vector<float>& table,
                                  int activeBands, std::span<const Vec3> positions, std::span<const Vec3> normals, Vec3 eye,
                                  bool fresnel) {
  const int bands = std::clamp(activeBands, 1, p.bands);
  const int active = texelsForOrder(bands);
  const std::size_t V = p.clusterOf.size(), N = static_cast<std::size_t>(p.vectors), R = static_cast<std::size_t>(p.rowTexels);
  std::vector<float> out(3 * V, 0.0f);
  if (positions.size() != V || normals.size() != V || groups.slot.size() != V ||
      table.size() != static_cast<std::size_t>(p.tableTexels) * 4) {
    return out;
  }
  const std::size_t perVertex = static_cast<std::size_t>(p.weightTexels) * 4;
  float gy[kMaxGlossyOrder * kMaxGlossyOrder + 4];
  for (std::size_t v = 0; v < V; ++v) {
    Rgb ks;
    std::fill(std::begin(gy), std::end(gy), 0.0f);
    if (!glossyLobeTowardEye(bands, &p.specular[kGlossySpecularFloats * v], positions[v], normals[v], eye, fresnel, gy, &ks)) continue;
    const std::size_t k = p.clusterOf[v];
    float sums[3] = {0.0f, 0.0f, 0.0f};
    for (std::size_t m = 0; m <= N; ++m) {
      float level = 1.0f;
      if (m > 0) {
        const std::size_t j = v * perVertex + (m - 1);
        level = p.weightBits == 8 ? static_cast<float>(static_cast<std::int8_t>(p.weightData[j]))
                                  : static_cast<float>(static_cast<std::int16_t>(p.weightData[2 * j] | (p.weightData[2 * j + 1] << 8)));
      }
      for (std::size_t c = 0; c < 3; ++c) {
        const float* row = &table[(((k * (1 + N) + m) * 3 + c) * R) * 4];
        float d = 0.0f;
        for (int t = 0; t < active; ++t) {
          const float* x = &row[static_cast<std::size_t>(t) * 4];
          const float* y = &gy[4 * t];
          d += x[0] * y[0] + x[1] * y[1] + x[2] * y[2] + x[3] * y[3];
        }
        sums[c] += m == 0 ? d : level * d;
      }
    }
    out[3 * v] = ks.r * sums[0];
    out[3 * v + 1] = ks.g * sums[1];
    out[3 * v + 2] = ks.b * sums[2];
  }
  return out;
}

}  // namespace prt::web
