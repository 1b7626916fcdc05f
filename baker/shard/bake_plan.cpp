#include "baker/shard/bake_plan.h"

#include <algorithm>

#include "baker/shard/byte_io.h"
#include "baker/shard/prepared_scene.h"
#include "baker/shard/shard_container.h"
#include "baker/transfer/hit_record.h"
#include "prt/checksum.h"

namespace prt::bake {
namespace {

constexpr std::size_t kMaxPathBytes = 4096;
constexpr std::uint32_t kMaxArgs = 1024;
constexpr std::size_t kMaxArgBytes = 4096;
constexpr std::uint32_t kMaxSceneFiles = 65536;

Status corrupt(const std::string& what) { return Status::error(StatusCode::kCorrupt, "bake plan: " + what); }

}  // namespace

std::uint32_t sceneHash(const Scene& scene) { return crc32c(encodePreparedScene(scene)); }

Status planRanges(std::uint64_t vertices, std::uint32_t shards, std::vector<VertexRange>* out) {
  const std::uint64_t blocks = (vertices + kBlockVertices - 1) / kBlockVertices;
  if (shards == 0 || shards > kMaxShards) {
    return Status::error(StatusCode::kInvalidArgument,
                         "shard count " + std::to_string(shards) + " is outside [1, " + std::to_string(kMaxShards) + "]");
  }
  if (shards > blocks) {
    return Status::error(StatusCode::kInvalidArgument, "shard count " + std::to_string(shards) + " exceeds the scene's " +
                                                           std::to_string(blocks) + " blocks of " +
                                                           std::to_string(kBlockVertices) + " vertices");
  }
  out->clear();
  for (std::uint64_t i = 0; i < shards; ++i) {
    const std::uint64_t b0 = i * blocks / shards, b1 = (i + 1) * blocks / shards;
    out->push_back({b0 * kBlockVertices, std::min<std::uint64_t>(vertices, b1 * kBlockVertices)});
  }
  return Status::ok();
}

std::vector<std::uint8_t> encodeBakePlan(BakePlan* plan) {
  std::vector<std::uint8_t> payload;
  ByteWriter w(&payload);
  w.string(plan->scenePath);
  w.string(plan->workingDirectory);
  w.u32(static_cast<std::uint32_t>(plan->bakeArgs.size()));
  for (const std::string& a : plan->bakeArgs) w.string(a);
  w.u32(plan->sceneHash);
  w.string(plan->sceneName);
  w.u32(static_cast<std::uint32_t>(plan->sceneFiles.size()));
  for (const SceneFile& f : plan->sceneFiles) {
    w.string(f.path);
    w.u64(f.bytes);
    w.u32(f.crc32c);
  }
  w.u64(plan->vertices);
  w.u64(plan->triangles);
  w.u32(plan->order);
  w.u32(plan->passes);
  w.u32(static_cast<std::uint32_t>(plan->shards.size()));
  for (const VertexRange& r : plan->shards) {
    w.u64(r.begin);
    w.u64(r.end);
  }
  ShardHeader h;
  h.kind = ShardFileKind::kPlan;
  h.vertexEnd = plan->vertices;
  std::vector<std::uint8_t> file = encodeShardFile(h, payload);
  plan->id = crc32c(file);
  return file;
}

Status decodeBakePlan(std::span<const std::uint8_t> bytes, BakePlan* plan) {
  ShardHeader h;
  std::span<const std::uint8_t> payload;
  PRT_RETURN_IF_ERROR(decodeShardFile(bytes, ShardFileKind::kPlan, &h, &payload));
  ByteReader r(payload);
  BakePlan p;
  std::uint32_t args = 0, shards = 0;
  if (!r.string(kMaxPathBytes, &p.scenePath) || !r.string(kMaxPathBytes, &p.workingDirectory) || !r.u32(&args)) {
    return corrupt("the scene path, working directory or argument count is cut short or too long");
  }
  if (args > kMaxArgs) return corrupt(std::to_string(args) + " bake arguments (at most " + std::to_string(kMaxArgs) + ")");
  p.bakeArgs.resize(args);
  for (std::string& a : p.bakeArgs) {
    if (!r.string(kMaxArgBytes, &a)) return corrupt("a bake argument is cut short or too long");
  }
  std::uint32_t files = 0;
  if (!r.u32(&p.sceneHash) || !r.string(kMaxPathBytes, &p.sceneName) || !r.u32(&files)) {
    return corrupt("the scene hash, name or file count is cut short or too long");
  }
  if (files > kMaxSceneFiles || files > r.remaining() / 16) return corrupt(std::to_string(files) + " scene files do not fit the file");
  p.sceneFiles.resize(files);
  for (SceneFile& f : p.sceneFiles) {
    if (!r.string(kMaxPathBytes, &f.path) || !r.u64(&f.bytes) || !r.u32(&f.crc32c)) return corrupt("a scene file's entry is cut short");
  }
  if (!r.u64(&p.vertices) || !r.u64(&p.triangles) || !r.u32(&p.order) || !r.u32(&p.passes) ||
      !r.u32(&shards)) {
    return corrupt("the scene and pass fields are cut short");
  }
  if (p.order < 2 || p.order > 8) return corrupt("order " + std::to_string(p.order) + " is outside [2, 8]");
  if (p.passes < 1 || p.passes > 65) return corrupt(std::to_string(p.passes) + " passes (1 to 65)");
  if (shards < 1 || shards > kMaxShards || shards > r.remaining() / 16) {
    return corrupt(std::to_string(shards) + " shards do not fit the file");
  }
  std::uint64_t next = 0;
  for (std::uint32_t i = 0; i < shards; ++i) {
    VertexRange v;
    r.u64(&v.begin);
    r.u64(&v.end);
    // Contiguous, non-empty, block-aligned: no gap, no overlap.
    if (v.begin != next || !(v.end > v.begin) || v.end > p.vertices || (v.end != p.vertices && v.end % kBlockVertices != 0)) {
      return corrupt("shard " + std::to_string(i) + " covers [" + std::to_string(v.begin) + ", " + std::to_string(v.end) +
                     "), which does not continue the ranges at " + std::to_string(next) + " in whole blocks");
    }
    next = v.end;
    p.shards.push_back(v);
  }
  if (next != p.vertices) return corrupt("the shards cover " + std::to_string(next) + " of " + std::to_string(p.vertices) + " vertices");
  if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the shard ranges");
  p.id = crc32c(bytes);
  *plan = std::move(p);
  return Status::ok();
}

std::string shardPath(const std::string& planPath, std::uint32_t pass, std::uint32_t shard) {
  return planPath + ".pass" + std::to_string(pass) + ".shard" + std::to_string(shard);
}

std::string mergedPassPath(const std::string& planPath, std::uint32_t pass) {
  return planPath + ".pass" + std::to_string(pass) + ".merged";
}

std::string preparedScenePath(const std::string& planPath) { return planPath + ".scene"; }

}  // namespace prt::bake
