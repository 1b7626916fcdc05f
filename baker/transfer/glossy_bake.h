// Glossy transfer matrices (docs/glossy.md; Fujita & Kanai 2004 §2.2, Sloan et al. 2002):
// the kernels bakeTransfer runs when BakeOptions::glossy is set. Private to prt_transfer and
// the shard library (baker/shard), whose bounce shards and merges run the same kernels.
//
// Shadowed matrix, accumulated in the direct pass from the same rays (w = 4pi/N):
//   distant  (M_x)_ij = w sum_{k visible, n.w_k > 0} y_i(w_k) y_j(w_k)
//            = a rank-K update M = w Y^T Y over the K visible samples (BLAS ssyrk, lower
//            triangle only; stored kSymmetric);
//   local    (M_x)_ij = w sum_k V_k [n.w_k > 0] q_k y_i(w_k) y_j(w'_k), q_k the remap weight
//            of the diffuse local transfer (1 area form, 1/cos theta' paper form), with no
//            cosine: the matrix maps lighting to incident radiance. Not symmetric: a gemm,
//            stored kFull.
// Interreflected matrix, bounce b >= 1 (3 channels, kFull), gathered over the direct pass's
// front-face hits h (direction w_h, hit point q_h on triangle t_h with barycentrics):
//   (M_x)^b_ij = w sum_h y_i(w_h) row^{b-1}_j(q_h),  row(q) = sum_corners bary * row(corner),
//   row^{b-1}_{c,j}(u) = B^{b-1}_{c,j}(u)                                   (diffuse sender)
//                      + F_c(n_u.v) sum_k g_l(k)(s_u) (M^{b-1}_{u,c})_kj y_k(R_u)  (glossy sender: f0 or f90 > 0)
// with v = -w_h (from q toward x), R_u = reflectView(v, n_u), F Schlick with the sender's f0,
// g the Phong band scales, B^{b-1} the diffuse bounce vector of the interreflection pass
// (B^0 = albedo x shadowed; albedo folded in) and M^0 the shadowed matrix. Evaluating each
// corner's outgoing radiance with its own normal and material, then interpolating, is how
// the diffuse bounces interpolate B.
// Diffuse receivers, bounce b <= glossyBounces: the diffuse transfer's bounce b
// (BakeResult::interreflected) gathers, besides B^{b-1}, the glossy part of the same rows
// with the receiver's cosine weight:
//   B^b_{x,c,j} = rho_c(x) sum_h Hit::weight_h [B^{b-1}_{c,j}(q_h) + glossy part of row^{b-1}_{c,j}(q_h)]
// so light a glossy surface reflects onto a diffuse one (D <- G <- light) is in both series.
// What is gathered, by path (receiver <- sender <- ... <- light): every path whose first
// glossyBounces reflections are any mix of diffuse and glossy ones; beyond glossyBounces,
// the diffuse bounces gather diffuse senders only (no M^{b-1} is kept there), so a glossy
// reflection more than glossyBounces steps from the receiver is dropped. Senders' radiance is evaluated at
// the hit triangle's corners (own normal, f0, exponent) and interpolated, not at the hit
// point; hits on back faces carry nothing (as for the diffuse bounces).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/sampling.h"
#include "prt/transfer_matrix.h"
#include "baker/scene/scene.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/transfer_bake.h"

namespace prt::bake {

// Makes the BLAS single-threaded: the baker's own threads split the vertices, and a
// single-threaded kernel on a fixed shape gives the same bits whatever options.threads.
void useSingleThreadedBlas();

// Makes the BLAS single-threaded and ends OpenBLAS's worker threads, which the library starts
// when it loads and which spin (sched_yield) for about 2^28 cycles before they sleep: CPU the
// baker never uses (it runs BLAS single-threaded), paid by every process, so by every shard
// and merge of a sharded bake (docs/bench/scale-out.md). Call it once, first.
void releaseBlasThreads();

// Per-thread accumulator of the shadowed matrix of one vertex at a time (scratch reused).
class GlossyShadowedKernel {
 public:
  // order 2..8; maxRays bounds the rays of one vertex (the sample count).
  GlossyShadowedKernel(int order, std::size_t maxRays);

  // Distant lighting: `visible` lists the count sample indices of unoccluded rays above the
  // tangent plane; sampleMajor is the [sample][coefficient] basis table; weight = 4pi/N.
  // Writes the kSymmetric packed matrix (matrixEntryCount(order, kSymmetric) floats).
  void distant(const float* sampleMajor, const std::uint32_t* visible, std::size_t count, float weight, float* packed,
               GlossyKernelStats* stats);

