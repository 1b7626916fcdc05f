#include "baker/transfer/texel_bake.h"

#include <utility>
#include <vector>

#include "baker/transfer/texel_range.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

// The pieces of texel_range.h in the order the passes need them, on every receiver at once.
Status bakeInto(const Scene& scene, std::span<const Uv> atlasUv, std::span<const TextureAtlas> atlases,
                const TexelBakeOptions& options, TexelBakeResult* out) {
  const BakeOptions& o = options.transfer;
  TexelReceivers receivers;
  PRT_RETURN_IF_ERROR(prepareTexelReceivers(scene, atlasUv, atlases, options, &receivers));
  const std::size_t count = receivers.count();

  TexelDirectRange direct;
  PRT_RETURN_IF_ERROR(bakeTexelDirectRange(scene, receivers, options, 0, count, &direct));
  out->passes.push_back(direct.stats);
  out->texelsOutsideLight = direct.outsideLight;

  TexelPasses passes;
  if (o.interreflection) {
    std::vector<float> previous, current;
    double energy0 = 0.0;
    PRT_RETURN_IF_ERROR(texelFirstBounce(receivers, o.order, direct.shadowed, &previous, &energy0));
    passes.interreflected = previous;
    passes.bounceEnergy.push_back(energy0);
    const std::vector<HitBlockView> views = hitBlockViews(direct.blocks);
    const std::size_t stride = 3 * static_cast<std::size_t>(shCoeffCount(o.order));
    for (int bounce = 1; bounce <= o.maxBounces; ++bounce) {
      // PRTT §4.2's bounce texture: the previous bounce per texel, dilated so that bilinear
      // reads at a chart's edge blend only that chart's values.
      TexelTexture bounceTexture;
      PRT_RETURN_IF_ERROR(scatterTexels(receivers, atlases, previous, stride, options.dilation, &bounceTexture));
      std::vector<double> blockEnergy;
      PassStats stats;
      PRT_RETURN_IF_ERROR(gatherTexelBounceRange(scene, atlasUv, atlases, receivers, options, bounce, 0, views,
                                                 bounceTexture, &current, &blockEnergy, &out->unmappedHits, &stats));
      double energy = 0.0;
      for (double e : blockEnergy) energy += e;  // fixed order: deterministic
      for (std::size_t i = 0; i < current.size(); ++i) passes.interreflected[i] += current[i];
      passes.bounceEnergy.push_back(energy);
      passes.bounces = bounce;
      out->passes.push_back(stats);
      std::swap(previous, current);
      if (!(energy > o.bounceThreshold * energy0)) break;
    }
  }
  passes.unshadowed = std::move(direct.unshadowed);
  passes.shadowed = std::move(direct.shadowed);
  passes.visibility = std::move(direct.visibility);
  // ---- the stored textures, dilated for the client's bilinear filter
  return finishTexelBake(receivers, atlases, options, std::move(passes), out);
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
