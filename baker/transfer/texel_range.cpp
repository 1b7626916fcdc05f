#include "baker/transfer/texel_range.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <string>

#include "baker/scene/normal_map.h"
#include "baker/texture/texel_dilate.h"
#include "baker/texture/texel_filter.h"
#include "baker/transfer/bounce_gather.h"
#include "baker/transfer/direct_pass.h"
#include "baker/transfer/embree_scene.h"
#include "baker/transfer/parallel_for.h"
#include "prt/octahedral_normal.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

Status checkTexelOptions(const Scene& scene, std::span<const Uv> atlasUv, const TexelBakeOptions& options) {
  if (options.transfer.glossy) {
    return Status::error(StatusCode::kInvalidArgument,
                         "transfer textures bake vector passes only (glossy matrices stay per vertex): turn glossy off");
  }
  PRT_RETURN_IF_ERROR(checkOptions(scene, options.transfer));
  PRT_RETURN_IF_ERROR(checkNormalMaps(scene));
  if (options.visibilityOrder != 0) {
    if (options.visibilityOrder < 2 || options.visibilityOrder > kMaxShOrder) {
      return Status::error(StatusCode::kInvalidArgument, "visibility order " + std::to_string(options.visibilityOrder) +
                                                             " is outside [2, " + std::to_string(kMaxShOrder) + "]");
    }
    if (isLocalLighting(options.transfer.lighting.model)) {
      return Status::error(StatusCode::kInvalidArgument,
                           "visibility vectors (TPFL glossy) need distant lighting: under local lighting the light's "
                           "basis is remapped per ray, so transfer is not a product with the lighting");
    }
  }
  if (options.dilation < 0 || options.dilation > kMaxDilationPasses) {
    return Status::error(StatusCode::kInvalidArgument, "dilation " + std::to_string(options.dilation) +
                                                           " is outside 0 … " + std::to_string(kMaxDilationPasses) +
                                                           " texels");
  }
  if (atlasUv.size() != scene.positions.size()) {
    return Status::error(StatusCode::kSizeMismatch, "the atlas has " + std::to_string(atlasUv.size()) +
                                                        " UVs for " + std::to_string(scene.positions.size()) +
                                                        " vertices");
  }
  return Status::ok();
}

Status badRange(const char* what, std::size_t begin, std::size_t end, std::size_t count) {
  return Status::error(StatusCode::kInvalidArgument, std::string(what) + " [" + std::to_string(begin) + ", " +
                                                         std::to_string(end) + ") is not a block-aligned range of the " +
                                                         std::to_string(count) + " texel receivers");
}

}  // namespace

Status prepareTexelReceivers(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                             const TexelBakeOptions& options, TexelReceivers* out) {
  PRT_RETURN_IF_ERROR(checkTexelOptions(scene, atlasUv, options));
  *out = TexelReceivers{};
  AtlasSamples& samples = out->samples;
  PRT_RETURN_IF_ERROR(rasteriseAtlases(scene.positions, scene.normals, scene.albedo, scene.indices, atlasUv, atlases,
                                       &samples));
  if (samples.texels.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "no texel of the atlases is covered by a triangle with UV area");
  }
  if (options.stitchSeams) {
    PRT_RETURN_IF_ERROR(
        findSeamTexels(scene.positions, scene.normals, scene.indices, atlasUv, atlases, samples, &out->seams));
  }
  const std::size_t receivers = samples.texels.size();
  out->positions.resize(receivers);
  out->normals.resize(receivers);
  for (std::size_t r = 0; r < receivers; ++r) {
    out->positions[r] = samples.texels[r].position;
    out->normals[r] = samples.texels[r].normal;
  }
  // Normal maps turn the cosine's normal per texel (PRTT §6.2); the interpolated normal keeps
  // the horizon and the ray offset, so a bump cannot see through its own surface.
  if (!scene.normalMapOf.empty()) {
    out->shading.resize(receivers);
    for (std::size_t r = 0; r < receivers; ++r) {
      const AtlasTexel& t = samples.texels[r];
      const std::size_t i = 3 * static_cast<std::size_t>(t.triangle);
      out->shading[r] = shadingNormalAt(scene, {scene.indices[i], scene.indices[i + 1], scene.indices[i + 2]}, t.bary,
                                        t.normal);
      if (scene.normalMapOf[scene.indices[i]] >= 0) ++out->normalMappedTexels;
    }
  }
  out->faceNormal = faceNormals(scene);
  std::vector<std::uint32_t> samplesPerTriangle(out->faceNormal.size(), 0);
  for (const AtlasTexel& t : samples.texels) ++samplesPerTriangle[t.triangle];
  out->area.resize(receivers);
  for (std::size_t r = 0; r < receivers; ++r) {
    const std::uint32_t t = samples.texels[r].triangle;
    out->area[r] = 0.5 * length(out->faceNormal[t]) / samplesPerTriangle[t];
  }
  return Status::ok();
}

