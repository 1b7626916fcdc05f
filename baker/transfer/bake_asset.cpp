#include "baker/transfer/bake_asset.h"

#include <utility>

#include "baker/scene/mesh_order.h"
#include "baker/transfer/local_sphere.h"

namespace prt::bake {
namespace {

LightingInfo resolveLighting(const Scene& scene, const AssetBakeOptions& o) {
  LightingInfo l = o.transfer.lighting;
  if (!isLocalLighting(l.model)) return l;
  const LightingInfo fallback = defaultLightingSphere(scene, l.model);
  l.center = o.lightCenter.value_or(fallback.center);
  l.radius = o.lightRadius.value_or(fallback.radius);
  return l;
}

BakedAsset makeAsset(Scene&& scene, BakeResult&& r, const AssetBakeOptions& o, const LightingInfo& lighting) {
  BakedAsset a;
  a.shOrder = r.order;
  a.positions = std::move(scene.positions);
  a.normals = std::move(scene.normals);
  a.albedo = std::move(scene.albedo);
  a.indices = std::move(scene.indices);
  a.name = o.name.value_or(scene.name);
  a.lighting = lighting;
  a.samples = o.transfer.samples;
  a.seed = o.transfer.seed;
  a.sampling = o.transfer.sampling == Sampling::kStratified ? "stratified" : "hammersley";
  if (o.storeUnshadowed) a.passes.push_back({TransferKind::kUnshadowed, 1, 0, std::move(r.unshadowed), {}});
  if (o.storeShadowed) a.passes.push_back({TransferKind::kShadowed, 1, 0, std::move(r.shadowed), {}});
  if (o.storeInterreflected) a.passes.push_back({TransferKind::kInterreflected, 3, r.bounces, std::move(r.interreflected), {}});
  if (o.transfer.glossy) {
    a.passes.push_back({TransferKind::kShadowed, 1, 0, std::move(r.glossyShadowed), {}, TransferForm::kMatrix});
    if (!r.glossyInterreflected.empty()) {
      a.passes.push_back(
          {TransferKind::kInterreflected, 3, r.glossyBounces, std::move(r.glossyInterreflected), {}, TransferForm::kMatrix});
    }
    a.specular = std::move(scene.specular);
  }
  return a;
}

// Encodes every pass with the codec; the floats are dropped once encoded.
Status compressPasses(const TransferCodecSettings& settings, BakedAsset* a, std::vector<CompressedPass>* out) {
  for (TransferPass& pass : a->passes) {
    CompressedPass c;
    c.kind = pass.kind;
    c.form = pass.form;
    c.floatBytes = pass.coeffs.size() * sizeof(float);
    const Status s = pass.form == TransferForm::kMatrix
                         ? encodeTransferMatrix(pass.coeffs, a->shOrder, matrixPackingFor(pass.kind, a->lighting.model),
                                                pass.channels, settings, &pass.encoded, &c.codec)
                         : encodeTransfer(pass.coeffs, a->shOrder, pass.channels, settings, &pass.encoded, &c.codec);
    if (!s.isOk()) {
      return Status::error(s.code(), std::string("cannot compress: ") + transferKindName(pass.kind) + " " +
                                         (pass.form == TransferForm::kMatrix ? "glossy matrix" : "transfer") + ": " +
                                         s.message());
    }
    c.encodedBytes = pass.encoded.size();
    out->push_back(c);
    pass.coeffs.clear();
    pass.coeffs.shrink_to_fit();
  }
  return Status::ok();
}

}  // namespace

Status bakeAsset(Scene&& scene, const AssetBakeOptions& options, BakedAsset* asset, AssetBakeReport* report,
                 const std::function<void(const AssetBakeReport&)>& started) {
  *report = AssetBakeReport{};
  if (options.transfer.glossy) PRT_RETURN_IF_ERROR(applyGlossyMaterials(options.glossyMaterials, &scene));
  optimizeMeshOrder(&scene);
  report->vertices = scene.positions.size();
  report->triangles = scene.indices.size() / 3;
  BakeOptions transfer = options.transfer;
  transfer.lighting = resolveLighting(scene, options);
  transfer.interreflection = options.storeInterreflected;
  report->lighting = transfer.lighting;
  if (started) started(*report);

  BakeResult result;
  PRT_RETURN_IF_ERROR(bakeTransfer(scene, transfer, &result));
  report->bounces = result.bounces;
  report->glossyBounces = result.glossyBounces;
  report->bounceEnergy = result.bounceEnergy;
  report->passes = result.passes;
  report->verticesOutsideLight = result.verticesOutsideLight;

  *asset = makeAsset(std::move(scene), std::move(result), options, transfer.lighting);
  if (options.compress) PRT_RETURN_IF_ERROR(compressPasses(*options.compress, asset, &report->compressed));
  return Status::ok();
}

}  // namespace prt::bake
