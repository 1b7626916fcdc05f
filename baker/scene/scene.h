// The baker's in-memory scene: one triangle soup in world space, every glTF primitive
// flattened into it with its node transform applied. Produced by the glTF loader and by
// the built-in default scene; consumed by the transfer passes and written to the asset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "baker/scene/gltf_texture.h"
#include "prt/glossy_lobe.h"
#include "prt/vec3.h"

namespace prt::bake {

// glTF 2.0 metallic-roughness parameters at a vertex (defaults: a rough dielectric).
struct PbrVertex {
  float metallic = 0.0f;   // [0, 1]
  float roughness = 1.0f;  // perceptual roughness, [0, 1]
  // Specular reflectance at normal incidence of the dielectric part: 0.04 by default, scaled
  // by KHR_materials_specular (specularFactor x specularColorFactor, capped at 1 per the
  // extension); 0 makes the dielectric part purely Lambertian.
  Rgb dielectricF0{0.04f, 0.04f, 0.04f};
  // Grazing reflectance of the dielectric part: KHR_materials_specular's specularFactor
  // (1 without it), which scales F90 as well as F0.
  float dielectricF90 = 1.0f;
};

// A texture coordinate as glTF stores it: u to the right, v down from the image's top.
struct Uv {
  float u = 0, v = 0;
};

// A tangent-space normal map (glTF material.normalTexture). Its texels are the stored 8-bit
// values / 255 (linear data, not sRGB); the tangent-space normal at a texel is
// normalize((2 rgb - 1) * (scale, scale, 1)), +x along the vertex tangent, +y along the
// bitangent, +z along the interpolated vertex normal (docs/transfer-textures.md, "Normal maps").
struct NormalMap {
  LinearTexture texture;
  WrapMode wrapS = WrapMode::kRepeat;
  WrapMode wrapT = WrapMode::kRepeat;
  float scale = 1.0f;  // normalTexture.scale
};

// A vertex's tangent frame as glTF's TANGENT stores it: `direction` unit and orthogonal to the
// vertex normal, bitangent = handedness * cross(normal, direction), handedness +1 or -1.
struct Tangent {
  Vec3 direction{1, 0, 0};
  float handedness = 1.0f;
};

struct Scene {
  std::vector<Vec3> positions;       // world space, metres (glTF units), +y up
  std::vector<Vec3> normals;         // unit length, one per position
  std::vector<Rgb> albedo;           // linear diffuse reflectance in [0, 1], one per position:
                                     // the base colour, until applyGlossyMaterials splits it
  // The metallic-roughness material of each vertex (glTF's), one per position or empty
  // (unknown: a rough dielectric). Only a glossy bake reads it (glossy_materials.h).
  std::vector<PbrVertex> pbr;
  // The glossy part (docs/glossy.md), one per position, filled by applyGlossyMaterials (or
  // by hand in tests); empty: no glossy part (f0 = 0).
  std::vector<SpecularMaterial> specular;
  // TEXCOORD_0 and TEXCOORD_1 as the file stores them (no KHR_texture_transform: an atlas is
  // the raw attribute), one per position, or empty when some triangle primitive lacks the
  // set or stores it in a type glTF does not allow; texcoordAbsent[k] then says why (empty
  // when the set is present). Candidates for the transfer-texture atlas (uv_atlas_choice.h);
  // a generated atlas (baker/unwrap/seam_split.h) takes the lightmap slot, texcoord[1].
  std::vector<Uv> texcoord[2];
  std::string texcoordAbsent[2];
  // Normal maps, read only by the texel bake (a vertex cannot resolve them). normalMapOf is
  // per position (-1: none) or empty (no vertex has one); where it is not empty,
  // normalMapUv (the map's texture coordinates, KHR_texture_transform applied) and tangents
  // are per position too. All vertices of a triangle share one map (one glTF primitive).
  std::vector<NormalMap> normalMaps;
  std::vector<std::int32_t> normalMapOf;
  std::vector<Uv> normalMapUv;
  std::vector<Tangent> tangents;
  std::vector<std::uint32_t> indices;  // 3 per triangle, counter-clockwise front faces
  // The objects the triangles belong to (a glTF node's instance of its mesh, or a part of the
  // built-in scene): triangleObject is per triangle, an index into objectNames, or empty (the
  // whole scene is one object). Texture sets (PRTT §4.3) give each object its own atlas, so
  // instances of one mesh, which share UVs, do not overlap (docs/transfer-textures.md).
  std::vector<std::uint32_t> triangleObject;
  std::vector<std::string> objectNames;
  std::string name;                  // for catalogues and logs
};

}  // namespace prt::bake
