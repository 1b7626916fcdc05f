#include "baker/transfer/bake_asset.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "baker/scene/mesh_order.h"
#include "baker/scene/uv_atlas_choice.h"
#include "baker/transfer/local_sphere.h"
#include "baker/transfer/texel_bake.h"
#include "baker/transfer/texture_sets.h"
#include "prt/glossy_codec_weights.h"
#include "prt/rtt.h"

namespace prt::bake {
namespace {

bool wantsVisibility(const AssetBakeOptions& o) { return o.texels && o.texels->visibilityOrder > 0; }

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
  }
  // Matrix and visibility passes both shade with the vertices' glossy materials.
  if (o.transfer.glossy || wantsVisibility(o)) a.specular = std::move(scene.specular);
  return a;
}

// Encodes every pass with the codec, matrix passes with `matrices`; the floats are dropped once
// encoded.
Status compressPasses(const TransferCodecSettings& settings, const TransferCodecSettings& matrices, BakedAsset* a,
                      std::vector<CompressedPass>* out) {
  // Matrix CPCA fits in glossy exit radiance's metric: rows weighted by the asset's sharpest
  // lobe (prt/glossy_codec_weights.h; docs/glossy.md "Compressing in the exit-radiance metric").
  TransferCodecSettings matrixSettings = matrices;
  // A bi-scale asset's matrices are dotted with the RTT, not convolved with a lobe: every row
  // counts alike there (docs/bi-scale.md).
  if (matrices.encoding == TransferEncoding::kCpca && a->rtt.empty()) {
    if (Status s = glossyMatrixRowWeights(a->shOrder, a->specular, &matrixSettings.cpcaMatrixRowWeights); !s.isOk()) return s;
  }
  for (TransferPass& pass : a->passes) {
    CompressedPass c;
    c.kind = pass.kind;
    c.form = pass.form;
    c.domain = pass.domain;
    c.floatBytes = pass.coeffs.size() * sizeof(float);
    // A visibility pass is a vector pass of its own order (its blob's order is the pass's).
    const int order = pass.form == TransferForm::kVisibility ? pass.order : a->shOrder;
    const Status s = pass.form == TransferForm::kMatrix
                         ? encodeTransferMatrix(pass.coeffs, a->shOrder, matrixPackingFor(pass.kind, a->lighting.model),
                                                pass.channels, matrixSettings, &pass.encoded, &c.codec)
                         : encodeTransfer(pass.coeffs, order, pass.channels, settings, &pass.encoded, &c.codec);
    if (!s.isOk()) {
      return Status::error(s.code(), std::string("cannot compress: ") + transferKindName(pass.kind) + " " +
                                         (pass.form == TransferForm::kMatrix         ? "glossy matrix"
                                          : pass.form == TransferForm::kVisibility ? "texel visibility"
                                          : pass.domain == TransferDomain::kTexel  ? "texel transfer"
                                                                                   : "transfer") + ": " +
                                         s.message());
    }
    c.encodedBytes = pass.encoded.size();
    out->push_back(c);
    pass.coeffs.clear();
    pass.coeffs.shrink_to_fit();
  }
  return Status::ok();
}

// The texel passes of `scene` over its chosen atlas, appended to *passes (unshadowed,
// shadowed, interreflected as options stores them, then the visibility pass when asked for;
// domain kTexel); fills the atlas fields.
struct TexelBake {
  std::vector<float> atlasUv;
  std::vector<TextureAtlas> atlases;
  std::vector<std::uint8_t> coverage;
  std::vector<std::int16_t> normals;  // TexelBakeResult::normals
  std::vector<TransferPass> passes;
};

