// Texel rasterisation for transfer textures (docs/transfer-textures.md, "Texel rasterisation"):
// every texel of a W×H atlas that some triangle's UV footprint touches gets one surface
// sample (triangle, barycentrics, world position, unit normal), the G-buffer of PRTT's
// Algorithm 1, computed on the CPU so a bake job needs no GPU.
//
// Conventions (glTF): UV (0, 0) is the image's top-left corner, u to the right, v down;
// pixel coordinates are uv × (W, H), so texel (x, y) covers [x, x+1) × [y, y+1) and its
// centre is (x + 0.5, y + 0.5); texel index = y × W + x. Distances are in texels.
//
// Coverage is conservative: a texel is used iff its square and the triangle overlap with
// positive area (touching an edge or a corner only does not count), tested per row on the
// triangle's exact extent in double precision, so every texel a triangle reaches holds data,
// and a triangle smaller than a texel still gets at least one.
//
// Ownership: among the triangles touching a texel, the one whose UV footprint is nearest the
// texel centre owns it (distance 0 when the centre is inside or on an edge; ties go to the
// lower triangle index), and the sample is that triangle's point nearest the centre: the
// centre itself, with exact barycentrics, when inside; otherwise the centre clamped onto the
// triangle's boundary. A sample never extrapolates off the surface, which is where light
// leaks start. A texel touched by several triangles yields exactly one sample.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/scene/uv_atlas_check.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// A layout that touches more than this many texels per atlas texel (plus per triangle) can
// only come from stacked charts; past it the rasterisation fails instead of running for hours.
inline constexpr double kMaxTexelVisitsPerTexel = 64.0;
inline constexpr double kMaxTexelVisitsPerTriangle = 64.0;

struct TexelSample {
  std::uint32_t texel = 0;      // y × width + x
  std::uint32_t triangle = 0;   // the owner: corners are indices[3 × triangle + 0 … 2]
  std::array<float, 3> bary{};  // weights of the owner's corners in index order, each >= 0, sum 1
  float uvDistance = 0;         // texels from the texel centre to the sample's UV point; 0 inside
  Vec3 position;                // world space, on the owner triangle
  Vec3 normal;                  // unit: the corner normals (normalised) interpolated, normalised
};

struct TexelRaster {
  int width = 0, height = 0;
  std::vector<TexelSample> samples;     // one per used texel, in ascending texel index
  std::vector<std::uint8_t> coverage;   // width × height, row-major: 1 where a sample exists, else 0
  std::size_t degenerateTriangles = 0;  // zero UV area (mesh clean-up's relative test): skipped
  // Samples whose interpolated normal cancelled out (opposed corner normals): they take the
  // face normal, or, on a zero-area 3D triangle, the normal of their heaviest corner.
  std::size_t normalFallbacks = 0;
};

// Rasterises `indices` (3 per triangle, either winding) with `uvs` (in [0, 1]) into a
// width × height atlas (1 … kMaxAtlasSize each, uv_atlas_check.h) and replaces *out with the
// result. `positions` (world, metres), `normals` (non-zero, any length) and `uvs` have one
// entry per vertex; only vertices some triangle references are read. Errors: kSizeMismatch
// (the three of different lengths), kInvalidArgument (an index count not a multiple of 3, an
// index out of range, a UV outside [0, 1], a zero normal, the atlas size), kNotFinite (a NaN
// or infinite UV, position or normal), kResourceExhausted (over the visit budget above, or
// out of memory); *out is then empty. Safe on untrusted input; deterministic (single-threaded:
// the same input gives the same bytes).
Status rasteriseTexels(std::span<const Vec3> positions, std::span<const Vec3> normals,
                       std::span<const std::uint32_t> indices, std::span<const Uv> uvs, int width, int height,
                       TexelRaster* out);

}  // namespace prt::bake
