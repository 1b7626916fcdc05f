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

// `shards` ranges (u64 begin, end; the caller checked they fit) tiling [0, items) in whole
// blocks: contiguous, non-empty, no gap, no overlap.
Status readRanges(ByteReader* r, std::uint32_t shards, std::uint64_t items, const char* label, const char* what,
                  std::vector<VertexRange>* out) {
  std::uint64_t next = 0;
  for (std::uint32_t i = 0; i < shards; ++i) {
    VertexRange v;
    r->u64(&v.begin);
    r->u64(&v.end);
    if (v.begin != next || !(v.end > v.begin) || v.end > items || (v.end != items && v.end % kBlockVertices != 0)) {
      return corrupt(std::string(label) + " " + std::to_string(i) + " covers [" + std::to_string(v.begin) + ", " +
                     std::to_string(v.end) + "), which does not continue the ranges at " + std::to_string(next) +
                     " in whole blocks");
    }
    next = v.end;
    out->push_back(v);
  }
  if (next != items) {
    return corrupt("the " + std::string(label) + "s cover " + std::to_string(next) + " of " + std::to_string(items) + " " + what);
  }
  return Status::ok();
}

}  // namespace

std::uint32_t sceneHash(const Scene& scene, std::span<const Uv> atlasUv) { return crc32c(encodePreparedScene(scene, atlasUv)); }

Status planRanges(std::uint64_t vertices, std::uint32_t shards, std::vector<VertexRange>* out, const char* what) {
  const std::uint64_t blocks = (vertices + kBlockVertices - 1) / kBlockVertices;
  if (shards == 0 || shards > kMaxShards) {
    return Status::error(StatusCode::kInvalidArgument,
                         "shard count " + std::to_string(shards) + " is outside [1, " + std::to_string(kMaxShards) + "]");
  }
  if (shards > blocks) {
    return Status::error(StatusCode::kInvalidArgument, "shard count " + std::to_string(shards) + " exceeds the scene's " +
                                                           std::to_string(blocks) + " blocks of " +
                                                           std::to_string(kBlockVertices) + " " + what);
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
  w.u32(static_cast<std::uint32_t>(plan->atlases.size()));
  for (const TextureAtlas& a : plan->atlases) {
    w.u32(a.width);
    w.u32(a.height);
    w.u32(a.firstTriangle);
    w.u32(a.triangleCount);
  }
  if (!plan->atlases.empty()) {
    w.u64(plan->texelReceivers);
    for (const VertexRange& r : plan->texelShards) {
      w.u64(r.begin);
      w.u64(r.end);
    }
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
  PRT_RETURN_IF_ERROR(readRanges(&r, shards, p.vertices, "shard", "vertices", &p.shards));
  std::uint32_t atlases = 0;
  if (!r.u32(&atlases)) return corrupt("the atlas count is cut short");
  if (atlases > kMaxAssetAtlases || atlases > r.remaining() / 16) return corrupt(std::to_string(atlases) + " atlases do not fit the file");
  std::uint64_t nextTriangle = 0;
  for (std::uint32_t a = 0; a < atlases; ++a) {
    TextureAtlas t;
    r.u32(&t.width);
    r.u32(&t.height);
    r.u32(&t.firstTriangle);
    r.u32(&t.triangleCount);
    // Runs of triangles, one after another, covering them all (as the asset's atlases must).
    if (t.width < 1 || t.width > kMaxAssetAtlasSize || t.height < 1 || t.height > kMaxAssetAtlasSize ||
        t.firstTriangle != nextTriangle || t.triangleCount == 0) {
      return corrupt("atlas " + std::to_string(a) + " (" + std::to_string(t.width) + " x " + std::to_string(t.height) +
                     " over triangles from " + std::to_string(t.firstTriangle) + ") is not a run continuing the atlases at triangle " +
                     std::to_string(nextTriangle));
    }
    nextTriangle += t.triangleCount;
    p.atlases.push_back(t);
  }
  if (atlases > 0) {
    if (nextTriangle != p.triangles) {
      return corrupt("the atlases cover " + std::to_string(nextTriangle) + " of " + std::to_string(p.triangles) + " triangles");
    }
    if (!r.u64(&p.texelReceivers) || p.texelReceivers == 0) return corrupt("the texel receiver count is cut short or 0");
    if (shards > r.remaining() / 16) return corrupt("the texel shard ranges are cut short");
    PRT_RETURN_IF_ERROR(readRanges(&r, shards, p.texelReceivers, "texel shard", "texel receivers", &p.texelShards));
  }
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

std::string texelShardPath(const std::string& planPath, std::uint32_t pass, std::uint32_t shard) {
  return planPath + ".pass" + std::to_string(pass) + ".texels.shard" + std::to_string(shard);
}

std::string texelMergedPassPath(const std::string& planPath, std::uint32_t pass) {
  return planPath + ".pass" + std::to_string(pass) + ".texels.merged";
}

std::string preparedScenePath(const std::string& planPath) { return planPath + ".scene"; }

}  // namespace prt::bake