// The asset's texel fields of a finished texel bake over `uv`: the atlas UVs, the coverage,
// the normals and the passes options store (out->atlases are set by the caller).
void fillTexelBake(TexelBakeResult&& r, std::span<const Uv> uv, const AssetBakeOptions& o, TexelBake* out) {
  out->atlasUv.resize(2 * uv.size());
  for (std::size_t v = 0; v < uv.size(); ++v) {
    out->atlasUv[2 * v] = uv[v].u;
    out->atlasUv[2 * v + 1] = uv[v].v;
  }
  out->coverage = std::move(r.coverage);
  out->normals = std::move(r.normals);
  auto texelPass = [](TransferKind kind, int channels, int bounces, std::vector<float>&& coeffs) {
    TransferPass p{kind, channels, bounces, std::move(coeffs), {}};
    p.domain = TransferDomain::kTexel;
    return p;
  };
  out->passes.clear();
  if (o.storeUnshadowed) out->passes.push_back(texelPass(TransferKind::kUnshadowed, 1, 0, std::move(r.unshadowed)));
  if (o.storeShadowed) out->passes.push_back(texelPass(TransferKind::kShadowed, 1, 0, std::move(r.shadowed)));
  if (o.storeInterreflected) {
    out->passes.push_back(texelPass(TransferKind::kInterreflected, 3, r.bounces, std::move(r.interreflected)));
  }
  if (r.visibilityOrder > 0) {
    TransferPass v = texelPass(TransferKind::kShadowed, 1, 0, std::move(r.visibility));
    v.form = TransferForm::kVisibility;
    v.order = r.visibilityOrder;
    out->passes.push_back(std::move(v));
  }
}

// The texel bake's part of the asset, after the vertex passes makeAsset put there.
void attachTexels(TexelBake&& texel, const AssetBakeOptions& o, BakedAsset* asset) {
  if (!o.texels->keepVertexPasses) {
    std::erase_if(asset->passes, [](const TransferPass& p) { return p.form == TransferForm::kVector; });
  }
  for (TransferPass& p : texel.passes) asset->passes.push_back(std::move(p));
  asset->atlasUv = std::move(texel.atlasUv);
  asset->atlases = std::move(texel.atlases);
  asset->texelCoverage = std::move(texel.coverage);
  asset->texelNormals = std::move(texel.normals);
}

// The texel passes over the planned atlases; `triangleAtlas` per triangle of the (reordered)
// scene, grouped in ascending runs (empty: one atlas).
Status bakeTexels(const Scene& scene, const AssetBakeOptions& o, const BakeOptions& transfer, TextureSetPlan&& plan,
                  TexelBake* out, TexelBakeReport* report) {
  const std::vector<Uv>& uv = scene.texcoord[plan.texcoord];
  const std::size_t triangles = scene.indices.size() / 3;
  out->atlases = texelAtlasesOf(plan, triangles);
  for (std::size_t a = 0; a < plan.atlases.size(); ++a) plan.atlases[a].triangles = out->atlases[a].triangleCount;
  report->texcoord = plan.atlases.front().texcoord;
  for (const TexelAtlasReport& a : plan.atlases) {
    if (a.texcoord != report->texcoord) report->texcoord = -1;
  }
  report->size = plan.atlases.front().size;
  report->charts = 0;
  for (const TexelAtlasReport& a : plan.atlases) report->charts += a.charts;
  report->rejected = std::move(plan.rejected);
  report->sets = std::move(plan.reason);
  if (plan.atlases.size() == 1) report->generated = plan.atlases.front().generated;
  const TexelBakeOptions options = texelBakeOptions(o, transfer);
  TexelBakeResult r;
  PRT_RETURN_IF_ERROR(bakeTexelTransfer(scene, uv, out->atlases, options, &r));
  report->texels = r.texels;
  report->sampledTexels = r.sampledTexels;
  report->normalMappedTexels = r.normalMappedTexels;
  report->bounces = r.bounces;
  report->visibilityOrder = r.visibilityOrder;
  report->passes = r.passes;
  // Per atlas: its sampled texels, and the texel density its triangles get.
  for (std::size_t a = 0, firstTexel = 0; a < out->atlases.size(); ++a) {
    const TextureAtlas& atlas = out->atlases[a];
    const std::size_t texels = std::size_t{atlas.width} * atlas.height;
    TexelAtlasReport& ar = plan.atlases[a];
    ar.sampledTexels = static_cast<std::uint64_t>(std::count(r.coverage.begin() + static_cast<std::ptrdiff_t>(firstTexel),
                                                             r.coverage.begin() + static_cast<std::ptrdiff_t>(firstTexel + texels),
                                                             std::uint8_t{1}));
    double surface = 0.0, area = 0.0;
    for (std::size_t tri = atlas.firstTriangle; tri < atlas.firstTriangle + atlas.triangleCount; ++tri) {
      const std::uint32_t i0 = scene.indices[3 * tri], i1 = scene.indices[3 * tri + 1], i2 = scene.indices[3 * tri + 2];
      surface += 0.5 * length(cross(scene.positions[i1] - scene.positions[i0], scene.positions[i2] - scene.positions[i0]));
      const double du1 = uv[i1].u - uv[i0].u, dv1 = uv[i1].v - uv[i0].v, du2 = uv[i2].u - uv[i0].u, dv2 = uv[i2].v - uv[i0].v;
      area += 0.5 * std::abs(du1 * dv2 - dv1 * du2) * atlas.width * atlas.height;
    }
    ar.texelsPerMetre = surface > 0.0 ? std::sqrt(area / surface) : 0.0;
    firstTexel += texels;
  }
  report->atlases = std::move(plan.atlases);

  fillTexelBake(std::move(r), uv, o, out);
  return Status::ok();
}

