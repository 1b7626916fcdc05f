// The lightmap-atlas generator: Blender's Smart UV Project run headless on the scene's
// world-space triangles, inside a check-and-retry loop, because Blender 3.4's island margin is
// not in texels (docs/transfer-textures.md, "Generating an atlas"). Library code, so a cluster
// job generates atlases the way prt-bake does.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/scene/uv_atlas_check.h"
#include "prt/status.h"

namespace prt::bake {

inline constexpr double kDefaultUnwrapTimeoutSeconds = 600.0;
inline constexpr int kDefaultUnwrapAttempts = 4;

struct UvUnwrapOptions {
  int size = 512;    // atlas side in texels the layout must be valid at (with sideFromLayout: a first guess)
  int padding = 2;   // gutter texels required between charts at that side
  // When set, the side follows each layout (prt-bake's --texels-per-unit: texels per metre
  // depend on the UV area) instead of `size`; it gets the unwrapped scene (atlas in texcoord[1]).
  std::function<Status(const Scene& unwrapped, int* side)> sideFromLayout;
  std::string blender = "blender";  // the executable: a path, or a name looked up on PATH
  double timeoutSeconds = kDefaultUnwrapTimeoutSeconds;  // per Blender run; past it Blender is killed
  int maxAttempts = kDefaultUnwrapAttempts;  // Blender runs, each with twice the previous margin
  std::function<void(const std::string&)> log;  // one line per attempt, for progress output
};

struct UvUnwrapAttempt {
  double margin = 0.0;   // island_margin passed to Blender (UV units)
  int side = 0;          // the side the layout was checked at
  double seconds = 0.0;  // the Blender run, start-up included
  std::string result;    // the check's summary ("valid", or its counts)
};

struct UvUnwrapReport {
  std::vector<UvUnwrapAttempt> attempts;
  int side = 0;        // the side of the accepted layout
  UvAtlasReport atlas;  // its check (valid)
  double seconds = 0.0;  // the whole generation
};

// Lays out a valid atlas of `scene` at options' side and padding (Blender, in a private temp
// directory removed on every path), and returns the scene with vertices split at chart seams
// and the atlas as texcoord[1] in *out. The same scene and options give the same bytes.
// Errors name the problem: kNotFound when Blender is missing (how to install it), kIoError
// when it cannot be run, kResourceExhausted past the time limit, kUnavailable when Blender
// fails (its last output lines), kInvalidArgument when the atlas is still invalid after the
// attempts (the check's first problem, with the advice that fits it). One call at a time per
// process (kInternal otherwise): the signal cleanup tracks one scratch directory and child.
Status unwrapUvAtlas(const Scene& scene, const UvUnwrapOptions& options, Scene* out, UvUnwrapReport* report);

}  // namespace prt::bake
