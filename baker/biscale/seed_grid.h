// A hashed uniform grid over points (the seeds of a synthesised id map): finds every point
// within one cell size of a query in the 27 cells around it. Hashed, so a sparse scene (small
// objects far apart) costs memory per occupied cell, not per cell of its bounding box.
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "prt/vec3.h"

namespace prt::bake {

class SeedGrid {
 public:
  // cellSize: world units, finite and > 0 (the caller checks).
  explicit SeedGrid(double cellSize) : inverse_(1.0 / cellSize) {}

  // Adds point `id` at p (finite).
  void insert(Vec3 p, std::uint32_t id) { cells_[keyOf(p)].push_back(id); }

  // Calls visit(id) for every id inserted in the 3 × 3 × 3 cells around p's: a superset of the
  // points within cellSize of p. Cells in a fixed order, ids in insertion order.
  template <class Visit>
  void forNeighbours(Vec3 p, Visit&& visit) const {
    const Key k = keyOf(p);
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(Key{k.x + dx, k.y + dy, k.z + dz});
          if (it == cells_.end()) continue;
          for (std::uint32_t id : it->second) visit(id);
        }
  }

 private:
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ULL;
      h ^= static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
      h ^= static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ULL + (h << 6) + (h >> 2);
      return static_cast<std::size_t>(h);
    }
  };

  // Clamped, so a far point cannot overflow the integer; clamping is monotone, so two points
  // within one cell of each other stay in neighbouring cells.
  std::int64_t cellOf(float c) const {
    const double k = std::floor(static_cast<double>(c) * inverse_);
    constexpr double kLimit = 1e15;
    return static_cast<std::int64_t>(k < -kLimit ? -kLimit : (k > kLimit ? kLimit : k));
  }
  Key keyOf(Vec3 p) const { return {cellOf(p.x), cellOf(p.y), cellOf(p.z)}; }

  double inverse_;
  std::unordered_map<Key, std::vector<std::uint32_t>, KeyHash> cells_;
};

}  // namespace prt::bake
