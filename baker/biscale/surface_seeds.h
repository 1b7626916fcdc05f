// The seeds of a synthesised id map (docs/bi-scale.md, "Synthesised id map"): points on the
// mesh, one per cell, spread area-uniformly with a minimum spacing (dart throwing), then gaps
// filled so that every surface sample has a seed facing its way within one cell diameter.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "baker/biscale/seed_grid.h"
#include "baker/texture/atlas_samples.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// A seed serves a point only where their normals are within acos(0.3) ≈ 72.5°: the two sides
// of a thin wall, or a box's adjacent faces, get their own cells.
inline constexpr float kFacingCos = 0.3f;

struct SurfaceSeed {
  Vec3 position;  // world space, on the mesh
  Vec3 normal;    // unit
};

// The seed nearest p (Euclidean, 3D; ties to the lower index) within `radius` (<= the grid's
// cell size) whose normal has a dot product > kFacingCos with `normal` (unit); kNoSeed if none.
inline constexpr std::uint32_t kNoSeed = 0xFFFFFFFFu;
std::uint32_t nearestFacingSeed(const SeedGrid& grid, std::span<const SurfaceSeed> seeds, Vec3 p, Vec3 normal,
                                double radius);

// Appends `count` seeds to *seeds (and *grid, of cell size >= cellDiameter): darts uniform by
// area over the triangles, each kept when no facing seed lies within the spacing, which starts
// at 0.6 × cellDiameter and shrinks by 15% after each round of 32 × count + 1024 darts that
// leaves seeds missing, so it always ends. `indices` must be validated (3 per triangle, in range: rasteriseAtlases checks
// them) and the mesh's area > 0. Deterministic from `seed` (Pcg32).
void throwSeedDarts(std::span<const Vec3> positions, std::span<const Vec3> normals,
                    std::span<const std::uint32_t> indices, double cellDiameter, std::size_t count, std::uint64_t seed,
                    std::vector<SurfaceSeed>* seeds, SeedGrid* grid);

// Adds a seed at every texel (in order) with no facing seed within `radius`, the texel's own
// position and normal: small parts no dart hit and the far side of thin walls get cells.
// Stops once *seeds holds more than maxSeeds. Deterministic.
void fillSeedGaps(std::span<const AtlasTexel> texels, double radius, std::size_t maxSeeds,
                  std::vector<SurfaceSeed>* seeds, SeedGrid* grid);

}  // namespace prt::bake