// The one atlas a synthesised id map lies on: the scene's UVs where valid, else generated.
TexelBakeSettings idMapAtlasSettings(const AssetBakeOptions::BiScale& b) {
  TexelBakeSettings t;
  t.textureSize = b.idMapSize;
  t.sets = TextureSets::kScene;
  t.unwrap = b.unwrap;
  if (t.unwrap) {
    t.unwrap->size = b.idMapSize;
    t.unwrap->padding = t.padding;
  }
  return t;
}

struct IdMapAsset {
  std::vector<float> atlasUv;
  TextureAtlas atlas;
  SynthesisedIdMap map;
};

// The synthesised id map over the planned atlas of the prepared (reordered) scene, and the
// vertex tangents along the same direction field as the placements' axes.
Status synthesiseIdMapAsset(const Scene& scene, const TextureSetPlan& plan, const AssetBakeOptions::BiScale& b,
                            std::vector<Vec3>* tangents, IdMapAsset* out) {
  static const std::vector<Uv> kNone;
  const std::vector<Uv>& uv = b.idMapSize > 0 ? scene.texcoord[plan.texcoord] : kNone;
  out->atlasUv.resize(2 * uv.size());
  for (std::size_t v = 0; v < uv.size(); ++v) {
    out->atlasUv[2 * v] = uv[v].u;
    out->atlasUv[2 * v + 1] = uv[v].v;
  }
  tangents->resize(scene.normals.size());
  if (b.idMapSize == 0) {
    PRT_RETURN_IF_ERROR(synthesiseTriangleIdMap(scene.positions, scene.normals, scene.indices, *b.synthesised, &out->map));
  } else {
    const auto side = static_cast<std::uint32_t>(plan.atlases.front().size);
    out->atlas = {side, side, 0, static_cast<std::uint32_t>(scene.indices.size() / 3)};
    PRT_RETURN_IF_ERROR(synthesiseIdMap(scene.positions, scene.normals, scene.indices, uv, {&out->atlas, 1}, *b.synthesised, &out->map));
  }
  for (std::size_t v = 0; v < scene.normals.size(); ++v) (*tangents)[v] = patchTangent(scene.normals[v]);
  return Status::ok();
}

