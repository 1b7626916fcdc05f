#include "baker/transfer/glossy_bake.h"

#include <cblas.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <mutex>
#include <string>

#include "baker/transfer/direct_pass.h"
#include "baker/transfer/parallel_for.h"
#include "prt/glossy_lobe.h"
#include "prt/sh_basis.h"

// Declared by OpenBLAS's cblas.h too; repeated so that the build does not depend on which
// cblas.h alternative (netlib or OpenBLAS) /usr/include points at.
extern "C" void openblas_set_num_threads(int num_threads);
extern "C" int openblas_get_num_threads(void);
// OpenBLAS's own shutdown of its thread pool (what it runs at fork and exit), not in cblas.h.
extern "C" int blas_thread_shutdown_(void);

namespace prt::bake {
namespace {

// Rows of one BLAS call: bounds the scratch (chunk x order^2 floats) for any sample count,
// and is large enough that the call runs at the kernel's block rate.
constexpr std::size_t kChunkRows = 512;
// Hits of one vertex block whose rows a glossy gather holds at once (kGroupHits x 3 order^2
// floats per thread: 2.4 MB at order 5).
constexpr std::size_t kGroupHits = 8192;

// packedIndex[i * n2 + j] = matrixEntryIndex(i, j, packing).
std::vector<std::uint32_t> packedIndexTable(int n2, MatrixPacking packing) {
  std::vector<std::uint32_t> t(static_cast<std::size_t>(n2) * n2);
  for (int i = 0; i < n2; ++i) {
    for (int j = 0; j < n2; ++j) {
      t[static_cast<std::size_t>(i) * n2 + j] = static_cast<std::uint32_t>(matrixEntryIndex(i, j, packing));
    }
  }
  return t;
}

// tmp = t^T M for a dense row-major n2 x n2 M: n2 contiguous axpys, which vectorise.
void vectorTimesDense(const float* __restrict t, const float* __restrict m, std::size_t n2, float* __restrict tmp) {
  std::fill(tmp, tmp + n2, 0.0f);
  for (std::size_t q = 0; q < n2; ++q) {
    const float tq = t[q];
    const float* row = m + q * n2;
    for (std::size_t j = 0; j < n2; ++j) tmp[j] += tq * row[j];
  }
}

}  // namespace

// Only when it is not single-threaded already: openblas_set_num_threads restarts the pool
// that releaseBlasThreads ended.
void useSingleThreadedBlas() {
  if (openblas_get_num_threads() != 1) openblas_set_num_threads(1);
}

void releaseBlasThreads() {
  useSingleThreadedBlas();
  blas_thread_shutdown_();
}

GlossyShadowedKernel::GlossyShadowedKernel(int order, std::size_t maxRays) : order_(order), n2_(shCoeffCount(order)) {
  a_.resize(std::min(maxRays, kChunkRows) * static_cast<std::size_t>(n2_) + 1);
  dense_.resize(static_cast<std::size_t>(n2_) * n2_);
}

void GlossyShadowedKernel::distant(const float* sampleMajor, const std::uint32_t* visible, std::size_t count,
                                   float weight, float* packed, GlossyKernelStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n2 = static_cast<std::size_t>(n2_);
  std::fill(dense_.begin(), dense_.end(), 0.0f);
  for (std::size_t r0 = 0; r0 < count; r0 += kChunkRows) {
    const std::size_t kc = std::min(kChunkRows, count - r0);
    for (std::size_t r = 0; r < kc; ++r) {
      std::memcpy(&a_[r * n2], sampleMajor + static_cast<std::size_t>(visible[r0 + r]) * n2, n2 * sizeof(float));
    }
    // C = w A^T A + C, A = [ray][coefficient]: the lower triangle of the Gram matrix.
    cblas_ssyrk(CblasRowMajor, CblasLower, CblasTrans, n2_, static_cast<int>(kc), weight, a_.data(), n2_, 1.0f,
                dense_.data(), n2_);
  }
  for (std::size_t i = 0; i < n2; ++i) {
    for (std::size_t j = 0; j <= i; ++j) packed[i * (i + 1) / 2 + j] = dense_[i * n2 + j];
  }
  stats->flops += static_cast<std::uint64_t>(count) * n2 * (n2 + 1);
  stats->threadSeconds += secondsSince(t0);
}

void GlossyShadowedKernel::local(const float* sampleMajor, const std::uint32_t* sample, const float* rayWeight,
                                 std::size_t count, const float* remapped, float* packed, GlossyKernelStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n2 = static_cast<std::size_t>(n2_);
  std::fill(dense_.begin(), dense_.end(), 0.0f);
  for (std::size_t r0 = 0; r0 < count; r0 += kChunkRows) {
    const std::size_t kc = std::min(kChunkRows, count - r0);
    // A = [coefficient][ray] of weighted receiver directions y_i(w_r) w q_r.
    for (std::size_t i = 0; i < n2; ++i) {
      for (std::size_t r = 0; r < kc; ++r) {
        a_[i * kc + r] = sampleMajor[static_cast<std::size_t>(sample[r0 + r]) * n2 + i] * rayWeight[r0 + r];
      }
    }
    // C_ij += sum_r A_ir y_j(w'_r): rows receive, columns index the lighting on S.
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, n2_, n2_, static_cast<int>(kc), 1.0f, a_.data(),
                static_cast<int>(kc), remapped + r0, static_cast<int>(count), 1.0f, dense_.data(), n2_);
  }
  for (std::size_t i = 0; i < n2; ++i) {
    for (std::size_t j = 0; j < n2; ++j) packed[matrixEntryIndex(i, j, MatrixPacking::kFull)] = dense_[i * n2 + j];
  }
  stats->flops += 2ull * count * n2 * n2;
  stats->threadSeconds += secondsSince(t0);
}

