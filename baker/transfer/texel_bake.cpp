#include "baker/transfer/texel_bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "baker/scene/normal_map.h"
#include "baker/texture/atlas_samples.h"
#include "baker/texture/texel_dilate.h"
#include "baker/texture/texel_filter.h"
#include "baker/texture/texel_seams.h"
#include "baker/transfer/direct_pass.h"
#include "baker/transfer/embree_scene.h"
#include "baker/transfer/parallel_for.h"
#include "prt/octahedral_normal.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

// A per-texel texture of all atlases (AtlasSamples' texel numbering), `stride` floats a texel.
struct TexelTexture {
  std::vector<float> values;
  std::size_t stride = 0;
};

// Writes each receiver's `stride` floats to its texel, dilates every atlas `passes` texels
// into its gutters and stitches `seams` (texel_seams.h; only with passes >= 1, which fills
// every texel a seam texel reads); *filled gets 1 for sampled or filled texels.
Status scatterAndDilate(const AtlasSamples& samples, std::span<const TextureAtlas> atlases,
                        std::span<const SeamTexel> seams, const float* perReceiver, std::size_t stride, int passes,
                        TexelTexture* out, std::vector<std::uint8_t>* filled) {
  out->stride = stride;
  out->values.assign(samples.firstTexel.back() * stride, 0.0f);
  for (std::size_t r = 0; r < samples.texels.size(); ++r) {
    std::copy_n(perReceiver + r * stride, stride, &out->values[samples.texels[r].index * stride]);
  }
  filled->assign(samples.firstTexel.back(), 0);
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const std::uint64_t first = samples.firstTexel[a], count = samples.firstTexel[a + 1] - first;
    const int w = static_cast<int>(atlases[a].width), h = static_cast<int>(atlases[a].height);
    std::vector<std::uint8_t> atlasFilled;
    PRT_RETURN_IF_ERROR(dilateGutters(std::span<float>(out->values).subspan(first * stride, count * stride), w, h,
                                      static_cast<int>(stride),
                                      std::span<const std::uint8_t>(samples.sampled).subspan(first, count), passes,
                                      &atlasFilled));
    std::copy(atlasFilled.begin(), atlasFilled.end(), filled->begin() + static_cast<std::ptrdiff_t>(first));
  }
  if (passes >= 1) stitchSeams(seams, atlases, samples.firstTexel, *filled, out->values, stride);
  return Status::ok();
}

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