  // Local lighting over `count` rays: rayWeight[r] = w q_r (0 when occluded or the ray never
  // reaches S), sample[r] its sample index, remapped[i * count + r] = y_i(w'_r).
  // Writes the kFull packed matrix (order^4 floats).
  void local(const float* sampleMajor, const std::uint32_t* sample, const float* rayWeight, std::size_t count,
             const float* remapped, float* packed, GlossyKernelStats* stats);

 private:
  int order_, n2_;
  std::vector<float> a_, dense_;
};

// Everything one glossy bounce reads and writes.
struct GlossyBounceJob {
  const Scene* scene = nullptr;
  int order = 0;
  int bounce = 0;                                 // b >= 1
  std::span<const HitBlockView> blocks;               // the direct pass's hits, kBlockVertices per block
  // blocks[j] is the scene's block firstBlock + j: a sharded bake gathers one vertex range.
  // Every per-vertex output below is indexed from that block's first vertex.
  std::size_t firstBlock = 0;
  const DirectionSet* dirs = nullptr;             // the sample directions w_k
  const float* sampleMajor = nullptr;             // [sample][coefficient]
  float sampleWeight = 0.0f;                      // 4pi/N
  const float* diffusePrevious = nullptr;         // B^{b-1}: [vertex][channel][coefficient]
  // Glossy senders: senderIndex[v] >= 0 for vertices with f0 or f90 > 0 (some Fresnel term).
  const std::vector<std::int32_t>* senderIndex = nullptr;
  const float* glossyPrevious = nullptr;  // M^{b-1}: b = 1: [vertex][packed] (previousPacking,
                                          // 1 channel, all vertices); b >= 2: [sender][channel][dense
                                          // row-major n2 x n2], as glossyCurrent
  MatrixPacking previousPacking = MatrixPacking::kFull;
  // b = 1: glossyPrevious holds the senders' packed matrices only, indexed by sender (a
  // sharded bake's merged pass keeps no others) instead of every vertex's.
  bool previousBySender = false;
  float* glossyCurrent = nullptr;   // M^b at senders, [sender][channel][dense n2 x n2]; null: not kept
  float* interreflected = nullptr;  // += M^b, [vertex][channel][full]; null: not summed here
  // Written when non-null: M^b of the blocks' vertices, [vertex][channel][dense n2 x n2] (the
  // layout of glossyCurrent): a sharded bake's bounce shard, summed into the series at the merge.
  float* bounceMatrices = nullptr;
  // Written (not added to) when non-null: the glossy senders' radiance a diffuse receiver
  // gathers in its bounce b, sum_h Hit::weight * glossy part of row^{b-1}(q_h),
  // [vertex][channel][coefficient], albedo not applied.
  float* diffuseFromGlossy = nullptr;
  unsigned threads = 1;
  const BakeOptions* options = nullptr;  // for progress
};

struct SampleTable;

// A job of bounce `bounce` over `blocks` with what every caller sets alike: the scene, order,
// samples (`table`: directions, [sample][coefficient] basis, weight), B^{b-1}, the senders,
// threads and progress from `options`. The caller adds the matrices it reads and writes.
GlossyBounceJob glossyBounceJob(const Scene& scene, const BakeOptions& options, const SampleTable& table, int bounce,
                                std::span<const HitBlockView> blocks, const float* diffusePrevious,
                                const std::vector<std::int32_t>* senderIndex);

// Gathers bounce `job.bounce` for the job's blocks (deterministic whatever job.threads).
// Returns the stats entry "glossy bounce N".
PassStats gatherGlossyBounce(const GlossyBounceJob& job);

// Per vertex, its index among the glossy senders (f0 or f90 > 0: some Fresnel term), in
// vertex order, else -1; *senders counts them.
std::vector<std::int32_t> glossySenderIndex(const Scene& scene, std::size_t* senders);

// The interreflected matrix series' start: every vertex's shadowed matrix (`packing`) in all
// three channels, full packing ([vertex][channel][full]).
std::vector<float> expandShadowedMatrices(std::span<const float> shadowed, int order, MatrixPacking packing);

// interreflected ([vertex][channel][full]) += bounce ([vertex][channel][dense n2 x n2]) over
// `vertices` vertices, element by element as gatherGlossyBounce adds M^b.
void addBounceMatrices(const float* bounce, std::size_t vertices, int order, float* interreflected);

}  // namespace prt::bake