Status bakeTexelDirectRange(const Scene& scene, const TexelReceivers& receivers, const TexelBakeOptions& options,
                            std::size_t begin, std::size_t end, TexelDirectRange* out) {
  const BakeOptions& o = options.transfer;
  const std::size_t total = receivers.count();
  if (begin % kBlockVertices != 0 || !(begin < end) || end > total) return badRange("texel range", begin, end, total);
  SampleTable table;
  PRT_RETURN_IF_ERROR(makeSamples(o, &table));
  if (options.visibilityOrder > 0) PRT_RETURN_IF_ERROR(addVisibilityBasis(options.visibilityOrder, &table));
  EmbreeScene embree;
  PRT_RETURN_IF_ERROR(EmbreeScene::build(scene, &embree));
  const std::size_t count = end - begin, n2 = static_cast<std::size_t>(shCoeffCount(o.order));
  const std::size_t m2 = static_cast<std::size_t>(shCoeffCount(options.visibilityOrder));
  out->unshadowed.assign(count * n2, 0.0f);
  out->shadowed.assign(count * n2, 0.0f);
  out->visibility.assign(options.visibilityOrder > 0 ? count * m2 : 0, 0.0f);
  out->blocks.clear();
  std::vector<std::uint8_t> outside(count, 0);
  DirectPassJob job;
  job.embree = &embree;
  job.table = &table;
  job.options = &o;
  // Blocks of the range start at `begin`, a block boundary: each holds the receivers it holds
  // in the whole pass, and a receiver's rays depend on it alone.
  job.positions = std::span<const Vec3>(receivers.positions).subspan(begin, count);
  job.normals = std::span<const Vec3>(receivers.normals).subspan(begin, count);
  if (!receivers.shading.empty()) job.shadingNormals = std::span<const Vec3>(receivers.shading).subspan(begin, count);
  job.faceNormal = receivers.faceNormal;
  job.threads = o.threads ? o.threads : defaultThreadCount();
  job.unshadowed = out->unshadowed.data();
  job.shadowed = out->shadowed.data();
  job.blocks = o.interreflection ? &out->blocks : nullptr;
  job.outside = outside.data();
  job.visibility = out->visibility.empty() ? nullptr : out->visibility.data();
  GlossyKernelStats unused;
  out->stats = runDirectPass(job, &unused);
  out->outsideLight = 0;
  for (std::uint8_t x : outside) out->outsideLight += x;
  return Status::ok();
}

Status texelFirstBounce(const TexelReceivers& receivers, int order, std::span<const float> shadowed,
                        std::vector<float>* bounce, double* energy) {
  const std::size_t count = receivers.count(), n2 = static_cast<std::size_t>(shCoeffCount(order)), stride = 3 * n2;
  if (shadowed.size() != count * n2) {
    return Status::error(StatusCode::kSizeMismatch, "the shadowed transfer has " + std::to_string(shadowed.size()) +
                                                        " floats for " + std::to_string(count) + " texel receivers");
  }
  bounce->assign(count * stride, 0.0f);
  double e = 0.0;
  for (std::size_t r = 0; r < count; ++r) {
    const Rgb a = receivers.samples.texels[r].albedo;
    const float rho[3] = {a.r, a.g, a.b};
    for (std::size_t c = 0; c < 3; ++c) {
      for (std::size_t i = 0; i < n2; ++i) (*bounce)[r * stride + c * n2 + i] = rho[c] * shadowed[r * n2 + i];
      e += receivers.area[r] * (*bounce)[r * stride + c * n2];
    }
  }
  *energy = e;
  return Status::ok();
}

