// The fixed set of test lightings `prt-bake compress-report` measures exit-radiance error
// under: environment maps at several rotations, and small distant caps ("local lights")
// from several directions.
#pragma once

#include <string>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

struct TestLighting {
  std::string name;          // "forest.exr yaw 120", "cap +y"
  std::vector<Rgb> coeffs;   // order^2 radiance coefficients
};

// Rotations applied to every environment map (yaw about +y, then a tilt about +x), degrees.
struct EnvRotation {
  float yawDeg = 0.0f;
  float tiltDeg = 0.0f;
};
inline constexpr EnvRotation kTestEnvRotations[] = {{0, 0}, {120, 0}, {240, 0}, {45, 60}};

// Angular radius of the caps, radians (about 8.6 degrees: a small, sun-like source).
inline constexpr float kTestCapRadius = 0.15f;

// The lightings at `order`: every *.exr file in `envDir` (sorted by name; at least one
// required) projected (layout from its aspect ratio) and rotated by each of
// kTestEnvRotations, then white caps of radiance 1 about six fixed directions.
Status makeTestLightings(const std::string& envDir, int order, std::vector<TestLighting>* out);

}  // namespace prt
