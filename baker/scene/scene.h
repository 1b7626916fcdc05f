// The baker's in-memory scene: one triangle soup in world space, every glTF primitive
// flattened into it with its node transform applied. Produced by the glTF loader and by
// the built-in default scene; consumed by the transfer passes and written to the asset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prt/glossy_lobe.h"
#include "prt/vec3.h"

namespace prt::bake {

struct Scene {
  std::vector<Vec3> positions;       // world space, metres (glTF units), +y up
  std::vector<Vec3> normals;         // unit length, one per position
  std::vector<Rgb> albedo;           // linear diffuse reflectance in [0, 1], one per position:
                                     // (1 - metallic) x base colour for glTF materials
  // The glossy part (docs/glossy.md), one per position: f0 = mix(0.04, base colour,
  // metallic) (0 with KHR_materials_specular factor 0, and for the built-in diffuse walls),
  // exponent from roughness (specularExponentFromRoughness) or --specular-exponent.
  // Empty for scenes built before materials were read: treated as f0 = 0 (no glossy part).
  std::vector<SpecularMaterial> specular;
  std::vector<std::uint32_t> indices;  // 3 per triangle, counter-clockwise front faces
  std::string name;                  // for catalogues and logs
};

}  // namespace prt::bake
