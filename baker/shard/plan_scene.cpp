#include "baker/shard/plan_scene.h"

#include <cstdio>
#include <vector>

#include "baker/shard/prepared_scene.h"
#include "baker/shard/shard_container.h"
#include "native/file_io.h"
#include "native/mapped_file.h"
#include "prt/checksum.h"

namespace prt::bake {
namespace {

constexpr std::uint64_t kMaxPreparedSceneBytes = std::uint64_t{1} << 40;

std::string sceneLabel(const BakePlan& plan) {
  return plan.scenePath.empty() ? std::string("the built-in room") : "the scene '" + plan.scenePath + "'";
}

}  // namespace

Status writePreparedScene(const BakePlan& plan, const std::string& planPath, const Scene& scene,
                          std::span<const Uv> atlasUv, std::span<const std::string> inputs) {
  ShardHeader h;
  h.kind = ShardFileKind::kPreparedScene;
  h.planId = plan.id;
  h.vertexEnd = plan.vertices;
  return writeFileAtomically(preparedScenePath(planPath), encodeShardFile(h, encodePreparedScene(scene, atlasUv)), inputs);
}

Status checkSceneFiles(const BakePlan& plan) {
  for (const SceneFile& f : plan.sceneFiles) {
    // A scene file is read whole by the loader too (kMaxGltfFileBytes), so it fits memory.
    std::vector<std::uint8_t> bytes;
    PRT_RETURN_IF_ERROR(readFileBytes(f.path, kMaxGltfFileBytes, &bytes));
    const std::uint32_t crc = crc32c(bytes);
    if (bytes.size() == f.bytes && crc == f.crc32c) continue;
    char text[160];
    std::snprintf(text, sizeof text, " is %zu bytes with CRC-32C %08x; the plan has %llu bytes, %08x): make a new plan",
                  bytes.size(), crc, static_cast<unsigned long long>(f.bytes), f.crc32c);
    return Status::error(StatusCode::kInvalidArgument,
                         sceneLabel(plan) + " changed since the plan was made (its file '" + f.path + "'" + text);
  }
  return Status::ok();
}

Status readPreparedScene(const BakePlan& plan, const std::string& planPath, Scene* scene, std::vector<Uv>* atlasUv) {
  const std::string path = preparedScenePath(planPath);
  const std::string named = "the prepared scene ('" + path + "')";
  MappedFile file;
  if (Status s = MappedFile::open(path, kMaxPreparedSceneBytes, &file); !s.isOk()) {
    if (s.code() == StatusCode::kNotFound) {
      return Status::error(StatusCode::kNotFound, named + " is missing (it is written by prt-bake plan: make the plan again)");
    }
    return Status::error(s.code(), named + ": " + s.message());
  }
  ShardHeader h;
  std::span<const std::uint8_t> payload;
  if (Status s = decodeShardFile(file.bytes(), ShardFileKind::kPreparedScene, &h, &payload); !s.isOk()) {
    return Status::error(s.code(), named + " is corrupt: " + s.message());
  }
  if (h.planId != plan.id) {
    char text[120];
    std::snprintf(text, sizeof text, " belongs to another plan (plan id %08x, this plan is %08x)", h.planId, plan.id);
    return Status::error(StatusCode::kInvalidArgument, named + text);
  }
  // The payload is sceneHash()'s bytes, so its checked CRC is the scene's hash.
  if (h.payloadCrc != plan.sceneHash || h.vertexEnd != plan.vertices) {
    char text[160];
    std::snprintf(text, sizeof text, " holds another scene (scene hash %08x, %llu vertices; the plan has %08x, %llu vertices)",
                  h.payloadCrc, static_cast<unsigned long long>(h.vertexEnd), plan.sceneHash,
                  static_cast<unsigned long long>(plan.vertices));
    return Status::error(StatusCode::kCorrupt, named + text);
  }
  if (Status s = decodePreparedScene(payload, scene, atlasUv); !s.isOk()) return Status::error(s.code(), named + " is corrupt: " + s.message());
  if (scene->positions.size() != plan.vertices || scene->indices.size() / 3 != plan.triangles) {
    return Status::error(StatusCode::kCorrupt, named + " does not have the plan's vertex and triangle counts");
  }
  if (atlasUv->empty() != plan.atlases.empty()) {
    return Status::error(StatusCode::kCorrupt, named + (plan.atlases.empty() ? " holds atlas UVs the plan has no atlas for"
                                                                            : " has no atlas UVs for the plan's texel atlases"));
  }
  scene->name = plan.sceneName;
  return Status::ok();
}

}  // namespace prt::bake
