// Helpers shared by the shared-library tests.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "prt/sampling.h"
#include "prt/vec3.h"

namespace prt::test {

// `count` deterministic pseudo-random unit directions, plus the axes and a few awkward
// ones (poles, equator, near-pole) where recurrences tend to break.
inline std::vector<Vec3> testDirections(int count) {
  std::vector<Vec3> dirs = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                            {0.7071068f, 0.7071068f, 0}, {1e-4f, 0, 1}, {0.6f, -0.8f, 0}};
  for (Vec3& d : dirs) d = d * (1.0f / length(d));
  Pcg32 rng(12345);
  while (static_cast<int>(dirs.size()) < count) {
    dirs.push_back(squareToSphere(rng.nextFloat(), rng.nextFloat()));
  }
  return dirs;
}

}  // namespace prt::test
