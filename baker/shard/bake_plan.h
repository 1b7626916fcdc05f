// A sharded bake's plan (docs/scale-out.md): which scene, with which bake arguments, split
// into which vertex ranges, over how many passes. Every shard and merge reads it, the
// prepared scene stored beside it (prepared_scene.h) and checks that the scene's files are
// still the ones planned (size and CRC-32C of each), so a changed scene is refused instead of
// baked into a mixture.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "baker/scene/gltf_loader.h"
#include "baker/scene/scene.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

inline constexpr std::uint32_t kMaxShards = 65536;

struct VertexRange {
  std::uint64_t begin = 0, end = 0;
};

struct BakePlan {
  std::string scenePath;               // absolute; empty for the built-in room (--default)
  std::vector<std::string> bakeArgs;   // the bake's arguments as given to `plan` (no --shards)
  std::string workingDirectory;        // where `plan` ran: relative paths in bakeArgs are from there
  std::uint32_t sceneHash = 0;         // sceneHash() of the prepared scene
  std::string sceneName;               // the loaded scene's name (the asset's default name)
  std::vector<SceneFile> sceneFiles;   // every file the scene's load read; none for the built-in room
  std::uint64_t vertices = 0, triangles = 0;
  std::uint32_t order = 0;
  std::uint32_t passes = 1;            // 1 (direct) + the bounce limit when interreflection is stored
  std::vector<VertexRange> shards;     // contiguous, block-aligned, covering [0, vertices)
  // Texel bakes (--texels) only, else empty and 0: the asset's atlases over the prepared
  // scene's triangles (picked or generated once, here), how many texel receivers their
  // rasterisation gives, and each shard's receiver range (block-aligned, as `shards`).
  std::vector<TextureAtlas> atlases;
  std::uint64_t texelReceivers = 0;
  std::vector<VertexRange> texelShards;
  std::uint32_t id = 0;                // CRC-32C of the plan file (set by encode and decode)
};

// CRC-32C of the prepared scene's vertex count, positions, normals, albedo, indices and, when
// it has them, its vertices' specular materials (glossy bakes) and atlas UVs (texel bakes):
// of encodePreparedScene's bytes.
std::uint32_t sceneHash(const Scene& scene, std::span<const Uv> atlasUv = {});

// `shards` contiguous ranges of whole 64-item blocks over `vertices` items, sizes differing by
// at most one block. kInvalidArgument when shards is 0, above kMaxShards, or above the block
// count (naming both, the items as `what`: "vertices", "texel receivers").
Status planRanges(std::uint64_t vertices, std::uint32_t shards, std::vector<VertexRange>* out,
                  const char* what = "vertices");

// The plan file's bytes; sets plan->id.
std::vector<std::uint8_t> encodeBakePlan(BakePlan* plan);

// Reads a plan file's bytes, checking the container and that the ranges tile the vertices
// in whole blocks. Errors name the problem (kTruncated, kBadMagic, kChecksumMismatch, kCorrupt).
Status decodeBakePlan(std::span<const std::uint8_t> bytes, BakePlan* plan);

// Where shard `shard` of pass `pass` and merged pass `pass` of the plan at `planPath` live:
// beside the plan, "<plan>.pass<K>.shard<i>" and "<plan>.pass<K>.merged".
std::string shardPath(const std::string& planPath, std::uint32_t pass, std::uint32_t shard);
std::string mergedPassPath(const std::string& planPath, std::uint32_t pass);
// A texel plan's files of the texel series, beside the vertex ones: "<plan>.pass<K>.texels.shard<i>"
// and "<plan>.pass<K>.texels.merged".
std::string texelShardPath(const std::string& planPath, std::uint32_t pass, std::uint32_t shard);
std::string texelMergedPassPath(const std::string& planPath, std::uint32_t pass);
// "<plan>.scene": the prepared scene `plan` writes beside the plan.
std::string preparedScenePath(const std::string& planPath);

}  // namespace prt::bake