PassStats gatherGlossyBounce(const GlossyBounceJob& job) {
  const auto t0 = std::chrono::steady_clock::now();
  const Scene& scene = *job.scene;
  const std::size_t vertexCount = scene.positions.size();
  const int order = job.order;
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order)), row3 = 3 * n2, full = n2 * n2;
  const std::size_t blockCount = job.blocks.size();
  const std::size_t rangeBegin = job.firstBlock * kBlockVertices;
  const std::size_t rangeEnd = std::min(vertexCount, (job.firstBlock + blockCount) * kBlockVertices);
  const std::vector<std::int32_t>& senderIndex = *job.senderIndex;
  const bool firstBounce = job.bounce == 1;
  // The senders' previous bounce as dense row-major matrices, indexed by sender: for bounce 1
  // a dense copy of the scalar shadowed matrices at the senders only (the packed layouts'
  // short runs cost several times more per product); later bounces are kept dense already.
  std::vector<float> dense0;
  if (firstBounce) {
    const std::size_t stride = matrixEntryCount(order, job.previousPacking);
    std::size_t count = 0;
    for (std::int32_t sender : senderIndex) count += sender >= 0;
    dense0.resize(count * full);
    for (std::size_t v = 0; v < vertexCount; ++v) {
      if (senderIndex[v] < 0) continue;
      const std::size_t at = job.previousBySender ? static_cast<std::size_t>(senderIndex[v]) : v;
      const float* src = job.glossyPrevious + at * stride;
      float* dst = &dense0[static_cast<std::size_t>(senderIndex[v]) * full];
      for (std::size_t q = 0; q < n2; ++q)
        for (std::size_t j = 0; j < n2; ++j) dst[q * n2 + j] = src[matrixEntryIndex(q, j, job.previousPacking)];
    }
  }
  const float* previous = firstBounce ? dense0.data() : job.glossyPrevious;
  const std::size_t prevStride = firstBounce ? full : 3 * full;
  const std::vector<std::uint32_t> fullIndex = packedIndexTable(static_cast<int>(n2), MatrixPacking::kFull);

  // Band scale of each coefficient for each sender (its own exponent).
  std::vector<int> bandOf(n2);
  for (std::size_t k = 0; k < n2; ++k) bandOf[k] = shBandOf(static_cast<int>(k));
  std::size_t senders = 0;
  for (std::int32_t s : senderIndex) senders += s >= 0;
  std::vector<float> senderScale(senders * n2);
  {
    std::vector<float> g(static_cast<std::size_t>(order));
    for (std::size_t v = 0; v < vertexCount; ++v) {
      if (senderIndex[v] < 0) continue;
      phongLobeBandScalesUnchecked(order, scene.specular[v].exponent, g.data());
      for (std::size_t k = 0; k < n2; ++k) senderScale[senderIndex[v] * n2 + k] = g[bandOf[k]];
    }
  }

  struct Scratch {
    std::vector<float> a, rows, glossyRows, dense, diffuse, yR, t, tmp;
    std::vector<std::uint64_t> order;  // (triangle, hit index) of one group's hits
  };
  const unsigned threads = std::max(1u, job.threads);
  std::vector<Scratch> scratch(threads);
  for (auto& s : scratch) {
    s.a.resize(kGroupHits * n2);
    s.rows.resize(kGroupHits * row3);
    s.glossyRows.resize(kGroupHits * row3);
    s.dense.resize(kBlockVertices * n2 * row3);
    s.diffuse.resize(kBlockVertices * row3);
    s.yR.resize(n2);
    s.t.resize(n2);
    s.tmp.resize(n2);
    s.order.reserve(kGroupHits);
  }
  const std::string name = "glossy bounce " + std::to_string(job.bounce);
  std::atomic<std::size_t> done{0};
  std::mutex progressMutex;

  parallelFor(blockCount, threads, [&](std::size_t block, unsigned thread) {
    Scratch& s = scratch[thread];
    const HitBlockView& rec = job.blocks[block];
    const std::size_t begin = (job.firstBlock + block) * kBlockVertices, end = std::min(vertexCount, begin + kBlockVertices);
    const std::size_t blockVertices = end - begin;
    const std::size_t vertexDense = n2 * row3;
    std::fill(s.dense.begin(), s.dense.begin() + static_cast<std::ptrdiff_t>(blockVertices * vertexDense), 0.0f);
    std::fill(s.diffuse.begin(), s.diffuse.begin() + static_cast<std::ptrdiff_t>(blockVertices * row3), 0.0f);
    const std::uint32_t totalHits = rec.hitStart[blockVertices];
    // The block's hits in groups of kGroupHits (fixed boundaries: deterministic). Within a
    // group, rows are computed in triangle order: the block's neighbouring receivers see
    // mostly the same triangles, so each sender's matrix is read from memory once per group
    // rather than once per hit. The rank-k updates then run per vertex in hit order.
    for (std::uint32_t g0 = 0; g0 < totalHits; g0 += static_cast<std::uint32_t>(kGroupHits)) {
      const std::uint32_t g1 = std::min<std::uint32_t>(totalHits, g0 + static_cast<std::uint32_t>(kGroupHits));
      s.order.resize(g1 - g0);
      for (std::uint32_t h = g0; h < g1; ++h) {
        s.order[h - g0] = (static_cast<std::uint64_t>(rec.hits[h].triangle) << 32) | h;
      }
      std::sort(s.order.begin(), s.order.end());
      std::fill(s.rows.begin(), s.rows.begin() + static_cast<std::ptrdiff_t>((g1 - g0) * row3), 0.0f);
      std::fill(s.glossyRows.begin(), s.glossyRows.begin() + static_cast<std::ptrdiff_t>((g1 - g0) * row3), 0.0f);
      for (const std::uint64_t key : s.order) {
        const auto h = static_cast<std::uint32_t>(key);
        const std::size_t r = h - g0;
        const Hit& hit = rec.hits[h];
        const std::uint32_t k = rec.hitSample[h];
        std::memcpy(&s.a[r * n2], job.sampleMajor + static_cast<std::size_t>(k) * n2, n2 * sizeof(float));
        const Vec3 toReceiver = job.dirs->at(k) * -1.0f;
        const float b1 = hit.u * (1.0f / 65535.0f), b2 = hit.v * (1.0f / 65535.0f);
        const float bary[3] = {1.0f - b1 - b2, b1, b2};
        float* row = &s.rows[r * row3];
        float* glossyRow = &s.glossyRows[r * row3];  // the glossy senders' part alone
        for (int corner = 0; corner < 3; ++corner) {
          const std::uint32_t u = scene.indices[3 * static_cast<std::size_t>(hit.triangle) + corner];
          const float bc = bary[corner];
          const float* diffuse = job.diffusePrevious + static_cast<std::size_t>(u) * row3;
          for (std::size_t i = 0; i < row3; ++i) row[i] += bc * diffuse[i];
          const std::int32_t sender = senderIndex[u];
          if (sender < 0) continue;
          const Vec3 nu = scene.normals[u];
          const Vec3 R = reflectView(toReceiver, nu);
          const Rgb F = schlickFresnel(scene.specular[u].f0, scene.specular[u].f90, dot(nu, toReceiver));
          const float Fc[3] = {F.r, F.g, F.b};
          evalShBasisUnchecked(order, R, s.yR.data());
          const float* g = &senderScale[static_cast<std::size_t>(sender) * n2];
          for (std::size_t q = 0; q < n2; ++q) s.t[q] = g[q] * s.yR[q];
          const float* M = previous + static_cast<std::size_t>(sender) * prevStride;
          const int channels = firstBounce ? 1 : 3;
          for (int pc = 0; pc < channels; ++pc) {
            const float* Mc = M + static_cast<std::size_t>(pc) * full;
            // tmp_j = sum_q t_q M_qj: the sender's outgoing radiance per lighting coefficient.
            vectorTimesDense(s.t.data(), Mc, n2, s.tmp.data());
            for (int c = (channels == 1 ? 0 : pc); c < (channels == 1 ? 3 : pc + 1); ++c) {
              const float f = bc * Fc[c];
              for (std::size_t j = 0; j < n2; ++j) glossyRow[c * n2 + j] += f * s.tmp[j];
            }
          }
        }
        for (std::size_t i = 0; i < row3; ++i) row[i] += glossyRow[i];
      }
      for (std::size_t local = 0; local < blockVertices; ++local) {
        const std::uint32_t lo = std::max(rec.hitStart[local], g0), hi = std::min(rec.hitStart[local + 1], g1);
        if (lo >= hi) continue;
        // The diffuse receiver's view of the same glossy reflections: cosine-weighted, as the
        // diffuse bounces weigh their senders (Hit::weight).
        if (job.diffuseFromGlossy) {
          float* acc = &s.diffuse[local * row3];
          for (std::uint32_t h = lo; h < hi; ++h) {
            const float w = rec.hits[h].weight;
            const float* glossyRow = &s.glossyRows[(h - g0) * row3];
            for (std::size_t i = 0; i < row3; ++i) acc[i] += w * glossyRow[i];
          }
        }
        // dense (n2 x 3n2) += w A^T rows: the rank-k update over this vertex's hits in the group.
        cblas_sgemm(CblasRowMajor, CblasTrans, CblasNoTrans, static_cast<int>(n2), static_cast<int>(row3),
                    static_cast<int>(hi - lo), job.sampleWeight, &s.a[(lo - g0) * n2], static_cast<int>(n2),
                    &s.rows[(lo - g0) * row3], static_cast<int>(row3), 1.0f, &s.dense[local * vertexDense],
                    static_cast<int>(row3));
      }
    }
    if (job.diffuseFromGlossy) {
      std::memcpy(job.diffuseFromGlossy + (begin - rangeBegin) * row3, s.diffuse.data(), blockVertices * row3 * sizeof(float));
    }
    for (std::size_t v = begin; v < end; ++v) {
      const float* gathered = &s.dense[(v - begin) * vertexDense];
      float* dst = job.interreflected ? job.interreflected + (v - rangeBegin) * 3 * full : nullptr;
      float* keep = (job.glossyCurrent && senderIndex[v] >= 0)
                        ? job.glossyCurrent + static_cast<std::size_t>(senderIndex[v]) * 3 * full
                        : nullptr;
      float* mine = job.bounceMatrices ? job.bounceMatrices + (v - rangeBegin) * 3 * full : nullptr;
      for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < n2; ++i) {
          for (std::size_t j = 0; j < n2; ++j) {
            const float value = gathered[i * row3 + c * n2 + j];
            if (dst) dst[c * full + fullIndex[i * n2 + j]] += value;
            if (keep) keep[c * full + i * n2 + j] = value;  // dense, for the next bounce
            if (mine) mine[c * full + i * n2 + j] = value;
          }
        }
      }
    }
    const std::size_t d = done.fetch_add(end - begin) + (end - begin);
    if (job.options && job.options->progress) {
      std::lock_guard<std::mutex> lock(progressMutex);
      job.options->progress({name.c_str(), d, rangeEnd - rangeBegin, 0});
    }
  });
  return {name, secondsSince(t0), 0};
}

