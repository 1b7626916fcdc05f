#include "baker/transfer/transfer_range.h"

#include <algorithm>
#include <string>

#include "baker/transfer/diffuse_bounce.h"
#include "baker/transfer/direct_pass.h"
#include "baker/transfer/embree_scene.h"
#include "baker/transfer/glossy_bake.h"
#include "baker/transfer/parallel_for.h"
#include "prt/checksum.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

// bakeTransfer's glossy gather of bounce b over the range's blocks (sizes checked here, the
// hit records by the caller): M^b into *glossy.bounce, and what the diffuse receivers gather
// from the glossy senders into *fromGlossy ([vertex of the range][channel][coefficient]).
Status gatherGlossyRange(const Scene& scene, const BakeOptions& o, int bounce, std::size_t firstBlock,
                         std::span<const HitBlockView> blocks, std::span<const float> diffusePrevious,
                         const GlossyRangeBounce& glossy, std::vector<float>* fromGlossy, PassStats* stats) {
  const std::size_t vertexCount = scene.positions.size(), n2 = static_cast<std::size_t>(shCoeffCount(o.order));
  const std::size_t begin = firstBlock * kBlockVertices;
  const std::size_t end = std::min(vertexCount, (firstBlock + blocks.size()) * kBlockVertices);
  const MatrixPacking packing = matrixPackingFor(TransferKind::kShadowed, o.lighting.model);
  std::size_t senders = 0;
  const std::vector<std::int32_t> senderIndex = glossySenderIndex(scene, &senders);
  const std::size_t perSender = bounce == 1 ? matrixEntryCount(o.order, packing) : 3 * n2 * n2;
  if (!o.glossy || bounce > o.glossyBounces || glossy.previous.size() != senders * perSender || !glossy.bounce) {
    return Status::error(StatusCode::kInvalidArgument, "glossy bounce " + std::to_string(bounce) + ": the senders' matrices (" +
                                                           std::to_string(glossy.previous.size()) + " floats) do not fit " +
                                                           std::to_string(senders) + " senders of this bake");
  }
  useSingleThreadedBlas();
  SampleTable table;
  PRT_RETURN_IF_ERROR(makeSamples(o, &table));
  fromGlossy->assign((end - begin) * 3 * n2, 0.0f);
  glossy.bounce->assign((end - begin) * 3 * n2 * n2, 0.0f);
  GlossyBounceJob job = glossyBounceJob(scene, o, table, bounce, blocks, diffusePrevious.data(), &senderIndex);
  job.firstBlock = firstBlock;
  job.glossyPrevious = glossy.previous.data();
  job.previousPacking = packing;
  job.previousBySender = true;
  job.bounceMatrices = glossy.bounce->data();
  job.diffuseFromGlossy = fromGlossy->data();
  *stats = gatherGlossyBounce(job);
  return Status::ok();
}

Status badRecords(std::size_t block, std::size_t triangles) {
  return Status::error(StatusCode::kCorrupt, "a hit record of block " + std::to_string(block) + " names a triangle not below " +
                                                 std::to_string(triangles) + " or has a weight that is not finite");
}

}  // namespace

Status bakeDirectRange(const Scene& scene, const BakeOptions& o, std::size_t begin, std::size_t end, DirectRange* out) {
  PRT_RETURN_IF_ERROR(checkOptions(scene, o));
  const std::size_t vertexCount = scene.positions.size();
  if (begin % kBlockVertices != 0 || !(begin < end) || end > vertexCount) {
    return Status::error(StatusCode::kInvalidArgument, "vertex range [" + std::to_string(begin) + ", " +
                                                           std::to_string(end) + ") is not a block-aligned range of the scene's " +
                                                           std::to_string(vertexCount) + " vertices");
  }
  // As bakeTransfer: the baker's threads split the vertices, and the kernel's bits stay fixed.
  if (o.glossy) useSingleThreadedBlas();
  SampleTable table;
  PRT_RETURN_IF_ERROR(makeSamples(o, &table));
  EmbreeScene embree;
  PRT_RETURN_IF_ERROR(EmbreeScene::build(scene, &embree));
  const int n2 = shCoeffCount(o.order);
  const std::size_t count = end - begin;
  out->unshadowed.assign(count * n2, 0.0f);
  out->shadowed.assign(count * n2, 0.0f);
  out->blocks.clear();
  const std::size_t glossyEntries = matrixEntryCount(o.order, matrixPackingFor(TransferKind::kShadowed, o.lighting.model));
  out->glossyShadowed.assign(o.glossy ? count * glossyEntries : 0, 0.0f);
  const std::vector<Vec3> faceNormal = faceNormals(scene);
  std::vector<std::uint8_t> outside(count, 0);
  DirectPassJob job;
  job.embree = &embree;
  job.table = &table;
  job.options = &o;
  // Receivers are the range's vertices; blocks of the range start at `begin`, a block
  // boundary, so each block holds the same vertices as in the whole-scene pass.
  job.positions = std::span<const Vec3>(scene.positions).subspan(begin, count);
  job.normals = std::span<const Vec3>(scene.normals).subspan(begin, count);
  job.faceNormal = faceNormal;
  job.threads = o.threads ? o.threads : defaultThreadCount();
  job.unshadowed = out->unshadowed.data();
  job.shadowed = out->shadowed.data();
  job.glossyShadowed = o.glossy ? out->glossyShadowed.data() : nullptr;
  job.glossyEntries = glossyEntries;
  job.blocks = o.interreflection ? &out->blocks : nullptr;
  job.outside = outside.data();
  GlossyKernelStats unused;
  out->stats = runDirectPass(job, &unused);
  out->verticesOutsideLight = 0;
  for (std::uint8_t x : outside) out->verticesOutsideLight += x;
  return Status::ok();
}

