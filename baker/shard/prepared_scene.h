// The prepared scene of a sharded bake (docs/scale-out.md, "Files"): the arrays a vertex bake
// and its asset read, after the glossy material split and optimizeMeshOrder, stored once by
// `plan` so that no shard or merge loads and prepares the glTF again (0.24 s a process on the
// dragon res2, paid by every shard and merge of every pass before this file existed).
//
// The payload is exactly the bytes sceneHash() hashes, so its CRC-32C (the container's payload
// checksum) is the plan's scene hash: a prepared scene of another scene cannot pass for this one.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/status.h"

namespace prt::bake {

// The payload: u64 vertices, positions, normals, albedo (f32 triples), u64 index count, the
// indices (u32), u32 flags, then with glossy materials (flag 1) each vertex's f0 r, g, b, f90,
// exponent (f32), then with a texel bake's atlas (flag 2, `atlasUv` not empty) each vertex's atlas u, v (f32).
std::vector<std::uint8_t> encodePreparedScene(const Scene& scene, std::span<const Uv> atlasUv = {});

// Reads a payload into the scene's positions, normals, albedo, indices and specular materials
// (other fields cleared) and, when given, *atlasUv (empty without). kCorrupt naming the problem
// when a size does not fit the bytes, the flags are unknown, the index count is not a multiple
// of 3 or an index is not below the vertex count.
Status decodePreparedScene(std::span<const std::uint8_t> payload, Scene* scene, std::vector<Uv>* atlasUv = nullptr);

}  // namespace prt::bake
