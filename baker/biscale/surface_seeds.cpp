#include "baker/biscale/surface_seeds.h"

#include <algorithm>
#include <cmath>

#include "prt/sampling.h"

namespace prt::bake {
namespace {

struct DVec {
  double x, y, z;
};
DVec toD(Vec3 a) { return {a.x, a.y, a.z}; }
DVec sub(DVec a, DVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DVec crossD(DVec a, DVec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double lengthD(DVec a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }

// Uniform in (0, 1) with 32 bits: nextFloat's 24 would leave a large mesh's smallest
// triangles unreachable.
double uniformOpen(Pcg32& rng) { return (static_cast<double>(rng.next()) + 0.5) * (1.0 / 4294967296.0); }

}  // namespace

std::uint32_t nearestFacingSeed(const SeedGrid& grid, std::span<const SurfaceSeed> seeds, Vec3 p, Vec3 normal,
                                double radius) {
  std::uint32_t best = kNoSeed;
  double bestD2 = radius * radius;
  grid.forNeighbours(p, [&](std::uint32_t id) {
    const SurfaceSeed& s = seeds[id];
    if (dot(s.normal, normal) <= kFacingCos) return;
    const DVec d = sub(toD(s.position), toD(p));
    const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (d2 < bestD2 || (d2 == bestD2 && id < best)) {
      bestD2 = d2;
      best = id;
    }
  });
  return best;
}

void throwSeedDarts(std::span<const Vec3> positions, std::span<const Vec3> normals,
                    std::span<const std::uint32_t> indices, double cellDiameter, std::size_t count, std::uint64_t seed,
                    std::vector<SurfaceSeed>* seeds, SeedGrid* grid) {
  const std::size_t triangles = indices.size() / 3;
  std::vector<double> cumulative(triangles);
  double total = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const DVec a = toD(positions[indices[3 * t]]), b = toD(positions[indices[3 * t + 1]]),
               c = toD(positions[indices[3 * t + 2]]);
    total += 0.5 * lengthD(crossD(sub(b, a), sub(c, a)));
    cumulative[t] = total;
  }
  Pcg32 rng(seed);
  // 0.6 of the mean diameter keeps the spacing well below random packing's jamming limit
  // (about 0.74 at this density), where darts would almost never land.
  double spacing = 0.6 * cellDiameter;
  const std::size_t budget = 32 * count + 1024;
  std::size_t darts = 0;
  const std::size_t target = seeds->size() + count;
  while (seeds->size() < target) {
    // Counted per round, not per miss in a row: a mesh folded into little volume (stacked
    // sheets) keeps landing an occasional dart, and would otherwise crawl.
    if (darts == budget) {
      spacing *= 0.85;
      darts = 0;
    }
    ++darts;
    const double r = uniformOpen(rng) * total;
    // upper_bound skips zero-area triangles: their cumulative sum equals the one before.
    const std::size_t t = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()),
        triangles - 1);
    const double su = std::sqrt(uniformOpen(rng)), r2 = uniformOpen(rng);
    const double w[3] = {1.0 - su, su * (1.0 - r2), su * r2};
    DVec p{0, 0, 0}, n{0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const DVec pk = toD(positions[indices[3 * t + k]]), nk = toD(normals[indices[3 * t + k]]);
      const double nl = lengthD(nk);
      p = {p.x + w[k] * pk.x, p.y + w[k] * pk.y, p.z + w[k] * pk.z};
      if (nl > 0) n = {n.x + w[k] * nk.x / nl, n.y + w[k] * nk.y / nl, n.z + w[k] * nk.z / nl};
    }
    double nl = lengthD(n);
    if (!(nl > 1e-6)) {
      // Opposed corner normals cancel: the face normal (the triangle has area, so it exists).
      const DVec a = toD(positions[indices[3 * t]]), b = toD(positions[indices[3 * t + 1]]),
                 c = toD(positions[indices[3 * t + 2]]);
      n = crossD(sub(b, a), sub(c, a));
      nl = lengthD(n);
    }
    const SurfaceSeed s{Vec3{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)},
                        Vec3{static_cast<float>(n.x / nl), static_cast<float>(n.y / nl), static_cast<float>(n.z / nl)}};
    if (nearestFacingSeed(*grid, *seeds, s.position, s.normal, spacing) != kNoSeed) continue;
    grid->insert(s.position, static_cast<std::uint32_t>(seeds->size()));
    seeds->push_back(s);
  }
}

void fillSeedGaps(std::span<const AtlasTexel> texels, double radius, std::size_t maxSeeds,
                  std::vector<SurfaceSeed>* seeds, SeedGrid* grid) {
  for (const AtlasTexel& t : texels) {
    if (seeds->size() > maxSeeds) return;
    if (nearestFacingSeed(*grid, *seeds, t.position, t.normal, radius) != kNoSeed) continue;
    grid->insert(t.position, static_cast<std::uint32_t>(seeds->size()));
    seeds->push_back({t.position, t.normal});
  }
}

}  // namespace prt::bake
