// Whether a UV set can serve as a lightmap atlas (transfer textures, docs/transfer-textures.md):
// every texel the baker writes must belong to one surface point only, so the UVs must be
// finite, inside [0, 1], non-degenerate where the surface has area, free of overlaps
// (stacked or mirrored copies included) and, between charts, at least `padding` texels apart
// at the target resolution (the gutter that dilation and bilinear filtering need).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// The atlas texture the UVs are checked for.
struct UvAtlasTarget {
  int width = 1024;   // texels, 1 … kMaxAtlasSize
  int height = 1024;  // texels, 1 … kMaxAtlasSize
  int padding = 2;    // texels of gutter required between charts, 0 … kMaxAtlasPadding
};

inline constexpr int kMaxAtlasSize = 16384;
inline constexpr int kMaxAtlasPadding = 64;

// Overlapping pairs are counted up to this many; past it the scan stops (a fully stacked
// layout would otherwise cost n² tests) and the count reads as "at least".
inline constexpr std::size_t kMaxOverlapsCounted = 10000;

struct UvAtlasReport {
  std::size_t triangles = 0;
  std::size_t nonFinite = 0;         // a corner's UV is NaN or infinite
  std::size_t outOfRange = 0;        // a corner's UV lies outside [0, 1] (such triangles are left
                                     // out of the overlap and gutter checks)
  std::size_t degenerate = 0;        // zero UV area where the 3D triangle has area
  std::size_t overlappingPairs = 0;  // pairs of triangles whose UV interiors intersect
  bool overlapCountCapped = false;   // overlappingPairs reached kMaxOverlapsCounted
  // How far the worst pair interpenetrates (smallest projection overlap, in texels at the
  // target): tells a sub-texel sliver fold from a stacked chart. 0 without overlaps.
  double deepestOverlapTexels = 0.0;
  std::size_t paddingConflicts = 0;  // texels of one chart within `padding` texels of another chart's
  // The rasterisation stopped at its budget (a layout covering the texture over 64 times, only
  // possible with overlaps): usedTexels and paddingConflicts count what was reached.
  bool rasterIncomplete = false;
  std::size_t charts = 0;            // connected components (triangles sharing an edge in 3D and in UV)
  std::size_t usedTexels = 0;        // texels some triangle touches (conservative rasterisation)
  double usedTexelFraction = 0.0;    // usedTexels / (width × height)
  // The first problems found (at most kMaxListedProblems), each naming the UV set, the
  // triangle(s) and, for padding, the texel.
  std::vector<std::string> problems;

  bool valid() const {
    return nonFinite == 0 && outOfRange == 0 && degenerate == 0 && overlappingPairs == 0 && paddingConflicts == 0;
  }
  // One line: "valid" or the counts of each kind of problem, then charts and texel use.
  std::string summary() const;
};

inline constexpr std::size_t kMaxListedProblems = 8;

// Checks `uvs` (one per position; `setName`, e.g. "TEXCOORD_1", labels the messages) as an
// atlas of `indices` (3 per triangle) for `target`. Problems with the UVs go into *out, not
// the status; the status is an error only for unusable arguments (sizes, indices, target).
Status checkUvAtlas(std::span<const Vec3> positions, std::span<const std::uint32_t> indices,
                    std::span<const Uv> uvs, const UvAtlasTarget& target, std::string_view setName,
                    UvAtlasReport* out);

// Charts of the triangles `indices` (3 per triangle) over `uvs` (one per position): triangles
// sharing an edge whose two corners agree in position and in UV are one chart (the count the
// report above gives). Indices must be < positions.size() == uvs.size() (kInvalidArgument else).
Status countUvCharts(std::span<const Vec3> positions, std::span<const std::uint32_t> indices, std::span<const Uv> uvs,
                     std::size_t* charts);

}  // namespace prt::bake
