#include "baker/biscale/id_map_synthesis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "baker/biscale/placement_gutters.h"
#include "baker/biscale/seed_grid.h"
#include "baker/biscale/surface_seeds.h"
#include "baker/texture/atlas_samples.h"
#include "baker/texture/texel_dilate.h"
#include "prt/sampling.h"

namespace prt::bake {
namespace {

// The phases come from their own stream, so a change in how many darts the seeding draws
// does not shift every phase.
constexpr std::uint64_t kPhaseStream = 0x6964206d61702031ULL;  // "id map 1"

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

Status checkSettings(const IdMapSettings& s) {
  if (!std::isfinite(s.patchWidth) || !(s.patchWidth > 0)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "patchWidth " + number(s.patchWidth) + " is not a finite number > 0 (world units)");
  }
  if (!std::isfinite(s.cellPatches) || !(s.cellPatches >= 1)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "cellPatches " + number(s.cellPatches) + " is not a finite number >= 1 (patch widths)");
  }
  if (!std::isfinite(s.patchWidth * s.cellPatches)) {
    return Status::error(StatusCode::kInvalidArgument, "patchWidth × cellPatches overflows");
  }
  if (s.gutterTexels < 0 || s.gutterTexels > kMaxDilationPasses) {
    return Status::error(StatusCode::kInvalidArgument, "gutterTexels " + std::to_string(s.gutterTexels) +
                                                           " is outside 0 … " + std::to_string(kMaxDilationPasses));
  }
  return Status::ok();
}

double meshArea(std::span<const Vec3> positions, std::span<const std::uint32_t> indices) {
  double total = 0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const Vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
    const double ux = double{b.x} - a.x, uy = double{b.y} - a.y, uz = double{b.z} - a.z;
    const double vx = double{c.x} - a.x, vy = double{c.y} - a.y, vz = double{c.z} - a.z;
    const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    total += 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  }
  return total;
}

Status tooManyCells(double count, double area, const IdMapSettings& s) {
  return Status::error(StatusCode::kInvalidArgument,
                       "the surface (area " + number(area) + ") needs " + number(count) +
                           " patch placements at patchWidth " + number(s.patchWidth) + " and cellPatches " +
                           number(s.cellPatches) + ", more than " + std::to_string(kMaxPatchPlacements) +
                           ": use a larger patchWidth or cellPatches");
}

// The placement of one seed: axes along the direction field, and a phase (u0, v0) in
// [0, 1)^2 that q takes at the seed, folded into the origin.
PatchPlacement placementAt(const SurfaceSeed& s, double patchWidth, float u0, float v0) {
  const Vec3 t = patchTangent(s.normal);
  const Vec3 b = cross(s.normal, t);
  const float w = static_cast<float>(patchWidth), inv = static_cast<float>(1.0 / patchWidth);
  return {s.position - (t * (u0 * w) + b * (v0 * w)), t * inv, b * inv};
}

// The cells for `samples` (every one ends with a facing seed within a cell diameter): seeds by
// dart throwing and gap filling, one placement each (phases from their own stream), and each
// sample's placement, by index, into *assigned. kInvalidArgument for a zero-area mesh or too
// many cells, naming the settings.
Status placeCells(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const std::uint32_t> indices,
                  std::span<const AtlasTexel> samples, const IdMapSettings& settings, const char* sampleName,
                  SynthesisedIdMap* r, std::vector<std::uint16_t>* assigned) {
  const double diameter = settings.patchWidth * settings.cellPatches;
  const double area = meshArea(positions, indices);
  if (!(area > 0)) return Status::error(StatusCode::kInvalidArgument, "the mesh has zero area: no surface to place patches on");
  const double cells = area / (kPi / 4 * diameter * diameter);
  if (!(cells <= static_cast<double>(kMaxPatchPlacements))) return tooManyCells(std::ceil(cells), area, settings);

  std::vector<SurfaceSeed> seeds;
  SeedGrid grid(diameter);
  throwSeedDarts(positions, normals, indices, diameter, std::max<std::size_t>(1, std::llround(cells)), settings.seed,
                 &seeds, &grid);
  fillSeedGaps(samples, diameter, kMaxPatchPlacements, &seeds, &grid);
  if (seeds.size() > kMaxPatchPlacements) {
    return Status::error(StatusCode::kInvalidArgument,
                         "the surface (area " + number(area) + ") needs more than " + std::to_string(kMaxPatchPlacements) +
                             " patch placements at patchWidth " + number(settings.patchWidth) + " and cellPatches " +
                             number(settings.cellPatches) + " (its parts and far sides need cells of their own): " +
                             "use a larger patchWidth or cellPatches");
  }
  Pcg32 phases(settings.seed, kPhaseStream);
  r->placements.reserve(seeds.size());
  for (const SurfaceSeed& s : seeds) {
    const float u0 = phases.nextFloat(), v0 = phases.nextFloat();
    r->placements.push_back(placementAt(s, settings.patchWidth, u0, v0));
  }
  for (const AtlasTexel& t : samples) {
    const std::uint32_t id = nearestFacingSeed(grid, seeds, t.position, t.normal, diameter);
    // fillSeedGaps left a facing seed within the diameter of every sample.
    if (id == kNoSeed) return Status::error(StatusCode::kInternal, std::string(sampleName) + " " + std::to_string(t.index) + " has no seed");
    (*assigned)[t.index] = static_cast<std::uint16_t>(id);
  }
  return Status::ok();
}

}  // namespace

