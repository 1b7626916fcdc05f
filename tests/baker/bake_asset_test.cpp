// bakeAsset, the baker's library entry point: the same numbers as bakeTransfer on the
// reordered scene, the chosen passes only, local-lighting defaults from the scene, the codec
// applied to every pass, the `started` report before the first progress call, and the texel
// visibility pass (TPFL glossy) with the glossy material split and its refusal of local light.
#include "baker/transfer/bake_asset.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "baker/scene/default_scene.h"
#include "baker/scene/mesh_order.h"
#include "baker/test_scenes.h"
#include "baker/transfer/local_sphere.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

Scene twoObjects() {
  Scene s;
  s.name = "plane and sphere";
  test::addPlane(&s, 2.0f, 12, 0.0f, {0.7f, 0.6f, 0.5f});
  test::addSphere(&s, {0.3f, 0.8f, 0}, 0.7f, 16, 8, {0.4f, 0.8f, 0.3f});
  return s;
}

AssetBakeOptions quick() {
  AssetBakeOptions o;
  o.transfer.order = 4;
  o.transfer.samples = 256;
  o.transfer.maxBounces = 2;
  o.transfer.threads = 2;
  return o;
}

TEST(BakeAsset, HoldsWhatBakeTransferComputesOnTheReorderedScene) {
  Scene reordered = twoObjects();
  optimizeMeshOrder(&reordered);
  BakeOptions transfer = quick().transfer;
  BakeResult expected;
  ASSERT_TRUE(bakeTransfer(reordered, transfer, &expected).isOk());

  BakedAsset asset;
  AssetBakeReport report;
  ASSERT_TRUE(bakeAsset(twoObjects(), quick(), &asset, &report).isOk());
  EXPECT_EQ(asset.positions.size(), reordered.positions.size());
  for (std::size_t v = 0; v < asset.positions.size(); ++v) {
    ASSERT_EQ(asset.positions[v].x, reordered.positions[v].x) << v;
    ASSERT_EQ(asset.positions[v].y, reordered.positions[v].y) << v;
  }
  EXPECT_EQ(asset.indices, reordered.indices);
  ASSERT_EQ(asset.passes.size(), 3u);
  EXPECT_EQ(asset.passes[0].kind, TransferKind::kUnshadowed);
  EXPECT_EQ(asset.passes[0].coeffs, expected.unshadowed);
  EXPECT_EQ(asset.passes[1].coeffs, expected.shadowed);
  EXPECT_EQ(asset.passes[2].coeffs, expected.interreflected);
  EXPECT_EQ(asset.passes[2].channels, 3);
  EXPECT_EQ(asset.passes[2].bounces, expected.bounces);
  EXPECT_EQ(asset.shOrder, 4);
  EXPECT_EQ(asset.samples, 256u);
  EXPECT_EQ(asset.seed, 1u);
  EXPECT_EQ(asset.sampling, "hammersley");
  EXPECT_EQ(asset.name, "plane and sphere");
  EXPECT_EQ(report.vertices, asset.positions.size());
  EXPECT_EQ(report.triangles, asset.indices.size() / 3);
  EXPECT_EQ(report.bounces, expected.bounces);
  EXPECT_EQ(report.bounceEnergy, expected.bounceEnergy);
  EXPECT_TRUE(report.compressed.empty());
}

TEST(BakeAsset, StoresOnlyTheChosenPassesAndItsName) {
  AssetBakeOptions o = quick();
  o.storeUnshadowed = false;
  o.storeInterreflected = false;
  o.name = "renamed";
  BakedAsset asset;
  AssetBakeReport report;
  ASSERT_TRUE(bakeAsset(twoObjects(), o, &asset, &report).isOk());
  ASSERT_EQ(asset.passes.size(), 1u);
  EXPECT_EQ(asset.passes[0].kind, TransferKind::kShadowed);
  EXPECT_EQ(asset.name, "renamed");
  EXPECT_EQ(report.bounces, 0);  // interreflection not stored: not computed either
}

TEST(BakeAsset, LocalLightingDefaultsComeFromTheSceneUnlessGiven) {
  AssetBakeOptions o = quick();
  o.transfer.lighting.model = LightingModel::kLocalSphere;
  o.transfer.lighting.radius = 123.0f;  // ignored: lightRadius decides
  Scene reordered = twoObjects();
  optimizeMeshOrder(&reordered);
  const LightingInfo fallback = defaultLightingSphere(reordered, LightingModel::kLocalSphere);

  BakedAsset asset;
  AssetBakeReport report;
  ASSERT_TRUE(bakeAsset(twoObjects(), o, &asset, &report).isOk());
  EXPECT_EQ(report.lighting.radius, fallback.radius);
  EXPECT_EQ(report.lighting.center.y, fallback.center.y);
  EXPECT_EQ(asset.lighting.radius, fallback.radius);

  o.lightRadius = 5.0f;
  o.lightCenter = Vec3{0.1f, 0.2f, 0.3f};
  ASSERT_TRUE(bakeAsset(twoObjects(), o, &asset, &report).isOk());
  EXPECT_EQ(asset.lighting.radius, 5.0f);
  EXPECT_EQ(asset.lighting.center.z, 0.3f);
  EXPECT_EQ(report.verticesOutsideLight, 0u);
}