Status scatterTexels(const TexelReceivers& receivers, std::span<const TextureAtlas> atlases, std::span<const float> perReceiver,
                     std::size_t stride, int dilation, TexelTexture* out) {
  const AtlasSamples& samples = receivers.samples;
  if (perReceiver.size() != samples.texels.size() * stride) {
    return Status::error(StatusCode::kSizeMismatch, std::to_string(perReceiver.size()) + " floats for " +
                                                        std::to_string(samples.texels.size()) + " texel receivers of " +
                                                        std::to_string(stride) + " each");
  }
  out->stride = stride;
  out->values.assign(samples.firstTexel.back() * stride, 0.0f);
  for (std::size_t r = 0; r < samples.texels.size(); ++r) {
    std::copy_n(perReceiver.data() + r * stride, stride, &out->values[samples.texels[r].index * stride]);
  }
  out->filled.assign(samples.firstTexel.back(), 0);
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const std::uint64_t first = samples.firstTexel[a], count = samples.firstTexel[a + 1] - first;
    const int w = static_cast<int>(atlases[a].width), h = static_cast<int>(atlases[a].height);
    std::vector<std::uint8_t> atlasFilled;
    PRT_RETURN_IF_ERROR(dilateGutters(std::span<float>(out->values).subspan(first * stride, count * stride), w, h,
                                      static_cast<int>(stride),
                                      std::span<const std::uint8_t>(samples.sampled).subspan(first, count), dilation,
                                      &atlasFilled));
    std::copy(atlasFilled.begin(), atlasFilled.end(), out->filled.begin() + static_cast<std::ptrdiff_t>(first));
  }
  // Only with dilation >= 1, which fills every texel a seam texel reads.
  if (dilation >= 1) stitchSeams(receivers.seams, atlases, samples.firstTexel, out->filled, out->values, stride);
  return Status::ok();
}

Status gatherTexelBounceRange(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                              const TexelReceivers& receivers, const TexelBakeOptions& options, int bounce,
                              std::size_t firstBlock, std::span<const HitBlockView> blocks, const TexelTexture& previous,
                              std::vector<float>* current, std::vector<double>* blockEnergy, std::uint64_t* unmapped,
                              PassStats* stats) {
  const BakeOptions& o = options.transfer;
  const std::size_t total = receivers.count(), n2 = static_cast<std::size_t>(shCoeffCount(o.order)), stride = 3 * n2;
  const std::size_t begin = firstBlock * kBlockVertices, end = std::min(total, (firstBlock + blocks.size()) * kBlockVertices);
  if (blocks.empty() || !(begin < end)) return badRange("texel bounce range", begin, end, total);
  if (previous.stride != stride || previous.values.size() != receivers.samples.firstTexel.back() * stride) {
    return Status::error(StatusCode::kSizeMismatch, "the previous bounce's texture does not hold " + std::to_string(stride) +
                                                        " floats a texel of the atlases");
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string name = "bounce " + std::to_string(bounce);
  ProgressReporter progress(o, name, end - begin);
  const std::size_t triangles = scene.indices.size() / 3;
  current->assign((end - begin) * stride, 0.0f);
  blockEnergy->assign(blocks.size(), 0.0);
  std::vector<std::uint64_t> blockUnmapped(blocks.size(), 0);
  std::vector<std::uint8_t> blockBad(blocks.size(), 0);
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();
  parallelFor(blocks.size(), threads, [&](std::size_t j, unsigned) {
    const HitBlockView& rec = blocks[j];
    const std::size_t b0 = (firstBlock + j) * kBlockVertices, b1 = std::min(total, b0 + kBlockVertices);
    // Records a shard read from a file index the scene: refused before any is used.
    if (rec.hitStart.size() != b1 - b0 + 1 || rec.hitStart.back() != rec.hits.size() || !hitRecordsFit(rec.hits, triangles)) {
      blockBad[j] = 1;
      return;
    }
    std::vector<float> gathered(stride);
    WeightedRows terms;
    double e = 0.0;
    for (std::size_t r = b0; r < b1; ++r) {
      std::fill(gathered.begin(), gathered.end(), 0.0f);
      terms.clear();
      const std::size_t local = r - b0;
      for (std::uint32_t h = rec.hitStart[local]; h < rec.hitStart[local + 1]; ++h) {
        const Hit& hit = rec.hits[h];
        const float w1 = hit.u * (1.0f / 65535.0f), w2 = hit.v * (1.0f / 65535.0f), w0 = 1.0f - w1 - w2;
        const std::uint32_t* corner = &scene.indices[3 * std::size_t{hit.triangle}];
        const Uv uv{w0 * atlasUv[corner[0]].u + w1 * atlasUv[corner[1]].u + w2 * atlasUv[corner[2]].u,
                    w0 * atlasUv[corner[0]].v + w1 * atlasUv[corner[1]].v + w2 * atlasUv[corner[2]].v};
        const std::uint32_t a = receivers.samples.triangleAtlas[hit.triangle];
        TexelTap taps[4];
        const int count = bilinearTaps(uv, atlases[a], receivers.samples.firstTexel[a], previous.filled, taps);
        if (count == 0) ++blockUnmapped[j];
        for (int t = 0; t < count; ++t) terms.add(taps[t].texel, hit.weight * taps[t].weight);
      }
      addWeightedRows(terms, previous.values.data(), stride, gathered.data());
      const Rgb albedo = receivers.samples.texels[r].albedo;
      const float rho[3] = {albedo.r, albedo.g, albedo.b};
      float* dst = &(*current)[(r - begin) * stride];
      for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < n2; ++i) dst[c * n2 + i] = rho[c] * gathered[c * n2 + i];
        e += receivers.area[r] * dst[c * n2];
      }
    }
    (*blockEnergy)[j] = e;
    progress.add(b1 - b0, 0);
  });
  for (std::size_t j = 0; j < blocks.size(); ++j) {
    if (blockBad[j]) {
      return Status::error(StatusCode::kCorrupt, "a hit record of texel block " + std::to_string(firstBlock + j) +
                                                     " names a triangle not below " + std::to_string(triangles) +
                                                     ", has a weight that is not finite, or its counts do not fit the block");
    }
  }
  for (std::uint64_t u : blockUnmapped) *unmapped += u;
  *stats = {name, secondsSince(t0), 0};
  return Status::ok();
}