Status bakeInto(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                const TexelBakeOptions& options, TexelBakeResult* out) {
  const BakeOptions& o = options.transfer;
  PRT_RETURN_IF_ERROR(checkTexelOptions(scene, atlasUv, options));
  AtlasSamples samples;
  PRT_RETURN_IF_ERROR(rasteriseAtlases(scene.positions, scene.normals, scene.albedo, scene.indices, atlasUv, atlases,
                                       &samples));
  if (samples.texels.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "no texel of the atlases is covered by a triangle with UV area");
  }
  std::vector<SeamTexel> seams;
  if (options.stitchSeams) {
    PRT_RETURN_IF_ERROR(findSeamTexels(scene.positions, scene.normals, scene.indices, atlasUv, atlases, samples, &seams));
  }
  const std::size_t receivers = samples.texels.size();
  std::vector<Vec3> positions(receivers), normals(receivers);
  for (std::size_t r = 0; r < receivers; ++r) {
    positions[r] = samples.texels[r].position;
    normals[r] = samples.texels[r].normal;
  }
  // Normal maps turn the cosine's normal per texel (PRTT §6.2); the interpolated normal keeps
  // the horizon and the ray offset, so a bump cannot see through its own surface.
  std::vector<Vec3> shading;
  if (!scene.normalMapOf.empty()) {
    shading.resize(receivers);
    for (std::size_t r = 0; r < receivers; ++r) {
      const AtlasTexel& t = samples.texels[r];
      const std::size_t i = 3 * static_cast<std::size_t>(t.triangle);
      shading[r] = shadingNormalAt(scene, {scene.indices[i], scene.indices[i + 1], scene.indices[i + 2]}, t.bary,
                                   t.normal);
      if (scene.normalMapOf[scene.indices[i]] >= 0) ++out->normalMappedTexels;
    }
  }

  SampleTable table;
  PRT_RETURN_IF_ERROR(makeSamples(o, &table));
  if (options.visibilityOrder > 0) PRT_RETURN_IF_ERROR(addVisibilityBasis(options.visibilityOrder, &table));
  const std::size_t m2 = static_cast<std::size_t>(shCoeffCount(options.visibilityOrder));
  std::vector<float> visibility(options.visibilityOrder > 0 ? receivers * m2 : 0);
  EmbreeScene embree;
  PRT_RETURN_IF_ERROR(EmbreeScene::build(scene, &embree));
  const std::vector<Vec3> faceNormal = faceNormals(scene);
  const int n2 = shCoeffCount(o.order);
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();

  // ---- direct pass at the texel samples, exactly the vertex bake's (direct_pass.h)
  std::vector<float> unshadowed(receivers * n2), shadowed(receivers * n2);
  std::vector<HitBlock> blocks;
  std::vector<std::uint8_t> outside(receivers, 0);
  {
    DirectPassJob job;
    job.embree = &embree;
    job.table = &table;
    job.options = &o;
    job.positions = positions;
    job.normals = normals;
    job.shadingNormals = shading;
    job.faceNormal = faceNormal;
    job.threads = threads;
    job.unshadowed = unshadowed.data();
    job.shadowed = shadowed.data();
    job.blocks = o.interreflection ? &blocks : nullptr;
    job.outside = outside.data();
    job.visibility = visibility.empty() ? nullptr : visibility.data();
    GlossyKernelStats unused;
    out->passes.push_back(runDirectPass(job, &unused));
  }
  for (std::uint8_t x : outside) out->texelsOutsideLight += x;

  std::vector<float> interreflected;
  if (o.interreflection) {
    // A texel's share of the surface: its owner triangle's area split evenly among the
    // triangle's samples, so bounce energies do not depend on the atlas resolution.
    std::vector<std::uint32_t> samplesPerTriangle(faceNormal.size(), 0);
    for (const AtlasTexel& t : samples.texels) ++samplesPerTriangle[t.triangle];
    std::vector<double> area(receivers);
    for (std::size_t r = 0; r < receivers; ++r) {
      const std::uint32_t t = samples.texels[r].triangle;
      area[r] = 0.5 * length(faceNormal[t]) / samplesPerTriangle[t];
    }
    const std::size_t stride = 3 * static_cast<std::size_t>(n2);
    std::vector<float> previous(receivers * stride), current(receivers * stride);
    double energy0 = 0.0;
    for (std::size_t r = 0; r < receivers; ++r) {
      const Rgb a = samples.texels[r].albedo;
      const float rho[3] = {a.r, a.g, a.b};
      for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < n2; ++i) previous[r * stride + c * n2 + i] = rho[c] * shadowed[r * n2 + i];
        energy0 += area[r] * previous[r * stride + c * n2];
      }
    }
    interreflected = previous;
    out->bounceEnergy.push_back(energy0);

    const std::size_t blockCount = blocks.size();
    std::vector<std::uint64_t> blockUnmapped(blockCount, 0);
    for (int bounce = 1; bounce <= o.maxBounces; ++bounce) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string name = "bounce " + std::to_string(bounce);
      ProgressReporter progress(o, name, receivers);
      // PRTT §4.2's bounce texture: the previous bounce per texel, dilated so that bilinear
      // reads at a chart's edge blend only that chart's values.
      TexelTexture bounceTexture;
      std::vector<std::uint8_t> filled;
      PRT_RETURN_IF_ERROR(
          scatterAndDilate(samples, atlases, seams, previous.data(), stride, options.dilation, &bounceTexture, &filled));
      std::vector<double> blockEnergy(blockCount, 0.0);
      std::fill(blockUnmapped.begin(), blockUnmapped.end(), 0);
      parallelFor(blockCount, threads, [&](std::size_t block, unsigned) {
        const HitBlock& rec = blocks[block];
        const std::size_t begin = block * kBlockVertices, end = std::min(receivers, begin + kBlockVertices);
        std::vector<float> gathered(stride);
        double e = 0.0;
        for (std::size_t r = begin; r < end; ++r) {
          std::fill(gathered.begin(), gathered.end(), 0.0f);
          const std::size_t local = r - begin;
          for (std::uint32_t h = rec.hitStart[local]; h < rec.hitStart[local + 1]; ++h) {
            const Hit& hit = rec.hits[h];
            const float b1 = hit.u * (1.0f / 65535.0f), b2 = hit.v * (1.0f / 65535.0f), b0 = 1.0f - b1 - b2;
            const std::uint32_t* corner = &scene.indices[3 * std::size_t{hit.triangle}];
            const Uv uv{b0 * atlasUv[corner[0]].u + b1 * atlasUv[corner[1]].u + b2 * atlasUv[corner[2]].u,
                        b0 * atlasUv[corner[0]].v + b1 * atlasUv[corner[1]].v + b2 * atlasUv[corner[2]].v};
            const std::uint32_t a = samples.triangleAtlas[hit.triangle];
            TexelTap taps[4];
            const int count = bilinearTaps(uv, atlases[a], samples.firstTexel[a], filled, taps);
            if (count == 0) ++blockUnmapped[block];
            for (int t = 0; t < count; ++t) {
              const float* src = &bounceTexture.values[taps[t].texel * stride];
              const float wt = hit.weight * taps[t].weight;
              for (std::size_t i = 0; i < stride; ++i) gathered[i] += wt * src[i];
            }
          }
          const Rgb albedo = samples.texels[r].albedo;
          const float rho[3] = {albedo.r, albedo.g, albedo.b};
          float* dst = &current[r * stride];
          for (int c = 0; c < 3; ++c) {
            for (int i = 0; i < n2; ++i) dst[c * n2 + i] = rho[c] * gathered[c * n2 + i];
            e += area[r] * dst[c * n2];
          }
        }
        blockEnergy[block] = e;
        progress.add(end - begin, 0);
      });
      double energy = 0.0;
      for (double e : blockEnergy) energy += e;  // fixed order: deterministic
      for (std::uint64_t u : blockUnmapped) out->unmappedHits += u;
      for (std::size_t i = 0; i < current.size(); ++i) interreflected[i] += current[i];
      out->bounceEnergy.push_back(energy);
      out->bounces = bounce;
      out->passes.push_back({name, secondsSince(t0), 0});
      std::swap(previous, current);
      if (!(energy > o.bounceThreshold * energy0)) break;
    }
  }

  // ---- the stored textures, dilated for the client's bilinear filter
  TexelTexture texture;
  std::vector<std::uint8_t> filled;
  PRT_RETURN_IF_ERROR(
      scatterAndDilate(samples, atlases, seams, unshadowed.data(), n2, options.dilation, &texture, &filled));
  out->unshadowed = std::move(texture.values);
  PRT_RETURN_IF_ERROR(
      scatterAndDilate(samples, atlases, seams, shadowed.data(), n2, options.dilation, &texture, &filled));
  out->shadowed = std::move(texture.values);
  if (o.interreflection) {
    PRT_RETURN_IF_ERROR(
        scatterAndDilate(samples, atlases, seams, interreflected.data(), 3 * n2, options.dilation, &texture, &filled));
    out->interreflected = std::move(texture.values);
  }
  if (!visibility.empty()) {
    PRT_RETURN_IF_ERROR(
        scatterAndDilate(samples, atlases, seams, visibility.data(), m2, options.dilation, &texture, &filled));
    out->visibility = std::move(texture.values);
    out->visibilityOrder = options.visibilityOrder;
  }
  if (out->normalMappedTexels > 0) {
    // Dilated like the transfer, so a bilinear read at a chart's edge blends normals of that
    // chart only; the sum of neighbours is made unit again before it is encoded.
    std::vector<float> flat(3 * receivers);
    for (std::size_t r = 0; r < receivers; ++r) {
      flat[3 * r] = shading[r].x;
      flat[3 * r + 1] = shading[r].y;
      flat[3 * r + 2] = shading[r].z;
    }
    PRT_RETURN_IF_ERROR(scatterAndDilate(samples, atlases, seams, flat.data(), 3, options.dilation, &texture, &filled));
    out->normals.assign(2 * texture.values.size() / 3, 0);
    for (std::size_t t = 0; t < filled.size(); ++t) {
      if (!samples.sampled[t] && !filled[t]) continue;  // empty: (0, 0), as the asset format demands
      const float* v = &texture.values[3 * t];
      const std::array<std::int16_t, 2> code = encodeOctahedralNormal(Vec3{v[0], v[1], v[2]});
      out->normals[2 * t] = code[0];
      out->normals[2 * t + 1] = code[1];
    }
  }
  out->order = o.order;
  out->texels = samples.firstTexel.back();
  out->sampledTexels = receivers;
  out->normalFallbacks = samples.normalFallbacks;
  out->seamTexels = options.dilation >= 1 ? seams.size() : 0;
  out->coverage.resize(out->texels);
  for (std::size_t t = 0; t < out->coverage.size(); ++t) {
    out->coverage[t] = static_cast<std::uint8_t>(samples.sampled[t]   ? TexelCoverage::kSampled
                                                 : filled[t]          ? TexelCoverage::kGutter
                                                                      : TexelCoverage::kEmpty);
  }
  return Status::ok();
}

}  // namespace

Status bakeTexelTransfer(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                         const TexelBakeOptions& options, TexelBakeResult* out) {
  TexelBakeResult result;
  PRT_RETURN_IF_ERROR(bakeInto(scene, atlasUv, atlases, options, &result));
  *out = std::move(result);
  return Status::ok();
}

}  // namespace prt::bake
