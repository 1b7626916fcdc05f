// Loading a glTF 2.0 file (.gltf with external or data-URI buffers, or .glb) into the
// baker's world-space triangle soup (scene.h).
//
// What is read: every TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitive of every node of
// the default scene (all root nodes when the file sets no `scene`), with node transforms
// (matrix or TRS) composed down the hierarchy; normals from NORMAL through the
// inverse-transpose, computed (mesh_normals.h) where missing or unusable; albedo =
// baseColorFactor × baseColorTexture (sRGB, bilinear, wrap modes, KHR_texture_transform) ×
// COLOR_0, as the file says it: glTF's range is [0, 1], and a value outside it (a COLOR_0
// above 1, say) is brought into it with a warning that counts them. Mirroring transforms keep counter-clockwise front faces.
//
// What is not: POINTS and LINES primitives (skipped with a warning; an error if nothing
// else is left), skins and morph targets (the bind pose and base geometry are used, with a
// warning), and any required extension outside kSupportedRequiredExtensions (an error naming
// it, e.g. KHR_draco_mesh_compression). Draco or meshopt data without an uncompressed
// fallback is an error too.
//
// Deviation from the glTF spec: where NORMAL is missing the spec asks for flat normals; the
// baker computes smooth ones over the primitive's shared vertices instead, because
// per-vertex transfer on a smooth mesh exported without normals needs them (a mesh whose
// hard edges are split into separate vertices still gets its hard edges).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "prt/status.h"
#include "baker/scene/scene.h"

namespace prt::bake {

// Scene-size limits, checked before memory is committed: vertex and triangle counts of the
// whole flattened scene (each node instance of a mesh counts again) and the input file size.
inline constexpr std::size_t kMaxSceneVertices = std::size_t{1} << 26;
inline constexpr std::size_t kMaxSceneTriangles = std::size_t{1} << 27;
inline constexpr std::size_t kMaxGltfFileBytes = std::size_t{1} << 31;

// Required extensions the loader honours or may ignore without changing the diffuse result.
inline constexpr std::string_view kSupportedRequiredExtensions[] = {
    "KHR_mesh_quantization", "KHR_texture_transform", "KHR_materials_unlit", "KHR_materials_emissive_strength"};

// Loads `path` (binary glTF is recognised by its magic bytes, not by the name) into `out`,
// which is left empty on failure. Non-fatal problems (skipped primitives, dropped
// degenerate or non-finite triangles, computed or fallback normals, undecodable textures,
// ignored features) are appended to `warnings`, when given and the load succeeds, one line
// each, counted rather than repeated. Errors (kInvalidArgument) name the file and the offending buffer,
// accessor, mesh, node or extension. Never throws.
// `files`, when given and the load succeeds, lists every file it read (the glTF, then its
// external buffers and images as the parser opened them) with its size and CRC-32C, so a
// sharded bake can tell later that the scene changed without loading it again.
struct SceneFile {
  std::string path;  // as opened: absolute when `path` is
  std::uint64_t bytes = 0;
  std::uint32_t crc32c = 0;
};
Status loadGltf(const std::string& path, Scene* out, std::vector<std::string>* warnings = nullptr,
                std::vector<SceneFile>* files = nullptr);

}  // namespace prt::bake
