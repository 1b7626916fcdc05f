#include "baker/transfer/transfer_bake.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <utility>

#include "baker/transfer/diffuse_bounce.h"
#include "baker/transfer/direct_pass.h"
#include "baker/transfer/embree_scene.h"
#include "baker/transfer/glossy_bake.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/local_sphere.h"
#include "baker/transfer/parallel_for.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

using Block = HitBlock;

}  // namespace

Status bakeTransfer(const Scene& scene, const BakeOptions& o, BakeResult* out) {
  if (Status st = checkOptions(scene, o); !st.isOk()) return st;
  const std::size_t vertexCount = scene.positions.size();

  SampleTable table;
  if (Status s = makeSamples(o, &table); !s.isOk()) return s;
  EmbreeScene embree;
  if (Status s = EmbreeScene::build(scene, &embree); !s.isOk()) return s;

  const int n2 = shCoeffCount(o.order);
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();
  const std::size_t blockCount = (vertexCount + kBlockVertices - 1) / kBlockVertices;

  out->order = o.order;
  out->unshadowed.assign(vertexCount * n2, 0.0f);
  out->shadowed.assign(vertexCount * n2, 0.0f);
  out->interreflected.clear();
  out->bounceEnergy.clear();
  out->passes.clear();
  out->bounces = 0;
  out->verticesOutsideLight = 0;
  out->glossyShadowed.clear();
  out->glossyInterreflected.clear();
  out->glossyBounces = 0;
  out->glossyRankUpdate = {};
  const MatrixPacking glossyPacking = matrixPackingFor(TransferKind::kShadowed, o.lighting.model);
  const std::size_t glossyEntries = matrixEntryCount(o.order, glossyPacking);
  if (o.glossy) {
    useSingleThreadedBlas();
    out->glossyShadowed.assign(vertexCount * glossyEntries, 0.0f);
  }

  // Geometric (winding) normals decide whether a ray hit the front of a triangle.
  const std::vector<Vec3> faceNormal = faceNormals(scene);

  // ---- direct pass: unshadowed + shadowed, recording front-face hits for the bounces
  std::vector<Block> blocks(o.interreflection ? blockCount : 0);
  std::vector<std::uint8_t> outside(vertexCount, 0);
  {
    DirectPassJob job;
    job.embree = &embree;
    job.table = &table;
    job.options = &o;
    job.positions = scene.positions;
    job.normals = scene.normals;
    job.faceNormal = faceNormal;
    job.threads = threads;
    job.unshadowed = out->unshadowed.data();
    job.shadowed = out->shadowed.data();
    job.glossyShadowed = o.glossy ? out->glossyShadowed.data() : nullptr;
    job.glossyEntries = glossyEntries;
    job.blocks = o.interreflection ? &blocks : nullptr;
    job.outside = outside.data();
    out->passes.push_back(runDirectPass(job, &out->glossyRankUpdate));
  }
  for (std::uint8_t x : outside) out->verticesOutsideLight += x;
  if (!o.interreflection) return Status::ok();

  // ---- interreflection: bounce 0 is the shadowed transfer times albedo, RGB
  // A bounce's energy is its area-weighted DC transfer summed over channels: proportional
  // to the power it reflects under constant lighting, so it does not depend on how finely
  // each surface happens to be tessellated.
  const std::vector<double> vertexArea = vertexAreas(scene);
  const std::vector<HitBlockView> views = hitBlockViews(blocks);
  const std::size_t stride = 3 * static_cast<std::size_t>(n2);
  std::vector<float> previous, current(vertexCount * stride);
  double energy0 = 0.0;
  firstBounce(scene, o.order, out->shadowed, vertexArea, &previous, &energy0);
  out->interreflected = previous;
  out->bounceEnergy.push_back(energy0);

  // Glossy interreflection: starts as the shadowed matrix in every channel, full packing;
  // bounce b gathers (glossy_bake.h) from B^{b-1} (`previous` inside the loop below) and
  // M^{b-1}, which beyond the first bounce is kept only at glossy senders and only for one bounce.
  const bool glossyBounce = o.glossy && o.glossyBounces > 0;
  const std::size_t fullEntries = matrixEntryCount(o.order, MatrixPacking::kFull);
  std::vector<std::int32_t> senderIndex;
  std::vector<float> glossyPrevious, glossyCurrent, diffuseFromGlossy;
  if (glossyBounce) {
    diffuseFromGlossy.assign(vertexCount * stride, 0.0f);
    out->glossyInterreflected = expandShadowedMatrices(out->glossyShadowed, o.order, glossyPacking);
    std::size_t senders = 0;
    senderIndex = glossySenderIndex(scene, &senders);
    if (o.glossyBounces > 1) glossyCurrent.assign(senders * 3 * fullEntries, 0.0f);
  }

  for (int bounce = 1; bounce <= o.maxBounces; ++bounce) {
    const bool glossyThisBounce = glossyBounce && bounce <= o.glossyBounces;
    if (glossyThisBounce) {
      GlossyBounceJob job = glossyBounceJob(scene, o, table, bounce, views, previous.data(), &senderIndex);
      job.glossyPrevious = bounce == 1 ? out->glossyShadowed.data() : glossyPrevious.data();
      job.previousPacking = glossyPacking;
      job.glossyCurrent = bounce < o.glossyBounces ? glossyCurrent.data() : nullptr;
      job.interreflected = out->glossyInterreflected.data();
      job.diffuseFromGlossy = diffuseFromGlossy.data();
      out->passes.push_back(gatherGlossyBounce(job));
      out->glossyBounces = bounce;
      if (bounce < o.glossyBounces) std::swap(glossyPrevious, glossyCurrent);
      if (bounce + 1 < o.glossyBounces && glossyCurrent.size() != glossyPrevious.size()) {
        glossyCurrent.assign(glossyPrevious.size(), 0.0f);
      }
      if (bounce == o.glossyBounces) {
        glossyPrevious.clear();
        glossyPrevious.shrink_to_fit();
        glossyCurrent.clear();
        glossyCurrent.shrink_to_fit();
      }
    }
    std::vector<double> blockEnergy(blockCount, 0.0);
    DiffuseBounceJob gather;
    gather.scene = &scene;
    gather.options = &o;
    gather.name = "bounce " + std::to_string(bounce);
    gather.blocks = views;
    gather.previous = previous.data();
    gather.fromGlossy = glossyThisBounce ? diffuseFromGlossy.data() : nullptr;
    gather.vertexArea = vertexArea;
    gather.current = current.data();
    gather.blockEnergy = blockEnergy.data();
    gather.threads = threads;
    const PassStats stats = gatherDiffuseBounce(gather);
    double energy = 0.0;
    for (double e : blockEnergy) energy += e;  // fixed order: deterministic
    for (std::size_t i = 0; i < current.size(); ++i) out->interreflected[i] += current[i];
    out->bounceEnergy.push_back(energy);
    out->bounces = bounce;
    out->passes.push_back(stats);
    std::swap(previous, current);
    if (!(energy > o.bounceThreshold * energy0)) break;
  }
  return Status::ok();
}

}  // namespace prt::bake
