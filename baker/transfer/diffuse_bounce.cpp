#include "baker/transfer/diffuse_bounce.h"

#include <algorithm>
#include <chrono>

#include "baker/transfer/bounce_gather.h"
#include "baker/transfer/direct_pass.h"
#include "baker/transfer/parallel_for.h"
#include "prt/checksum.h"
#include "prt/sh_basis.h"

namespace prt::bake {

std::vector<double> vertexAreas(const Scene& scene) {
  const std::vector<Vec3> faceNormal = faceNormals(scene);
  std::vector<double> vertexArea(scene.positions.size(), 0.0);
  for (std::size_t t = 0; t < faceNormal.size(); ++t) {
    const double third = 0.5 * length(faceNormal[t]) / 3.0;
    for (int c = 0; c < 3; ++c) vertexArea[scene.indices[3 * t + c]] += third;
  }
  return vertexArea;
}

void firstBounce(const Scene& scene, int order, std::span<const float> shadowed, std::span<const double> vertexArea,
                 std::vector<float>* bounce0, double* energy0) {
  const int n2 = shCoeffCount(order);
  const std::size_t stride = 3 * static_cast<std::size_t>(n2), vertexCount = scene.positions.size();
  bounce0->assign(vertexCount * stride, 0.0f);
  double energy = 0.0;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const float rho[3] = {scene.albedo[v].r, scene.albedo[v].g, scene.albedo[v].b};
    for (int c = 0; c < 3; ++c) {
      for (int i = 0; i < n2; ++i) (*bounce0)[v * stride + c * n2 + i] = rho[c] * shadowed[v * n2 + i];
      energy += vertexArea[v] * (*bounce0)[v * stride + c * n2];
    }
  }
  *energy0 = energy;
}

PassStats gatherDiffuseBounce(const DiffuseBounceJob& job) {
  const Scene& scene = *job.scene;
  const int n2 = shCoeffCount(job.options->order);
  const std::size_t stride = 3 * static_cast<std::size_t>(n2), vertexCount = scene.positions.size();
  const std::size_t rangeBegin = job.firstBlock * kBlockVertices;
  const std::size_t rangeEnd = std::min(vertexCount, (job.firstBlock + job.blocks.size()) * kBlockVertices);
  const auto t0 = std::chrono::steady_clock::now();
  ProgressReporter progress(*job.options, job.name, rangeEnd - rangeBegin);
  parallelFor(job.blocks.size(), job.threads, [&](std::size_t j, unsigned) {
    const HitBlockView& rec = job.blocks[j];
    const std::size_t begin = (job.firstBlock + j) * kBlockVertices, end = std::min(vertexCount, begin + kBlockVertices);
    if (job.checkTriangles > 0) {
      if (!hitRecordsFit(rec.hits, job.checkTriangles)) {
        job.badBlocks[j] = 1;
        return;
      }
      if (job.hitCrc) job.hitCrc[j] = crc32c(hitRecordBytes(rec.hits));
    }
    std::vector<float> gathered(stride);
    WeightedRows terms;
    double e = 0.0;
    for (std::size_t v = begin; v < end; ++v) {
      std::fill(gathered.begin(), gathered.end(), 0.0f);
      const std::size_t local = v - begin;
      gatherHits(rec.hits.subspan(rec.hitStart[local], rec.hitStart[local + 1] - rec.hitStart[local]),
                 scene.indices.data(), job.previous, stride, gathered.data(), &terms);
      if (job.fromGlossy) {
        const float* fromGlossy = &job.fromGlossy[(v - rangeBegin) * stride];
        for (std::size_t i = 0; i < stride; ++i) gathered[i] += fromGlossy[i];
      }
      const float rho[3] = {scene.albedo[v].r, scene.albedo[v].g, scene.albedo[v].b};
      float* dst = &job.current[(v - rangeBegin) * stride];
      for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < n2; ++i) dst[c * n2 + i] = rho[c] * gathered[c * n2 + i];
        e += job.vertexArea[v] * dst[c * n2];
      }
    }
    job.blockEnergy[j] = e;
    progress.add(end - begin, 0);
  });
  return {job.name, secondsSince(t0), 0};
}

}  // namespace prt::bake
