// The fused glossy step for frames whose lighting changed (docs/web-client.md, "Glossy
// rendering", "Fused relight"): each vertex's glossy exit radiance straight from the cluster
// table, without the transferred radiance T in between,
//   L_vc = k_s,c sum_m level_vm (sum_i table[k][m][c]_i g_l(i) y_i(R_v))   (level_v0 = 1)
// by linearity the same value as glossy.vert on glossy_transfer.vert's T. One shader point
// handles a group of up to kMaxGlossyGroup vertices of one cluster, so every table texel it
// fetches serves the whole group: the fetches per vertex fall by the group size (a software
// rasteriser spends most of a relight on them; docs/bench/glossy.md). GL-free: the grouping, the
// generated shader code and a CPU emulation in the shader's order, tested under Node.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "glossy_texture.h"
#include "prt/vec3.h"

namespace prt::web {

// Most vertices one fused point handles (two ivec4 member attributes).
inline constexpr int kMaxGlossyGroup = 8;
// Most dot products glossyFusedMain writes out, (1 + N') * 3 * rows texels * group size: keeps
// the generated shader (and its compile time) bounded at large N' and orders (the dragon's
// K = 128, N' = 29, order 5 at groups of 8: 5040).
inline constexpr int kMaxGlossyFusedDots = 8192;

// The group size the renderer uses for `vertices` in `clusters` clusters of a pass with
// `vectors` basis matrices and `rowTexels` texels a table row: the largest of 1, 2, 4 and 8
// (kMaxGlossyGroup) not above the mean cluster size, so that partly filled groups (a cluster's
// last) stay a small share, and within kMaxGlossyFusedDots. Larger groups fetch less per vertex
// (docs/bench/glossy.md, "Fused relight": 8 measured fastest in SwiftShader); a plain matrix
// pass (a cluster a vertex) gets 1.
int glossyGroupSize(std::size_t vertices, std::size_t clusters, int vectors, int rowTexels);

// Vertices grouped by cluster for the fused step: group g holds cluster `cluster[g]` and the
// vertex ids members[kMaxGlossyGroup * g + i], i < group size (-1 past a cluster's last
// vertex); vertex v's result is point output slot[v] = size * g + i.
struct GlossyGroups {
  int size = 0;                          // vertices per group (1 .. kMaxGlossyGroup)
  std::vector<std::uint32_t> cluster;    // per group
  std::vector<std::int32_t> members;     // kMaxGlossyGroup per group
  std::vector<std::uint32_t> slot;       // per vertex
  std::size_t groups() const { return cluster.size(); }
};

// Groups the vertices of `clusterOf` (ids < clusters) `size` at a time within each cluster, in
// cluster order and, within one, in vertex order. kInvalidArgument for a size outside
// 1 .. kMaxGlossyGroup or an id out of range (safe on untrusted ids).
Status groupGlossyVertices(std::span<const std::uint16_t> clusterOf, int clusters, int size, GlossyGroups* out);

// Per vertex, the 12 floats the fused step reads (3 RGBA32F texels): position and f90, normal
// and Phong exponent, f0 and 0. `specular` is GlossyTextures::specular (kGlossySpecularFloats a
// vertex). Empty when the spans disagree in length.
std::vector<float> packGlossyVertexData(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                        std::span<const float> specular);

// The main() (and its outputs vG0 .. vG{size-1}) appended to glossy.vert compiled with GROUP
// defined: the fused step for `bands` displayed bands of a pass packed with `rowTexels` texels a
// table row and `vectors` basis matrices a cluster, written out statement by statement (no
// loops: see glossy_transfer.vert for why). Trusted arguments (the renderer's own shape).
std::string glossyFusedMain(int size, int bands, int rowTexels, int vectors);

// The fused step on the CPU in the shader's order of operations: glossy exit radiance RGB per
// vertex toward `eye` from glossyTableCpu's table at `activeBands`, as glossyRadianceCpu gives it
// from the transferred radiance (equal up to float rounding).
std::vector<float> glossyFusedCpu(const GlossyTextures& packed, const GlossyGroups& groups, const std::vector<float>& table,
                                  int activeBands, std::span<const Vec3> positions, std::span<const Vec3> normals, Vec3 eye,
                                  bool fresnel = true);

}  // namespace prt::web
