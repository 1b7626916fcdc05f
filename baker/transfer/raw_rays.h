// Benchmark references for the direct pass: exactly its rays (same receivers in the same
// order, origins, directions, offsets) handed to Embree in one of several ways and doing
// nothing else (no SH, no hit records), so the direct pass's rate can be set beside Embree's
// own on the same machine in the same run, and the ways of tracing beside one another.
// Public to the benchmarks (bench/bake_bench.cpp).
#pragma once

#include "baker/scene/scene.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/status.h"

namespace prt::bake {

enum class RawRays {
  kSingle,        // one ray at a time (rtcOccluded1 / rtcIntersect1), incoherent: what the direct pass does
  kVertexStream,  // each receiver's fan as one coherent stream (rtcOccluded1M / rtcIntersect1M): the pass before 2026-12
  kPackets8,      // one sample direction over neighbouring receivers, 8 lanes (rtcOccluded8 / rtcIntersect8), coherent
  kPackets16,     // the same, 16 lanes
};
const char* rawRaysName(RawRays mode);

// Traces the direct pass's rays of `scene` under `options` (order, samples, seed, threads;
// receivers in the scene's vertex order, kBlockVertices to a block) the `mode` way, as
// occlusion queries or, with `nearestHit`, nearest-hit ones. out->seconds is the tracing time
// alone (the threads' summed tracing time over the thread count), out->rays the ray count.
// A packet's lanes share one direction and never mix directions; the rays are the same in
// every mode. Returns an error for options the bake would refuse.
Status measureRawRays(const Scene& scene, const BakeOptions& options, RawRays mode, bool nearestHit, PassStats* out);

}  // namespace prt::bake
