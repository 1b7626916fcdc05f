// From glTF's metallic-roughness parameters to the glossy PRT material (docs/glossy.md):
// the base colour splits into a Lambertian part and a Phong lobe about the mirror direction.
//   diffuse albedo  = (1 - metallic) x base colour
//   specular f0     = (1 - metallic) x dielectricF0 + metallic x base colour
//   lobe exponent s = specularExponentFromRoughness(roughness), or one fixed s for all
// A diffuse-only bake never calls this: there every surface is Lambertian with its base
// colour (metals included), as before glossy transfer existed.
#pragma once

#include <optional>

#include "baker/scene/scene.h"
#include "prt/glossy_lobe.h"
#include "prt/status.h"

namespace prt::bake {

struct GlossyMaterialOptions {
  std::optional<double> exponent;                   // --specular-exponent: the same s everywhere
  double maxExponent = kDefaultMaxSpecularExponent;  // --max-specular-exponent: roughness 0's s
};

// Rewrites scene->albedo and fills scene->specular from scene->pbr (empty pbr: every vertex
// a rough dielectric, PbrVertex's defaults). Errors (kInvalidArgument): an exponent that is
// negative or not finite, pbr of the wrong size, or parameters outside [0, 1].
Status applyGlossyMaterials(const GlossyMaterialOptions& options, Scene* scene);

}  // namespace prt::bake
