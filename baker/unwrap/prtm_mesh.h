// The raw mesh prt-bake exchanges with the Blender unwrap script (PRTM,
// bench/uv_atlas/mesh_raw.md): little-endian counts, float32 positions, optional float32
// UVs, uint32 indices.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// Writes `bytes` to `path` with plain stdio (a scratch file of the unwrap workspace, not an
// output: no temporary, rename or fsync); an error names the path and the system's reason.
Status writeScratchFile(const std::string& path, std::span<const std::uint8_t> bytes);

// Writes positions and indices (3 per triangle) without UVs to `path` (a private scratch file).
Status writePrtmMesh(const std::string& path, std::span<const Vec3> positions, std::span<const std::uint32_t> indices);

// Reads an unwrapped mesh with one vertex per triangle corner (positions, UVs, indices
// 0..3t-1, as the unwrap script writes it) for `triangles` triangles; every count is checked
// against the file's size before anything is allocated, and a file that does not match is an
// error naming it.
Status readPrtmCorners(const std::string& path, std::size_t triangles, std::vector<Vec3>* positions,
                       std::vector<Uv>* uvs);

}  // namespace prt::bake
