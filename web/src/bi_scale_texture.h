// The bi-scale client's GL-free parts (docs/bi-scale.md, "The client"): the per-vertex SH
// rotations into the tangent frames, packed for the rotation step; that step's GLSL, written
// out per shape; its CPU emulation; and the corner buffer the fragment pass draws from.
// Tested under Node (wasm_bi_scale_core).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "prt/patch_placement.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::web {

// Rotation entries a vertex needs for `bands` bands: the blocks of bands 1 .. bands - 1 (band 0
// is the identity), sum (2l + 1)^2.
int biScaleRotationEntries(int bands);
// RGBA texels a vertex's rotation takes: ceil(entries / 4).
inline int biScaleRotationTexels(int bands) { return (biScaleRotationEntries(bands) + 3) / 4; }

// Per vertex, the SH rotation D_v of the world-to-tangent rotation (rows: the tangent made
// orthogonal to the normal, cross(normal, tangent), the normal; prt::ShRotation), its blocks
// of bands 1 .. bands - 1 row-major, one after another, zero-padded to whole texels:
// values[(v * texelsPerVertex) * 4 + e]. bands 1 .. 8. kInvalidArgument naming a vertex whose
// frame is degenerate (normal and tangent parallel, or not finite).
struct BiScaleRotations {
  int bands = 0;
  int texelsPerVertex = 0;
  std::vector<float> values;
};
Status packBiScaleRotations(std::span<const Vec3> normals, std::span<const Vec3> tangents, int bands, BiScaleRotations* out);

// The rotation step's main() (appended to biscale_rotate.vert): one point per vertex and one
// draw per channel; reads T's row of the channel (rowTexels texels, glossy_transfer.vert's
// output) and the vertex's rotation texels, writes vR0 .. vR{rowTexels - 1}: band 0 as it is,
// bands 1 .. bands - 1 rotated, the rest 0. Written out with constant indices (see
// glossy_transfer.vert for why). bands 1 .. 8, rowTexels >= ceil(bands^2 / 4), <= 16.
std::string biScaleRotateMain(int bands, int rowTexels);

// The rotation step on the CPU: transfer is [channel][vertex][rowTexels * 4] (T's texture
// layout), out the same shape, as the shader computes it (float, its order of operations).
void biScaleRotateCpu(const BiScaleRotations& rotations, std::span<const float> transfer, int vertices, int rowTexels,
                      std::span<float> out);

// The fragment pass draws de-indexed triangles: per corner position, normal, tangent (3 floats
// each), patch uv and atlas uv (2 each; the one the asset lacks is 0), the triangle's three
// vertex ids (3 uint32) and its placement (a per-triangle id map's entry, else kNoPlacement), 17 words.
inline constexpr int kBiScaleCornerWords = 17;
// Corner words for `indices` (3 per triangle, each < positions.size(); the other spans one
// entry, or 2 for patchUv and atlasUv, per vertex, or empty; trianglePlacements one per
// triangle or empty). kInvalidArgument on inconsistent sizes or an index out of range.
Status packBiScaleCorners(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const Vec3> tangents,
                          std::span<const float> patchUv, std::span<const float> atlasUv,
                          std::span<const std::uint16_t> trianglePlacements, std::span<const std::uint32_t> indices,
                          std::vector<std::uint32_t>* out);

// The placements as RGBA32F texels, 3 a placement: (origin, 0), (axisU, 0), (axisV, 0).
std::vector<float> packPatchPlacements(std::span<const PatchPlacement> placements);

}  // namespace prt::web