Status gatherBounceRange(const Scene& scene, const BakeOptions& o, int bounce, std::size_t firstBlock,
                         std::span<const HitBlockView> blocks, std::span<const float> previous,
                         const GlossyRangeBounce* glossy, std::vector<float>* current, std::vector<double>* blockEnergy,
                         std::vector<std::uint32_t>* hitCrc, PassStats* stats) {
  const std::size_t vertexCount = scene.positions.size();
  const std::size_t stride = 3 * static_cast<std::size_t>(shCoeffCount(o.order));
  const std::size_t begin = firstBlock * kBlockVertices;
  const std::size_t end = std::min(vertexCount, (firstBlock + blocks.size()) * kBlockVertices);
  if (bounce < 1 || blocks.empty() || begin >= vertexCount || previous.size() != vertexCount * stride ||
      scene.albedo.size() != vertexCount) {
    return Status::error(StatusCode::kInvalidArgument, "bounce " + std::to_string(bounce) + " over blocks " +
                                                           std::to_string(firstBlock) + "+" + std::to_string(blocks.size()) +
                                                           " does not fit the scene");
  }
  const std::size_t triangles = scene.indices.size() / 3;
  if (hitCrc) hitCrc->assign(blocks.size(), 0);
  for (std::size_t j = 0; j < blocks.size(); ++j) {
    const HitBlockView& b = blocks[j];
    const std::size_t vertices = std::min(kBlockVertices, end - (begin + j * kBlockVertices));
    if (b.hitStart.size() != vertices + 1 || b.hitStart.front() != 0 || b.hitStart.back() != b.hits.size()) {
      return Status::error(StatusCode::kCorrupt, "hit records of block " + std::to_string(firstBlock + j) + " do not fit its vertices");
    }
    // The records' values (a sharded bake's decoder checks only sizes): the triangle is an
    // index, so it must be in range, and a weight that is not finite would make every later
    // bounce NaN. A glossy bounce reads them first, so they are checked here; a diffuse
    // one checks each block in the gather, while it is in cache.
    if (glossy && !hitRecordsFit(b.hits, triangles)) return badRecords(firstBlock + j, triangles);
    if (glossy && hitCrc) (*hitCrc)[j] = crc32c(hitRecordBytes(b.hits));
    if (glossy && (b.hitSample.size() != b.hits.size() ||
                   std::any_of(b.hitSample.begin(), b.hitSample.end(), [&](std::uint32_t k) { return k >= o.samples; }))) {
      return Status::error(StatusCode::kCorrupt, "the hits' sample indices of block " + std::to_string(firstBlock + j) +
                                                     " do not fit its hits or the " + std::to_string(o.samples) + " samples");
    }
  }
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();
  std::vector<float> fromGlossy;
  PassStats glossyStats;
  if (glossy) PRT_RETURN_IF_ERROR(gatherGlossyRange(scene, o, bounce, firstBlock, blocks, previous, *glossy, &fromGlossy, &glossyStats));
  const std::vector<double> vertexArea = vertexAreas(scene);
  current->assign((end - begin) * stride, 0.0f);
  blockEnergy->assign(blocks.size(), 0.0);
  DiffuseBounceJob job;
  job.scene = &scene;
  job.options = &o;
  job.name = "bounce " + std::to_string(bounce);
  job.firstBlock = firstBlock;
  job.blocks = blocks;
  job.previous = previous.data();
  job.fromGlossy = glossy ? fromGlossy.data() : nullptr;
  job.vertexArea = vertexArea;
  job.current = current->data();
  job.blockEnergy = blockEnergy->data();
  job.threads = threads;
  std::vector<std::uint8_t> badBlocks;
  if (!glossy) {
    badBlocks.assign(blocks.size(), 0);
    job.checkTriangles = triangles;
    job.badBlocks = badBlocks.data();
    job.hitCrc = hitCrc ? hitCrc->data() : nullptr;
  }
  *stats = gatherDiffuseBounce(job);
  for (std::size_t j = 0; j < badBlocks.size(); ++j) {
    if (badBlocks[j]) return badRecords(firstBlock + j, triangles);
  }
  stats->seconds += glossyStats.seconds;
  return Status::ok();
}

}  // namespace prt::bake