GlossyBounceJob glossyBounceJob(const Scene& scene, const BakeOptions& options, const SampleTable& table, int bounce,
                                std::span<const HitBlockView> blocks, const float* diffusePrevious,
                                const std::vector<std::int32_t>* senderIndex) {
  GlossyBounceJob job;
  job.scene = &scene;
  job.order = options.order;
  job.bounce = bounce;
  job.blocks = blocks;
  job.dirs = &table.dirs;
  job.sampleMajor = table.sampleMajor.data();
  job.sampleWeight = static_cast<float>(table.dirs.weight);
  job.diffusePrevious = diffusePrevious;
  job.senderIndex = senderIndex;
  job.threads = options.threads ? options.threads : defaultThreadCount();
  job.options = &options;
  return job;
}

std::vector<std::int32_t> glossySenderIndex(const Scene& scene, std::size_t* senders) {
  std::vector<std::int32_t> index(scene.positions.size(), -1);
  std::int32_t count = 0;
  for (std::size_t v = 0; v < scene.specular.size() && v < index.size(); ++v) {
    // A sender reflects glossily unless its Fresnel term is 0 at every angle (f0 = f90 = 0).
    const Rgb f0 = scene.specular[v].f0;
    if (f0.r > 0.0f || f0.g > 0.0f || f0.b > 0.0f || scene.specular[v].f90 > 0.0f) index[v] = count++;
  }
  *senders = static_cast<std::size_t>(count);
  return index;
}