Status synthesiseIdMap(std::span<const Vec3> positions, std::span<const Vec3> normals,
                       std::span<const std::uint32_t> indices, std::span<const Uv> atlasUv,
                       std::span<const TextureAtlas> atlases, const IdMapSettings& settings, SynthesisedIdMap* out) {
  *out = SynthesisedIdMap{};
  PRT_RETURN_IF_ERROR(checkSettings(settings));
  // The rasteriser validates the mesh (sizes, indices, finite values, UVs, non-zero normals)
  // and every triangle, since the atlases' runs cover them all.
  AtlasSamples samples;
  const std::vector<Rgb> noAlbedo(positions.size());
  PRT_RETURN_IF_ERROR(rasteriseAtlases(positions, normals, noAlbedo, indices, atlasUv, atlases, &samples));

  SynthesisedIdMap r;
  r.placementOfTexel.assign(samples.sampled.size(), kNoPlacement);
  PRT_RETURN_IF_ERROR(placeCells(positions, normals, indices, samples.texels, settings, "texel", &r, &r.placementOfTexel));
  PRT_RETURN_IF_ERROR(fillPlacementGutters(atlases, samples.firstTexel, samples.sampled, settings.gutterTexels,
                                           r.placementOfTexel));
  *out = std::move(r);
  return Status::ok();
}

Status synthesiseTriangleIdMap(std::span<const Vec3> positions, std::span<const Vec3> normals,
                               std::span<const std::uint32_t> indices, const IdMapSettings& settings, SynthesisedIdMap* out) {
  *out = SynthesisedIdMap{};
  PRT_RETURN_IF_ERROR(checkSettings(settings));
  if (normals.size() != positions.size() || indices.size() % 3 != 0 || indices.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "the mesh's normals, positions and indices disagree");
  }
  // Triangle centroids and face normals stand for the texels' samples.
  std::vector<AtlasTexel> samples;
  samples.reserve(indices.size() / 3);
  for (std::size_t t = 0; t < indices.size() / 3; ++t) {
    const std::uint32_t* c = &indices[3 * t];
    if (c[0] >= positions.size() || c[1] >= positions.size() || c[2] >= positions.size()) {
      return Status::error(StatusCode::kInvalidArgument, "triangle " + std::to_string(t) + " has an index out of range");
    }
    const Vec3 a = positions[c[0]], b = positions[c[1]], d = positions[c[2]];
    AtlasTexel s;
    s.index = t;
    s.triangle = static_cast<std::uint32_t>(t);
    s.position = (a + b + d) * (1.0f / 3.0f);
    Vec3 n = cross(b - a, d - a);
    const float length = std::sqrt(dot(n, n));
    // A degenerate triangle takes its vertices' mean normal.
    if (!(length > 0.0f)) n = normals[c[0]] + normals[c[1]] + normals[c[2]];
    const float nl = std::sqrt(dot(n, n));
    if (!std::isfinite(s.position.x + s.position.y + s.position.z) || !(nl > 0.0f) || !std::isfinite(nl)) {
      return Status::error(StatusCode::kInvalidArgument, "triangle " + std::to_string(t) + " has no finite position or normal");
    }
    s.normal = n * (1.0f / nl);
    samples.push_back(s);
  }
  SynthesisedIdMap r;
  r.placementOfTexel.resize(samples.size());
  PRT_RETURN_IF_ERROR(placeCells(positions, normals, indices, samples, settings, "triangle", &r, &r.placementOfTexel));
  *out = std::move(r);
  return Status::ok();
}

}  // namespace prt::bake