Status finishTexelBake(const TexelReceivers& receivers, std::span<const TextureAtlas> atlases,
                       const TexelBakeOptions& options, TexelPasses&& passes, TexelBakeResult* out) {
  const BakeOptions& o = options.transfer;
  const std::size_t count = receivers.count(), n2 = static_cast<std::size_t>(shCoeffCount(o.order));
  const std::size_t m2 = static_cast<std::size_t>(shCoeffCount(options.visibilityOrder));
  TexelTexture texture;
  PRT_RETURN_IF_ERROR(scatterTexels(receivers, atlases, passes.unshadowed, n2, options.dilation, &texture));
  out->unshadowed = std::move(texture.values);
  PRT_RETURN_IF_ERROR(scatterTexels(receivers, atlases, passes.shadowed, n2, options.dilation, &texture));
  out->shadowed = std::move(texture.values);
  if (o.interreflection) {
    PRT_RETURN_IF_ERROR(scatterTexels(receivers, atlases, passes.interreflected, 3 * n2, options.dilation, &texture));
    out->interreflected = std::move(texture.values);
  }
  if (!passes.visibility.empty()) {
    PRT_RETURN_IF_ERROR(scatterTexels(receivers, atlases, passes.visibility, m2, options.dilation, &texture));
    out->visibility = std::move(texture.values);
    out->visibilityOrder = options.visibilityOrder;
  }
  out->normalMappedTexels = receivers.normalMappedTexels;
  if (receivers.normalMappedTexels > 0) {
    // Dilated like the transfer, so a bilinear read at a chart's edge blends normals of that
    // chart only; the sum of neighbours is made unit again before it is encoded.
    std::vector<float> flat(3 * count);
    for (std::size_t r = 0; r < count; ++r) {
      flat[3 * r] = receivers.shading[r].x;
      flat[3 * r + 1] = receivers.shading[r].y;
      flat[3 * r + 2] = receivers.shading[r].z;
    }
    PRT_RETURN_IF_ERROR(scatterTexels(receivers, atlases, flat, 3, options.dilation, &texture));
    out->normals.assign(2 * texture.values.size() / 3, 0);
    for (std::size_t t = 0; t < texture.filled.size(); ++t) {
      if (!receivers.samples.sampled[t] && !texture.filled[t]) continue;  // empty: (0, 0), as the asset format demands
      const float* v = &texture.values[3 * t];
      const std::array<std::int16_t, 2> code = encodeOctahedralNormal(Vec3{v[0], v[1], v[2]});
      out->normals[2 * t] = code[0];
      out->normals[2 * t + 1] = code[1];
    }
  }
  out->order = o.order;
  out->texels = receivers.samples.firstTexel.back();
  out->sampledTexels = count;
  out->normalFallbacks = receivers.samples.normalFallbacks;
  out->seamTexels = options.dilation >= 1 ? receivers.seams.size() : 0;
  out->bounces = passes.bounces;
  out->bounceEnergy = std::move(passes.bounceEnergy);
  out->coverage.resize(out->texels);
  for (std::size_t t = 0; t < out->coverage.size(); ++t) {
    out->coverage[t] = static_cast<std::uint8_t>(receivers.samples.sampled[t] ? TexelCoverage::kSampled
                                                 : texture.filled[t]          ? TexelCoverage::kGutter
                                                                              : TexelCoverage::kEmpty);
  }
  return Status::ok();
}

}  // namespace prt::bake
