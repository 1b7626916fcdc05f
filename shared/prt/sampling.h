// Deterministic direction sets on the unit sphere for Monte Carlo SH projection.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// PCG32 (O'Neill): small, fast, identical output on every platform for a given seed.
class Pcg32 {
 public:
  explicit Pcg32(std::uint64_t seed, std::uint64_t stream = 0x853c49e6748fea9bULL);
  std::uint32_t next();
  // Uniform in [0, 1).
  float nextFloat() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }

 private:
  std::uint64_t state_ = 0, inc_ = 0;
};

// Unit directions stored as separate x, y, z arrays (the layout evalShBasisBatch takes),
// each carrying the same quadrature weight 4pi / count (steradians).
struct DirectionSet {
  std::vector<float> x, y, z;
  double weight = 0.0;
  std::size_t size() const { return x.size(); }
  Vec3 at(std::size_t k) const { return {x[k], y[k], z[k]}; }
};

// Maps the unit square to the sphere preserving area: z = 1 - 2u, phi = 2pi v.
Vec3 squareToSphere(float u, float v);

// Hammersley point set (as in Fujita & Kanai): u_k = (k + 1/2)/n, v_k = radical inverse
// of k in base 2, through squareToSphere. 1 <= count <= 1<<26.
Status hammersleySphere(std::size_t count, DirectionSet* out);

// Jittered stratified set: a side x side grid over the unit square, one uniform point per
// cell from Pcg32(seed), through squareToSphere. 1 <= side <= 8192.
Status stratifiedSphere(std::size_t side, std::uint64_t seed, DirectionSet* out);

}  // namespace prt
