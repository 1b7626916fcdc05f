// Bi-scale in the baker (docs/bi-scale.md): the parametric id map's tangents and patch
// coordinates (baker/scene/parametric_id_map.h), bakeAsset storing them with the RTT, its
// refusals, and the paper's reduction through the stored asset: a flat RTT with the asset's
// own tangent frames and patch coordinates gives the diffuse PRT of the same bake.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "baker/rtt/height_patch.h"
#include "baker/rtt/rtt_bake.h"
#include "baker/scene/default_scene.h"
#include "baker/scene/parametric_id_map.h"
#include "baker/transfer/bake_asset.h"
#include "prt/asset.h"
#include "prt/bi_scale.h"
#include "prt/rtt.h"

namespace prt::bake {
namespace {

// A quad in the xz plane (normal +y) whose u runs along +z and v along +x.
Scene uvQuad() {
  Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  s.normals.assign(4, {0, 1, 0});
  s.albedo.assign(4, {0.5f, 0.5f, 0.5f});
  s.indices = {0, 2, 1, 0, 3, 2};
  for (const Vec3& p : s.positions) s.texcoord[0].push_back({p.z, p.x});
  return s;
}

std::vector<std::uint8_t> flatRttBytes(int order, float albedo) {
  HeightPatch flat;
  EXPECT_TRUE(makeProceduralPatch("flat", 8, albedo, &flat).isOk());
  RttSettings s;
  s.order = order;
  s.spatial = 2;
  s.views = 4;
  Rtt rtt;
  EXPECT_TRUE(bakeRtt(flat, s, {}, &rtt).isOk());
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(encodeRtt(rtt, &bytes).isOk());
  return bytes;
}

TEST(ParametricIdMap, TangentsFollowIncreasingUAndPatchUvScales) {
  const Scene s = uvQuad();
  ParametricIdMap map;
  map.patchesPerUv = 4.0;
  std::vector<Vec3> tangents;
  std::vector<float> uv;
  std::size_t fallbacks = 99;
  ASSERT_TRUE(parametricIdMap(s, map, &tangents, &uv, &fallbacks).isOk());
  EXPECT_EQ(fallbacks, 0u);
  ASSERT_EQ(tangents.size(), 4u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(tangents[v].z, 1.0f, 1e-6f) << v;  // u runs along +z
    EXPECT_EQ(uv[2 * v], 4.0f * s.texcoord[0][v].u);
    EXPECT_EQ(uv[2 * v + 1], -4.0f * s.texcoord[0][v].v);  // glTF's v runs down the image
  }
  // The frame's +y, cross(n, t), is the patch's +v: here -x, where v decreases.
  const Vec3 b = cross(s.normals[0], tangents[0]);
  EXPECT_NEAR(b.x, 1.0f, 1e-6f);
}

TEST(ParametricIdMap, RefusesWhatItCannotPlace) {
  Scene s = uvQuad();
  std::vector<Vec3> t;
  std::vector<float> uv;
  ParametricIdMap map;
  map.patchesPerUv = 0.0;
  EXPECT_NE(parametricIdMap(s, map, &t, &uv, nullptr).message().find("patches per UV unit"), std::string::npos);
  map.patchesPerUv = 5000.0;  // 1 x 5000 patch widths: beyond float's precision bound
  EXPECT_NE(parametricIdMap(s, map, &t, &uv, nullptr).message().find("exceeds 4096 patch widths"), std::string::npos);
  map = {};
  map.texcoord = 1;
  s.texcoordAbsent[1] = "the primitive has no TEXCOORD_1";
  EXPECT_NE(parametricIdMap(s, map, &t, &uv, nullptr).message().find("no TEXCOORD_1 for the patch: the primitive has no TEXCOORD_1"),
            std::string::npos);
  s.texcoord[0].clear();
  map.texcoord = -1;
  EXPECT_NE(parametricIdMap(s, map, &t, &uv, nullptr).message().find("neither TEXCOORD_0"), std::string::npos);
}

AssetBakeOptions biScaleOptions(int order, int rttOrder, float albedo) {
  AssetBakeOptions o;
  o.transfer.order = order;
  o.transfer.samples = 256;
  o.transfer.maxBounces = 0;
  o.transfer.glossy = true;
  o.transfer.glossyBounces = 0;
  o.transfer.threads = 2;
  o.storeInterreflected = false;
  o.biScale = AssetBakeOptions::BiScale{};
  o.biScale->rtt = flatRttBytes(rttOrder, albedo);
  return o;
}

TEST(BakeAssetBiScale, RefusesWithoutMatricesOrWithAnRttAboveTheOrder) {
  BakedAsset asset;
  AssetBakeReport report;
  AssetBakeOptions o = biScaleOptions(3, 3, 0.5f);
  o.transfer.glossy = false;
  EXPECT_NE(bakeAsset(makeDefaultScene(), o, &asset, &report).message().find("add --glossy"), std::string::npos);
  o = biScaleOptions(3, 4, 0.5f);
  EXPECT_NE(bakeAsset(makeDefaultScene(), o, &asset, &report).message().find("the RTT is order 4, above the bake's order 3"),
            std::string::npos);
}

// The default room (lightmap UVs in TEXCOORD_1) baked with a flat RTT of albedo 0.7: the
// asset holds the RTT, a tangent per vertex and patch coordinates, and bi-scale shading from
// them equals 0.7 x the shadowed diffuse PRT of the same bake (the clamped cosine at order 5
// against the exact one: 0.47% of the peak in rtt_bake_tests; Monte Carlo noise is shared).
TEST(BakeAssetBiScale, FlatRttThroughTheStoredFramesIsDiffusePrt) {
  BakedAsset asset;
  AssetBakeReport report;
  ASSERT_TRUE(bakeAsset(makeDefaultScene(), biScaleOptions(5, 5, 0.7f), &asset, &report).isOk());
  const std::size_t V = asset.positions.size();
  ASSERT_EQ(asset.tangents.size(), V);
  ASSERT_EQ(asset.patchUv.size(), 2 * V);
  EXPECT_EQ(report.tangentFallbacks, 0u);
  std::vector<std::uint8_t> file;
  ASSERT_TRUE(encodeAsset(asset, &file).isOk());
  Rtt rtt;
  ASSERT_TRUE(decodeRtt(asset.rtt, &rtt).isOk());
  const TransferPass* matrix = findPass(asset, TransferKind::kShadowed, TransferForm::kMatrix);
  const TransferPass* vector = findPass(asset, TransferKind::kShadowed, TransferForm::kVector);
  ASSERT_TRUE(matrix != nullptr && vector != nullptr);
  std::vector<TangentFrame> frames(V);
  for (std::size_t v = 0; v < V; ++v) frames[v] = {asset.tangents[v], asset.normals[v]};
  std::vector<Rgb> light(25);
  for (int i = 0; i < 25; ++i) light[i] = {0.6f - 0.02f * i, 0.3f + 0.01f * i, (i % 4) * 0.05f};
  light[0] = {1.6f, 1.3f, 1.0f};
  light[2] = {0.9f, 0.8f, 0.7f};  // light from above
  const Vec3 eye{0.5f, 1.6f, 3.0f};
  std::vector<float> biScale(3 * V);
  ASSERT_TRUE(biScaleExitRadiance(rtt, matrix->coeffs, 5, matrixPackingFor(TransferKind::kShadowed, asset.lighting.model), 1,
                                  asset.positions, frames, asset.patchUv, eye, true, light, biScale)
                  .isOk());
  double worst = 0.0, peak = 0.0;
  for (std::size_t v = 0; v < V; ++v) {
    for (int c = 0; c < 3; ++c) {
      double diffuse = 0.0;
      for (int i = 0; i < 25; ++i) diffuse += vector->coeffs[v * 25 + i] * (c == 0 ? light[i].r : c == 1 ? light[i].g : light[i].b);
      diffuse *= 0.7;
      worst = std::max(worst, std::fabs(diffuse - biScale[3 * v + c]));
      peak = std::max(peak, std::fabs(diffuse));
    }
  }
  std::printf("default room, flat RTT through the stored frames vs diffuse PRT: worst %.2e of peak %.3f\n", worst, peak);
  EXPECT_GT(peak, 0.1);
  EXPECT_LT(worst, 0.02 * peak);
}

// The synthesised id map instead of the UVs: one atlas (the room's lightmap UVs), a placement
// per cell, an index per atlas texel, tangents along the placements' direction field.
TEST(BakeAssetBiScale, SynthesisedIdMapOverOneAtlas) {
  AssetBakeOptions o = biScaleOptions(3, 3, 0.5f);
  IdMapSettings m;
  m.patchWidth = 0.1;
  o.biScale->synthesised = m;
  o.biScale->idMapSize = 256;
  BakedAsset asset;
  AssetBakeReport report;
  ASSERT_TRUE(bakeAsset(makeDefaultScene(), o, &asset, &report).isOk());
  ASSERT_EQ(asset.atlases.size(), 1u);
  EXPECT_EQ(asset.atlases[0].width, 256u);
  EXPECT_EQ(asset.idMap.size(), 256u * 256u);
  EXPECT_TRUE(asset.patchUv.empty());
  EXPECT_GT(asset.patchPlacements.size(), 100u);
  EXPECT_EQ(report.placements, asset.patchPlacements.size());
  std::size_t placed = 0;
  for (std::size_t t = 0; t < asset.idMap.size(); ++t) {
    if (asset.idMap[t] == kNoPlacement) continue;
    ++placed;
    ASSERT_LT(asset.idMap[t], asset.patchPlacements.size());
    ASSERT_EQ(asset.texelCoverage[t], static_cast<std::uint8_t>(TexelCoverage::kSampled));
  }
  EXPECT_GT(placed, asset.idMap.size() / 3);
  for (std::size_t v = 0; v < asset.positions.size(); ++v) {
    const Vec3 t = patchTangent(asset.normals[v]);
    ASSERT_EQ(asset.tangents[v].x, t.x);
    ASSERT_EQ(asset.tangents[v].z, t.z);
  }
  std::vector<std::uint8_t> file;
  ASSERT_TRUE(encodeAsset(asset, &file).isOk());
  o.texels = TexelBakeSettings{};
  EXPECT_NE(bakeAsset(makeDefaultScene(), o, &asset, &report).message().find("cannot share one atlas yet"), std::string::npos);

  // Per triangle (the default): no atlas, a placement per triangle, every one placed.
  o.texels.reset();
  o.biScale->idMapSize = 0;
  ASSERT_TRUE(bakeAsset(makeDefaultScene(), o, &asset, &report).isOk());
  EXPECT_TRUE(asset.idMapPerTriangle);
  EXPECT_TRUE(asset.atlases.empty() && asset.atlasUv.empty());
  ASSERT_EQ(asset.idMap.size(), asset.indices.size() / 3);
  for (std::uint16_t id : asset.idMap) ASSERT_LT(id, asset.patchPlacements.size());
  ASSERT_TRUE(encodeAsset(asset, &file).isOk());
  BakedAsset back;
  ASSERT_TRUE(decodeAsset(file, &back).isOk());
  EXPECT_TRUE(back.idMapPerTriangle);
  EXPECT_EQ(back.idMap, asset.idMap);
}

}  // namespace
}  // namespace prt::bake