// Bi-scale needs the macro-scale matrices, an RTT of at most the bake's order and a UV set.
Status checkBiScaleOptions(const AssetBakeOptions& options, const Scene& scene) {
  if (!options.transfer.glossy) {
    return Status::error(StatusCode::kInvalidArgument, "bi-scale needs the glossy matrix passes (the macro scale): add --glossy");
  }
  Rtt rtt;
  if (Status s = decodeRtt(options.biScale->rtt, &rtt); !s.isOk()) return Status::error(s.code(), "the RTT: " + s.message());
  if (rtt.order > options.transfer.order) {
    return Status::error(StatusCode::kInvalidArgument, "the RTT is order " + std::to_string(rtt.order) + ", above the bake's order " +
                                                           std::to_string(options.transfer.order));
  }
  if (options.biScale->synthesised) {
    if (options.texels && options.biScale->idMapSize > 0) {
      return Status::error(StatusCode::kInvalidArgument,
                           "the synthesised id map and --texels cannot share one atlas yet: give one of them (or --patches-per-uv)");
    }
    return Status::ok();
  }
  int set = 0;
  return parametricUvSet(scene, options.biScale->placement, &set);
}

}  // namespace

Status texelAtlasSize(const Scene& scene, int texcoord, const TexelBakeSettings& settings, int* side) {
  auto outOfRange = [](const std::string& what, double value) {
    return Status::error(StatusCode::kInvalidArgument, what + " " + std::to_string(value) + " is outside 1 … " +
                                                           std::to_string(kMaxAtlasSize) + " texels");
  };
  if (settings.textureSize != 0) {
    if (settings.textureSize < 1 || settings.textureSize > kMaxAtlasSize) {
      return outOfRange("texture size", settings.textureSize);
    }
    *side = settings.textureSize;
    return Status::ok();
  }
  if (!(settings.texelsPerUnit >= 0.0) || !std::isfinite(settings.texelsPerUnit)) {
    return Status::error(StatusCode::kInvalidArgument, "texels per unit must be finite and >= 0");
  }
  if (settings.texelsPerUnit == 0.0) {
    *side = 512;
    return Status::ok();
  }
  if (texcoord < 0 || texcoord > 1 || scene.texcoord[texcoord].size() != scene.positions.size()) {
    return Status::error(StatusCode::kInvalidArgument, "texels per unit needs the atlas UV set");
  }
  const std::vector<Uv>& uv = scene.texcoord[texcoord];
  double surface = 0.0, uvArea = 0.0;
  for (std::size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
    const std::uint32_t a = scene.indices[t], b = scene.indices[t + 1], c = scene.indices[t + 2];
    surface += 0.5 * length(cross(scene.positions[b] - scene.positions[a], scene.positions[c] - scene.positions[a]));
    const double du1 = uv[b].u - uv[a].u, dv1 = uv[b].v - uv[a].v, du2 = uv[c].u - uv[a].u, dv2 = uv[c].v - uv[a].v;
    uvArea += 0.5 * std::abs(du1 * dv2 - dv1 * du2);
  }
  if (!(uvArea > 0.0)) return Status::error(StatusCode::kInvalidArgument, "the UV set has no area");
  const double wanted = std::ceil(settings.texelsPerUnit * std::sqrt(surface / uvArea));
  if (!(wanted >= 1.0 && wanted <= kMaxAtlasSize)) {
    return outOfRange("texels per unit " + std::to_string(settings.texelsPerUnit) + " needs an atlas side of", wanted);
  }
  *side = static_cast<int>(wanted);
  return Status::ok();
}

void prepareVertexBake(const AssetBakeOptions& options, Scene* scene, BakeOptions* transfer,
                       std::vector<std::uint32_t>* triangleGroup) {
  if (triangleGroup) {
    optimizeMeshOrder(scene, triangleGroup);
  } else {
    optimizeMeshOrder(scene);
  }
  *transfer = vertexBakeOptions(options, *scene);
}

BakeOptions vertexBakeOptions(const AssetBakeOptions& options, const Scene& prepared) {
  BakeOptions transfer = options.transfer;
  transfer.lighting = resolveLighting(prepared, options);
  transfer.interreflection = options.storeInterreflected;
  return transfer;
}

