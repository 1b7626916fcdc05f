// Procedural environments generated in code, so the CLI, its tests and demos have a known
// HDR input without shipping image files.
#pragma once

#include <string_view>

#include "prt/image.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// "sky": a 256x128 equirect (prt::projectEquirect's mapping, +y up) with a blue gradient
// sky above the horizon, dark-brown ground below and a small, bright sun disc.
inline constexpr int kBuiltinSkyWidth = 256;
inline constexpr int kBuiltinSkyHeight = 128;
// Sun centre: elevation 35 degrees, azimuth -50 degrees (from +x toward +z), i.e. up and
// toward +x and -z. tests/cli relies on these signs.
inline constexpr float kBuiltinSkySunElevationDeg = 35.0f;
inline constexpr float kBuiltinSkySunAzimuthDeg = -50.0f;
inline constexpr float kBuiltinSkySunRadiusDeg = 2.5f;
inline constexpr float kBuiltinSkySunRadiance = 1000.0f;

// Names accepted by makeBuiltinEnvironment, for help and error texts.
inline constexpr const char* kBuiltinEnvironmentNames = "sky";

// True for the names makeBuiltinEnvironment accepts.
bool isBuiltinEnvironment(std::string_view name);

// Unit direction of the built-in sky's sun in the world frame.
Vec3 builtinSkySunDirection();

// Renders the named environment (equirect) into `out`; an unknown name is an error listing
// the known ones.
Status makeBuiltinEnvironment(std::string_view name, RgbImage* out);

}  // namespace prt
