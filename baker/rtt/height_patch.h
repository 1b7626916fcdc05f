// A meso-scale patch for radiance transfer textures (docs/bi-scale.md): a periodic height
// field over the unit square with a Lambertian albedo, from a built-in procedural pattern or
// from images.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "prt/image.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// Heights and albedo at size x size grid points (x, y) = (i / size, j / size), i, j < size,
// row-major (j outer), repeating with period 1 in both directions. Heights are in the
// patch's length unit (the patch is 1 wide); albedo is linear, per channel in [0, 1].
struct HeightPatch {
  int size = 0;
  std::vector<float> height;
  std::vector<Rgb> albedo;
  bool coloured = false;  // albedo differs between channels somewhere: an RGB RTT
};

// The built-in patterns' names, for --help and errors: "flat, weave, holes, stucco".
extern const char* const kProceduralPatchNames;

// A built-in pattern at `size` grid points a side (8 .. 2048), grey albedo `albedo`:
// flat (height 0); weave (4 + 4 interleaved threads, cylinders undulating over and under
// each other); holes (a plate with 2 x 2 round pits); stucco (smooth periodic bumps from a
// fixed seed). kInvalidArgument for an unknown name or size.
Status makeProceduralPatch(std::string_view name, int size, float albedo, HeightPatch* out);

// A patch from a height image (its red channel, linear, times `heightScale`, in patch widths;
// square, 8 .. 2048 a side) and optionally an albedo image of the same size (linear RGB in
// [0, 1]; else grey `albedo`). The images are taken as periodic. kInvalidArgument names a
// size mismatch or an albedo texel outside [0, 1] (a reflectance above 1 is not a material;
// nothing is clamped).
Status makeImagePatch(const RgbImage& height, float heightScale, const RgbImage* albedoImage, float albedo, HeightPatch* out);

}  // namespace prt::bake