Status assembleVertexAsset(Scene&& scene, BakeResult&& result, const AssetBakeOptions& options,
                           const LightingInfo& lighting, BakedAsset* asset, std::vector<CompressedPass>* compressed) {
  *asset = makeAsset(std::move(scene), std::move(result), options, lighting);
  if (options.compress) {
    PRT_RETURN_IF_ERROR(compressPasses(*options.compress, options.compressMatrices.value_or(*options.compress), asset, compressed));
  }
  return Status::ok();
}

Status bakeAsset(Scene&& scene, const AssetBakeOptions& options, BakedAsset* asset, AssetBakeReport* report,
                 const std::function<void(const AssetBakeReport&)>& started) {
  *report = AssetBakeReport{};
  // Checked before any work (the texel bake would refuse it too, but only after the atlas).
  if (wantsVisibility(options) && isLocalLighting(options.transfer.lighting.model)) {
    return Status::error(StatusCode::kInvalidArgument,
                         std::string("the texel visibility pass (TPFL glossy) needs distant lighting, not ") +
                             lightingModelName(options.transfer.lighting.model) +
                             ": TPFL multiplies each texel's visibility with the distant light");
  }
  if (options.biScale) PRT_RETURN_IF_ERROR(checkBiScaleOptions(options, scene));
  TextureSetPlan atlas;
  const bool synthesised = options.biScale && options.biScale->synthesised;
  BakeOptions transfer;
  PRT_RETURN_IF_ERROR(prepareAssetScene(options, &scene, &transfer, &atlas));
  report->vertices = scene.positions.size();
  report->triangles = scene.indices.size() / 3;
  report->lighting = transfer.lighting;
  // In the final vertex order, before the bake: a coordinate out of range fails it early.
  std::vector<Vec3> tangents;
  std::vector<float> patchUv;
  IdMapAsset idMap;
  if (synthesised) {
    PRT_RETURN_IF_ERROR(synthesiseIdMapAsset(scene, atlas, *options.biScale, &tangents, &idMap));
    report->placements = idMap.map.placements.size();
    report->idMapSize = options.biScale->idMapSize;
  } else if (options.biScale) {
    PRT_RETURN_IF_ERROR(parametricIdMap(scene, options.biScale->placement, &tangents, &patchUv, &report->tangentFallbacks));
  }
  if (options.texels) {
    // What `started` can already say about the texture set; bakeTexels fills in the rest.
    report->texels = TexelBakeReport{};
    report->texels->sets = atlas.reason;
    report->texels->atlases = atlas.atlases;
  }
  if (started) started(*report);

  TexelBake texel;
  if (options.texels) {
    TexelBakeReport texelReport;
    PRT_RETURN_IF_ERROR(bakeTexels(scene, options, transfer, std::move(atlas), &texel, &texelReport));
    report->texels = std::move(texelReport);
  }

  BakeResult result;
  PRT_RETURN_IF_ERROR(bakeTransfer(scene, transfer, &result));
  report->bounces = result.bounces;
  report->glossyBounces = result.glossyBounces;
  report->bounceEnergy = result.bounceEnergy;
  report->passes = result.passes;
  report->verticesOutsideLight = result.verticesOutsideLight;

  *asset = makeAsset(std::move(scene), std::move(result), options, transfer.lighting);
  if (options.biScale) {
    asset->rtt = options.biScale->rtt;
    asset->tangents = std::move(tangents);
    asset->patchUv = std::move(patchUv);
    if (synthesised) {
      asset->patchPlacements = std::move(idMap.map.placements);
      asset->idMap = std::move(idMap.map.placementOfTexel);
      asset->idMapPerTriangle = options.biScale->idMapSize == 0;
      if (!asset->idMapPerTriangle) {
        asset->atlasUv = std::move(idMap.atlasUv);
        asset->atlases = {idMap.atlas};
        asset->texelCoverage.resize(asset->idMap.size());
        for (std::size_t t = 0; t < asset->idMap.size(); ++t) {
          asset->texelCoverage[t] = static_cast<std::uint8_t>(asset->idMap[t] == kNoPlacement ? TexelCoverage::kEmpty : TexelCoverage::kSampled);
        }
      }
    }
  }
  if (options.texels) attachTexels(std::move(texel), options, asset);
  if (options.compress) {
    PRT_RETURN_IF_ERROR(
        compressPasses(*options.compress, options.compressMatrices.value_or(*options.compress), asset, &report->compressed));
  }
  return Status::ok();
}