TEST(BakeAsset, CompressesEveryPassAndReportsSizes) {
  AssetBakeOptions o = quick();
  TransferCodecSettings q8;
  ASSERT_TRUE(parseTransferSetting("q8", TransferCodecSettings{}, &q8).isOk());
  o.compress = q8;
  BakedAsset asset;
  AssetBakeReport report;
  ASSERT_TRUE(bakeAsset(twoObjects(), o, &asset, &report).isOk());
  ASSERT_EQ(report.compressed.size(), asset.passes.size());
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(4));
  for (std::size_t i = 0; i < asset.passes.size(); ++i) {
    const TransferPass& p = asset.passes[i];
    EXPECT_TRUE(p.coeffs.empty()) << i;  // the floats are dropped once encoded
    EXPECT_EQ(report.compressed[i].kind, p.kind);
    EXPECT_EQ(report.compressed[i].encodedBytes, p.encoded.size());
    EXPECT_EQ(report.compressed[i].floatBytes, report.vertices * n2 * static_cast<std::size_t>(p.channels) * 4);
    EXPECT_LT(report.compressed[i].encodedBytes, report.compressed[i].floatBytes);
    EXPECT_GT(report.compressed[i].codec.relativeError, 0.0);
    EXPECT_LT(report.compressed[i].codec.relativeError, 0.05);
  }
}

TEST(BakeAsset, StartedComesOnceBeforeAnyProgress) {
  AssetBakeOptions o = quick();
  std::atomic<int> progressCalls{0};
  int startedCalls = 0, progressBeforeStart = -1;
  o.transfer.progress = [&](const BakeProgress&) { ++progressCalls; };
  BakedAsset asset;
  AssetBakeReport report;
  const auto started = [&](const AssetBakeReport& r) {
    ++startedCalls;
    progressBeforeStart = progressCalls.load();
    EXPECT_GT(r.vertices, 0u);
    EXPECT_GT(r.triangles, 0u);
  };
  ASSERT_TRUE(bakeAsset(twoObjects(), o, &asset, &report, started).isOk());
  EXPECT_EQ(startedCalls, 1);
  EXPECT_EQ(progressBeforeStart, 0);
  EXPECT_GT(progressCalls.load(), 0);
}

TEST(BakeAsset, PassesTheBakesErrorsThrough) {
  AssetBakeOptions o = quick();
  o.transfer.order = 1;
  BakedAsset asset;
  AssetBakeReport report;
  const Status s = bakeAsset(twoObjects(), o, &asset, &report);
  EXPECT_FALSE(s.isOk());
  EXPECT_NE(s.message().find("order"), std::string::npos) << s.message();
}

// The default room has a lightmap atlas valid at 512 texels a side.
TEST(BakeAsset, StoresTheTexelVisibilityPassWithTheGlossyMaterials) {
  AssetBakeOptions o;
  o.transfer.order = 2;
  o.transfer.samples = 16;
  o.transfer.maxBounces = 0;
  o.transfer.bounceThreshold = 0.0;
  o.storeUnshadowed = o.storeInterreflected = false;
  TexelBakeSettings t;
  t.textureSize = 512;
  t.visibilityOrder = 3;
  o.texels = t;
  TransferCodecSettings f16;
  f16.encoding = TransferEncoding::kFloat16;
  o.compress = f16;
  BakedAsset asset;
  AssetBakeReport report;
  const Status s = bakeAsset(makeDefaultScene(), o, &asset, &report);
  ASSERT_TRUE(s.isOk()) << s.message();
  ASSERT_TRUE(report.texels.has_value());
  EXPECT_EQ(report.texels->visibilityOrder, 3);
  const TransferPass* v = findPass(asset, TransferKind::kShadowed, TransferForm::kVisibility, TransferDomain::kTexel);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v, &asset.passes.back());
  EXPECT_EQ(v->order, 3);
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(v->encoded, &info).isOk());
  EXPECT_EQ(info.order, 3) << "compressed at its own order, not the asset's";
  EXPECT_EQ(info.vertexCount, assetTexelCount(asset));
  // The glossy split: a material per vertex, and the metal torus's diffuse albedo is 0
  // ((1 - metallic) x base colour), as with the matrix bake.
  ASSERT_EQ(asset.specular.size(), asset.positions.size());
  std::size_t glossy = 0, black = 0;
  for (const SpecularMaterial& m : asset.specular) glossy += m.f0.r > 0.0f ? 1 : 0;
  for (const Rgb& a : asset.albedo) black += a.r == 0.0f && a.g == 0.0f && a.b == 0.0f ? 1 : 0;
  EXPECT_GT(glossy, 1000u);
  EXPECT_GT(black, 100u);
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(encodeAsset(asset, &bytes).isOk());

  // TPFL needs distant light: refused before any work, naming the model.
  o.transfer.lighting.model = LightingModel::kLocalSphere;
  bool started = false;
  const Status local = bakeAsset(makeDefaultScene(), o, &asset, &report, [&](const AssetBakeReport&) { started = true; });
  EXPECT_EQ(local.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(local.message().find("needs distant lighting, not local-sphere"), std::string::npos) << local.message();
  EXPECT_FALSE(started);
}

}  // namespace
}  // namespace prt::bake
