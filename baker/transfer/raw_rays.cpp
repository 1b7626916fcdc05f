#include "baker/transfer/raw_rays.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "baker/transfer/direct_pass.h"
#include "baker/transfer/embree_scene.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/parallel_for.h"

namespace prt::bake {
namespace {

// One block's rays, receiver by receiver as fillRays writes them.
struct BlockRays {
  std::vector<RTCRayHit> rays;        // room for a block's rays; the first first.back() are this block's
  std::vector<std::uint32_t> sample;  // per ray, its sample index (ascending within a receiver)
  std::vector<std::uint32_t> first;   // per receiver, its first ray; plus one
};

RTCIntersectContext makeContext(bool coherent) {
  RTCIntersectContext c;
  rtcInitIntersectContext(&c);
  c.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  return c;
}

inline void packetQuery(const int* valid, RTCScene s, RTCIntersectContext* c, RTCRayHit8* p, bool hit) {
  if (hit) rtcIntersect8(valid, s, c, p);
  else rtcOccluded8(valid, s, c, &p->ray);
}
inline void packetQuery(const int* valid, RTCScene s, RTCIntersectContext* c, RTCRayHit16* p, bool hit) {
  if (hit) rtcIntersect16(valid, s, c, p);
  else rtcOccluded16(valid, s, c, &p->ray);
}

// Packets of one direction k over the block's receivers that trace k, in receiver order;
// lanes left over when the direction runs out stay invalid.
template <int W, typename Packet>
void tracePackets(RTCScene scene, std::size_t sampleCount, bool hit, BlockRays* b) {
  RTCIntersectContext context = makeContext(true);
  const std::size_t receivers = b->first.size() - 1;
  std::vector<std::uint32_t> cursor(b->first.begin(), b->first.end() - 1);
  alignas(64) Packet p;
  alignas(64) int valid[W];
  int lanes = 0;
  auto flush = [&] {
    for (int l = lanes; l < W; ++l) valid[l] = 0;
    packetQuery(valid, scene, &context, &p, hit);
    lanes = 0;
  };
  for (std::size_t k = 0; k < sampleCount; ++k) {
    for (std::size_t r = 0; r < receivers; ++r) {
      const std::uint32_t i = cursor[r];
      if (i == b->first[r + 1] || b->sample[i] != k) continue;
      cursor[r] = i + 1;
      const RTCRay& ray = b->rays[i].ray;
      p.ray.org_x[lanes] = ray.org_x;
      p.ray.org_y[lanes] = ray.org_y;
      p.ray.org_z[lanes] = ray.org_z;
      p.ray.tnear[lanes] = ray.tnear;
      p.ray.dir_x[lanes] = ray.dir_x;
      p.ray.dir_y[lanes] = ray.dir_y;
      p.ray.dir_z[lanes] = ray.dir_z;
      p.ray.time[lanes] = 0.0f;
      p.ray.tfar[lanes] = ray.tfar;
      p.ray.mask[lanes] = ray.mask;
      p.ray.id[lanes] = i;
      p.ray.flags[lanes] = 0;
      p.hit.geomID[lanes] = RTC_INVALID_GEOMETRY_ID;
      p.hit.instID[0][lanes] = RTC_INVALID_GEOMETRY_ID;
      valid[lanes] = -1;
      if (++lanes == W) flush();
    }
    if (lanes > 0) flush();
  }
}

void traceBlock(RTCScene scene, std::size_t sampleCount, RawRays mode, bool hit, BlockRays* b) {
  switch (mode) {
    case RawRays::kSingle: {
      RTCIntersectContext context = makeContext(false);
      for (std::uint32_t i = 0; i < b->first.back(); ++i) {
        if (hit) rtcIntersect1(scene, &context, &b->rays[i]);
        else rtcOccluded1(scene, &context, &b->rays[i].ray);
      }
      return;
    }
    case RawRays::kVertexStream: {
      RTCIntersectContext context = makeContext(true);
      for (std::size_t r = 0; r + 1 < b->first.size(); ++r) {
        RTCRayHit* fan = b->rays.data() + b->first[r];
        const unsigned count = b->first[r + 1] - b->first[r];
        if (hit) rtcIntersect1M(scene, &context, fan, count, sizeof(RTCRayHit));
        else rtcOccluded1M(scene, &context, &fan->ray, count, sizeof(RTCRayHit));
      }
      return;
    }
    case RawRays::kPackets8: return tracePackets<8, RTCRayHit8>(scene, sampleCount, hit, b);
    case RawRays::kPackets16: return tracePackets<16, RTCRayHit16>(scene, sampleCount, hit, b);
  }
}

}  // namespace

const char* rawRaysName(RawRays mode) {
  switch (mode) {
    case RawRays::kSingle: return "single rays";
    case RawRays::kVertexStream: return "one stream per receiver";
    case RawRays::kPackets8: return "packets of 8";
    case RawRays::kPackets16: return "packets of 16";
  }
  return "?";
}

Status measureRawRays(const Scene& scene, const BakeOptions& o, RawRays mode, bool nearestHit, PassStats* out) {
  if (Status st = checkOptions(scene, o); !st.isOk()) return st;
  SampleTable table;
  if (Status st = makeSamples(o, &table); !st.isOk()) return st;
  EmbreeScene embree;
  if (Status st = EmbreeScene::build(scene, &embree); !st.isOk()) return st;
  const float eps = rayOffset(embree);
  const std::size_t vertexCount = scene.positions.size(), sampleCount = table.dirs.size();
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();
  const std::size_t blockCount = (vertexCount + kBlockVertices - 1) / kBlockVertices;
  struct Scratch {
    BlockRays block;
    std::vector<float> weight;
  };
  std::vector<Scratch> scratch(threads);
  for (Scratch& s : scratch) {
    s.block.rays.resize(kBlockVertices * sampleCount);
    s.block.sample.resize(kBlockVertices * sampleCount);
    s.weight.resize(sampleCount);
  }
  std::atomic<std::uint64_t> rays{0};
  std::atomic<std::int64_t> traceNanos{0};
  parallelFor(blockCount, threads, [&](std::size_t block, unsigned thread) {
    Scratch& s = scratch[thread];
    const std::size_t begin = block * kBlockVertices, end = std::min(vertexCount, begin + kBlockVertices);
    BlockRays& b = s.block;
    b.first.assign(1, 0);
    for (std::size_t v = begin; v < end; ++v) {
      const Vec3 n = scene.normals[v];
      const std::uint32_t at = b.first.back();
      const unsigned count =
          fillRays(table, n, n, scene.positions[v] + n * eps, eps, &b.rays[at], &b.sample[at], s.weight.data());
      b.first.push_back(at + count);
    }
    const auto t0 = std::chrono::steady_clock::now();
    traceBlock(embree.handle(), sampleCount, mode, nearestHit, &b);
    traceNanos += std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
    rays += b.first.back();
  });
  out->name = std::string(rawRaysName(mode)) + (nearestHit ? ", nearest hit" : ", occlusion");
  out->seconds = 1e-9 * static_cast<double>(traceNanos.load()) / threads;
  out->rays = rays.load();
  return Status::ok();
}

}  // namespace prt::bake