std::vector<float> expandShadowedMatrices(std::span<const float> shadowed, int order, MatrixPacking packing) {
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order));
  const std::size_t entries = matrixEntryCount(order, packing), full = matrixEntryCount(order, MatrixPacking::kFull);
  const std::size_t vertices = shadowed.size() / entries;
  std::vector<float> out(vertices * 3 * full, 0.0f);
  for (std::size_t v = 0; v < vertices; ++v) {
    const float* src = &shadowed[v * entries];
    float* dst = &out[v * 3 * full];
    for (std::size_t i = 0; i < n2; ++i) {
      for (std::size_t j = 0; j < n2; ++j) {
        const float m = src[matrixEntryIndex(i, j, packing)];
        for (std::size_t c = 0; c < 3; ++c) dst[c * full + matrixEntryIndex(i, j, MatrixPacking::kFull)] = m;
      }
    }
  }
  return out;
}

void addBounceMatrices(const float* bounce, std::size_t vertices, int order, float* interreflected) {
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order)), full = n2 * n2;
  const std::vector<std::uint32_t> fullIndex = packedIndexTable(static_cast<int>(n2), MatrixPacking::kFull);
  for (std::size_t v = 0; v < vertices; ++v) {
    const float* src = bounce + v * 3 * full;
    float* dst = interreflected + v * 3 * full;
    for (std::size_t c = 0; c < 3; ++c) {
      for (std::size_t e = 0; e < full; ++e) dst[c * full + fullIndex[e]] += src[c * full + e];
    }
  }
}

}  // namespace prt::bake