Status prepareAssetScene(const AssetBakeOptions& options, Scene* scene, BakeOptions* transfer, TextureSetPlan* atlas) {
  // A visibility pass is glossy too: it shades with the split's lobe, and the diffuse passes
  // must then hold the split's diffuse part, exactly as with transfer.glossy.
  if (options.transfer.glossy || wantsVisibility(options)) {
    PRT_RETURN_IF_ERROR(applyGlossyMaterials(options.glossyMaterials, scene));
  }
  // Before the vertex order: a generated atlas splits vertices at its seams, and texture sets
  // split them between objects. The order keeps each atlas's triangles contiguous (the
  // asset's atlases are runs of triangles).
  *atlas = TextureSetPlan{};
  if (options.texels) PRT_RETURN_IF_ERROR(planTextureSets(*options.texels, scene, atlas));
  // A synthesised id map lies on one atlas of its own (checkBiScaleOptions refuses it with texels).
  if (options.biScale && options.biScale->synthesised && options.biScale->idMapSize > 0) {
    PRT_RETURN_IF_ERROR(planTextureSets(idMapAtlasSettings(*options.biScale), scene, atlas));
  }
  prepareVertexBake(options, scene, transfer, &atlas->triangleAtlas);
  return Status::ok();
}

std::vector<TextureAtlas> texelAtlasesOf(const TextureSetPlan& plan, std::size_t triangles) {
  std::vector<TextureAtlas> atlases;
  for (std::size_t a = 0, first = 0; a < plan.atlases.size(); ++a) {
    std::size_t end = first;
    if (plan.triangleAtlas.empty()) {
      end = triangles;
    } else {
      while (end < triangles && plan.triangleAtlas[end] == a) ++end;
    }
    const auto side = static_cast<std::uint32_t>(plan.atlases[a].size);
    atlases.push_back(TextureAtlas{side, side, static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(end - first)});
    first = end;
  }
  return atlases;
}

TexelBakeOptions texelBakeOptions(const AssetBakeOptions& options, const BakeOptions& transfer) {
  TexelBakeOptions t;
  t.transfer = transfer;
  t.transfer.glossy = false;  // glossy stays per vertex (matrices)
  t.dilation = options.texels->dilation;
  t.visibilityOrder = options.texels->visibilityOrder;
  if (transfer.progress) {
    // The same bar as the vertex passes, named "texel direct", "texel bounce N".
    t.transfer.progress = [&transfer](const BakeProgress& p) {
      const std::string name = std::string("texel ") + p.pass;
      transfer.progress({name.c_str(), p.done, p.total, p.rays});
    };
  }
  return t;
}

Status assembleTexelAsset(Scene&& scene, BakeResult&& vertex, TexelBakeResult&& texels, std::span<const Uv> atlasUv,
                          std::vector<TextureAtlas> atlases, const AssetBakeOptions& options, const LightingInfo& lighting,
                          BakedAsset* asset, std::vector<CompressedPass>* compressed) {
  TexelBake texel;
  texel.atlases = std::move(atlases);
  fillTexelBake(std::move(texels), atlasUv, options, &texel);
  *asset = makeAsset(std::move(scene), std::move(vertex), options, lighting);
  attachTexels(std::move(texel), options, asset);
  if (options.compress) {
    PRT_RETURN_IF_ERROR(compressPasses(*options.compress, options.compressMatrices.value_or(*options.compress), asset, compressed));
  }
  return Status::ok();
}

}  // namespace prt::bake
