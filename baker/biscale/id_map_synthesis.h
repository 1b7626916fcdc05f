// The synthesised id map of bi-scale radiance transfer (Sloan et al. 2003, §4.3; docs/bi-scale.md,
// "Synthesised id map"): the surface is cut into cells around seeds spread over it, each cell
// carries one placement of the periodic RTT patch (a frame along the smooth direction field
// patchTangent and a random phase), and every texel of the mesh's atlases records the cell
// it lies in. Exact within a cell (q is linear in the surface point); a phase jump at cell borders.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/asset.h"
#include "prt/patch_placement.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

struct IdMapSettings {
  double patchWidth = 0;   // world units the RTT's patch spans; finite, > 0
  double cellPatches = 3;  // a cell's mean diameter in patch widths (a disc of the mean cell area); finite, >= 1
  std::uint64_t seed = 1;  // the seeds' positions and the phases (Pcg32)
  int gutterTexels = 3;    // texels around each chart given its placement (0 … kMaxDilationPasses), as the asset's dilation
};

struct SynthesisedIdMap {
  std::vector<PatchPlacement> placements;  // at most kMaxPatchPlacements
  // One per texel of all atlases (atlas after atlas, row-major: BakedAsset::texelCoverage's
  // order): the index of the placement whose cell holds the texel's surface sample, the
  // nearest sampled texel's within gutterTexels of a chart, else kNoPlacement.
  std::vector<std::uint16_t> placementOfTexel;
};

// Synthesises the id map of the mesh (positions and normals world space, normals non-zero;
// indices 3 per triangle; atlasUv one per vertex in [0, 1]) over `atlases`
// (rasteriseAtlases's rules). A texel takes the seed nearest its sample (Euclidean, 3D) among
// those whose normal is within acos(0.3) of its own; there is always one within one cell
// diameter. Errors: kInvalidArgument naming the setting (patchWidth, cellPatches,
// gutterTexels), or a surface needing more than kMaxPatchPlacements cells (with the count and
// what to enlarge), or a mesh of zero area; rasteriseAtlases's errors. *out is then empty.
// Safe on untrusted input; deterministic (single-threaded, the same bytes for the same input).
Status synthesiseIdMap(std::span<const Vec3> positions, std::span<const Vec3> normals,
                       std::span<const std::uint32_t> indices, std::span<const Uv> atlasUv,
                       std::span<const TextureAtlas> atlases, const IdMapSettings& settings, SynthesisedIdMap* out);

// The same over the mesh's triangles instead of an atlas (no UVs needed): each triangle takes
// the placement of the facing seed nearest its centroid (its face normal), so cells end on
// mesh edges; for meshes whose triangles are much smaller than a cell (scans). placementOfTexel
// then holds one entry per triangle. Errors as synthesiseIdMap's, and kInvalidArgument for
// inconsistent sizes, an index out of range or a non-finite position.
Status synthesiseTriangleIdMap(std::span<const Vec3> positions, std::span<const Vec3> normals,
                               std::span<const std::uint32_t> indices, const IdMapSettings& settings, SynthesisedIdMap* out);

}  // namespace prt::bake
