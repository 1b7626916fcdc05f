// Asset format 1.7's bi-scale sections (docs/asset-format.md, "Bi-scale"): tangents, patch uv
// and an RTT round-trip and decode on their own (decodeAssetBiScale, the progressive client's
// path); checkAsset and the reader refuse the same broken values; a file missing one of the
// three, or holding them without a matrix pass, is refused by name; every cut and byte flip
// of a bi-scale file is rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "asset_raw_file.h"
#include "prt/asset.h"
#include "prt/rtt.h"
#include "prt/transfer_matrix.h"

namespace prt {
namespace {

using test::Bytes;
using test::encodeOrDie;
using test::expectError;

Bytes smallRtt(int order) {
  Rtt rtt;
  rtt.order = order;
  rtt.channels = 1;
  rtt.spatial = 2;
  rtt.views = 2;
  rtt.coeffs.resize(rtt.coeffCount());
  for (std::size_t i = 0; i < rtt.coeffs.size(); ++i) rtt.coeffs[i] = 0.01f * static_cast<float>(i % 17);
  Bytes out;
  EXPECT_TRUE(encodeRtt(rtt, &out).isOk());
  return out;
}

// A strip of V vertices on the plane y = 0 (normal +y) with a shadowed matrix pass and the
// bi-scale sections: tangents along +x turned slightly in the plane, patch uv from x and z.
BakedAsset biScaleAsset(int order, std::size_t V) {
  BakedAsset a;
  a.shOrder = order;
  for (std::size_t v = 0; v < V; ++v) {
    const float t = static_cast<float>(v);
    a.positions.push_back({t, 0.0f, 0.5f * t});
    a.normals.push_back({0.0f, 1.0f, 0.0f});
    a.albedo.push_back({0.5f, 0.5f, 0.5f});
    a.specular.push_back({{0.0f, 0.0f, 0.0f}, 0.0f, 0.0f});
    const float angle = 0.1f * t;
    a.tangents.push_back({std::cos(angle), 0.0f, std::sin(angle)});
    a.patchUv.push_back(3.0f * t);
    a.patchUv.push_back(-1.5f * t);
  }
  for (std::size_t v = 0; v + 2 < V; ++v) {
    for (std::size_t k = 0; k < 3; ++k) a.indices.push_back(static_cast<std::uint32_t>(v + k));
  }
  TransferPass m;
  m.kind = TransferKind::kShadowed;
  m.form = TransferForm::kMatrix;
  m.coeffs.resize(V * matrixEntryCount(order, MatrixPacking::kSymmetric));
  for (std::size_t i = 0; i < m.coeffs.size(); ++i) m.coeffs[i] = 0.001f * static_cast<float>(i % 31);
  a.passes.push_back(m);
  a.rtt = smallRtt(order);
  a.name = "bi-scale";
  return a;
}

TEST(AssetBiScale, RoundTripsAndDecodesOnItsOwn) {
  const BakedAsset a = biScaleAsset(3, 6);
  const Bytes file = encodeOrDie(a);
  BakedAsset out;
  ASSERT_TRUE(decodeAsset(file, &out).isOk());
  EXPECT_EQ(out.rtt, a.rtt);
  EXPECT_EQ(out.patchUv, a.patchUv);
  ASSERT_EQ(out.tangents.size(), a.tangents.size());
  for (std::size_t v = 0; v < a.tangents.size(); ++v) {
    EXPECT_EQ(out.tangents[v].x, a.tangents[v].x);
    EXPECT_EQ(out.tangents[v].z, a.tangents[v].z);
  }
  BakedAsset alone;
  ASSERT_TRUE(decodeAssetBiScale(file, &alone).isOk());
  EXPECT_EQ(alone.rtt, a.rtt);
  EXPECT_EQ(alone.patchUv, a.patchUv);
  EXPECT_EQ(alone.tangents.size(), a.tangents.size());
  EXPECT_TRUE(alone.positions.empty());  // the rest of *out is left alone
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(file, &summary).isOk());
  EXPECT_EQ(summary.versionMinor, 7);

  // A file without them decodes them empty.
  BakedAsset plain = a;
  plain.rtt.clear();
  plain.tangents.clear();
  plain.patchUv.clear();
  BakedAsset none = a;
  ASSERT_TRUE(decodeAssetBiScale(encodeOrDie(plain), &none).isOk());
  EXPECT_TRUE(none.rtt.empty() && none.tangents.empty() && none.patchUv.empty());
}

TEST(AssetBiScale, CheckAssetRefusesBrokenSections) {
  Bytes out;
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.rtt.clear();
    expectError(encodeAsset(a, &out), StatusCode::kInvalidArgument, "but no RTT");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.passes[0].form = TransferForm::kVector;
    a.passes[0].coeffs.assign(4 * 4, 0.1f);
    a.specular.clear();
    expectError(encodeAsset(a, &out), StatusCode::kInvalidArgument, "no vertex matrix pass");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.tangents.pop_back();
    expectError(encodeAsset(a, &out), StatusCode::kSizeMismatch, "bi-scale needs 1 and 2 per vertex");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.tangents[2] = {1.01f, 0.0f, 0.0f};
    expectError(encodeAsset(a, &out), StatusCode::kInvalidArgument, "tangent of vertex 2 has length");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.tangents[1] = {0.0f, 1.0f, 0.0f};
    expectError(encodeAsset(a, &out), StatusCode::kInvalidArgument, "tangent of vertex 1 is not orthogonal");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.tangents[3].x = NAN;
    expectError(encodeAsset(a, &out), StatusCode::kNotFinite, "tangent of vertex 3 is not finite");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.patchUv[5] = 5000.0f;
    expectError(encodeAsset(a, &out), StatusCode::kInvalidArgument, "patch uv of vertex 2 v is");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.rtt = smallRtt(3);
    expectError(encodeAsset(a, &out), StatusCode::kInvalidArgument, "RTT: order 3 exceeds the asset's order 2");
  }
  {
    BakedAsset a = biScaleAsset(2, 4);
    a.rtt[a.rtt.size() - 1] ^= 1;  // the RTT's own checksum catches a damaged byte
    expectError(encodeAsset(a, &out), StatusCode::kChecksumMismatch, "RTT: ");
  }
}

// Files the writer would refuse, crafted section by section: the reader names the problem.
TEST(AssetBiScale, TheReaderRefusesWhatTheWriterWould) {
  const Bytes good = encodeOrDie(biScaleAsset(2, 5));
  const auto type = [](AssetSectionType t) { return static_cast<std::uint32_t>(t); };
  BakedAsset out;
  for (AssetSectionType dropped : {AssetSectionType::kTangents, AssetSectionType::kPatchUv, AssetSectionType::kRtt}) {
    test::RawAsset r = test::split(good);
    std::erase_if(r.sections, [&](const test::RawSection& s) { return s.type == type(dropped); });
    expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "the asset has bi-scale sections but no");
  }
  {
    test::RawAsset r = test::split(good);
    float bent[3] = {0.6f, 0.8f, 0.0f};  // unit, but not orthogonal to the normal +y
    test::RawSection* t = test::findSection(r, type(AssetSectionType::kTangents));
    for (int k = 0; k < 3; ++k) test::wr32(t->payload, 12 + 4 * static_cast<std::size_t>(k), test::bitsOf(bent[k]));
    const Bytes bad = test::build(r);
    expectError(decodeAsset(bad, &out), StatusCode::kCorrupt, "tangent of vertex 1 is not orthogonal");
    expectError(decodeAssetBiScale(bad, &out), StatusCode::kCorrupt, "tangent of vertex 1 is not orthogonal");
  }
  {
    test::RawAsset r = test::split(good);
    test::wr32(test::findSection(r, type(AssetSectionType::kPatchUv))->payload, 8, test::bitsOf(INFINITY));
    expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "patch uv of vertex 1 u is not finite");
  }
  {
    test::RawAsset r = test::split(good);
    test::findSection(r, type(AssetSectionType::kRtt))->payload.pop_back();
    expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "section 9 (RTT): RTT: ");
  }
  {  // Bi-scale sections with only a vector pass.
    BakedAsset plain = biScaleAsset(2, 5);
    plain.rtt.clear();
    plain.tangents.clear();
    plain.patchUv.clear();
    plain.passes[0].form = TransferForm::kVector;
    plain.passes[0].coeffs.assign(5 * 4, 0.1f);
    plain.specular.clear();
    test::RawAsset r = test::split(encodeOrDie(plain));
    const test::RawAsset g = test::split(good);
    for (const test::RawSection& s : g.sections) {
      if (s.type == type(AssetSectionType::kTangents) || s.type == type(AssetSectionType::kPatchUv) ||
          s.type == type(AssetSectionType::kRtt)) {
        r.sections.push_back(s);
      }
    }
    expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "is present without a matrix transfer section");
  }
}

// The synthesised id map instead of patch uv: placements, one index per atlas texel, the atlas
// sections without a texel pass.
BakedAsset synthesisedAsset(int order, std::size_t V) {
  BakedAsset a = biScaleAsset(order, V);
  a.patchUv.clear();
  a.patchPlacements = {{{0, 0, 0}, {10, 0, 0}, {0, 0, 10}}, {{1, 0, 0.5f}, {0, 0, 10}, {-10, 0, 0}}};
  a.atlases = {{4, 2, 0, static_cast<std::uint32_t>(a.indices.size() / 3)}};
  for (std::size_t v = 0; v < V; ++v) {
    a.atlasUv.push_back(static_cast<float>(v) / static_cast<float>(V));
    a.atlasUv.push_back(0.5f);
  }
  a.texelCoverage = {1, 1, 1, 0, 1, 1, 2, 0};
  a.idMap = {0, 0, 1, kNoPlacement, 1, 1, 0, kNoPlacement};
  return a;
}

TEST(AssetBiScale, SynthesisedIdMapRoundTripsWithItsAtlas) {
  const BakedAsset a = synthesisedAsset(2, 5);
  const Bytes file = encodeOrDie(a);
  BakedAsset out;
  ASSERT_TRUE(decodeAsset(file, &out).isOk());
  EXPECT_EQ(out.idMap, a.idMap);
  ASSERT_EQ(out.patchPlacements.size(), 2u);
  EXPECT_EQ(out.patchPlacements[1].origin.z, 0.5f);
  EXPECT_EQ(out.patchPlacements[1].axisV.x, -10.0f);
  EXPECT_TRUE(out.patchUv.empty());
  EXPECT_EQ(out.texelCoverage, a.texelCoverage);
  BakedAsset alone;
  ASSERT_TRUE(decodeAssetBiScale(file, &alone).isOk());
  EXPECT_EQ(alone.idMap, a.idMap);
  EXPECT_EQ(alone.patchPlacements.size(), 2u);

  Bytes bytes;
  BakedAsset b = a;
  b.idMap[2] = 2;  // only placements 0 and 1 exist
  expectError(encodeAsset(b, &bytes), StatusCode::kInvalidArgument, "id map texel 2 names placement 2 of 2");
  b = a;
  b.patchUv.assign(10, 0.5f);
  expectError(encodeAsset(b, &bytes), StatusCode::kInvalidArgument, "both patch uv");
  b = a;
  b.idMap.pop_back();
  expectError(encodeAsset(b, &bytes), StatusCode::kSizeMismatch, "7 id map entries for 8 atlas texels");
  b = a;
  b.patchPlacements[0].axisU.y = NAN;
  expectError(encodeAsset(b, &bytes), StatusCode::kNotFinite, "patch placement 0 is not finite");

  // The reader: an index past the placements, and an id map without its atlas sections.
  const auto type = [](AssetSectionType t) { return static_cast<std::uint32_t>(t); };
  test::RawAsset r = test::split(file);
  test::findSection(r, type(AssetSectionType::kIdMap))->payload[0] = 7;
  expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "id map texel 0 names placement 7 of 2");
  r = test::split(file);
  std::erase_if(r.sections, [&](const test::RawSection& s) { return s.type == type(AssetSectionType::kAtlases); });
  expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "the asset has an id map but no atlases section");
  r = test::split(file);
  std::erase_if(r.sections, [&](const test::RawSection& s) { return s.type == type(AssetSectionType::kPatchPlacements); });
  expectError(decodeAsset(test::build(r), &out), StatusCode::kCorrupt, "has an id map but no patch placements");
  for (std::size_t i = 0; i < file.size(); ++i) {
    Bytes bad = file;
    bad[i] ^= 0x21;
    ASSERT_FALSE(decodeAsset(bad, &out).isOk()) << "byte " << i;
  }
}

TEST(AssetBiScale, EveryPrefixAndByteFlipOfABiScaleFileIsRejected) {
  const Bytes file = encodeOrDie(biScaleAsset(2, 3));
  BakedAsset out;
  for (std::size_t n = 0; n < file.size(); ++n) {
    const Bytes cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(n));
    ASSERT_FALSE(decodeAsset(cut, &out).isOk()) << "prefix " << n;
  }
  for (std::size_t i = 0; i < file.size(); ++i) {
    Bytes bad = file;
    bad[i] ^= 0x21;
    ASSERT_FALSE(decodeAsset(bad, &out).isOk()) << "byte " << i;
    ASSERT_FALSE(verifyAsset(bad, nullptr).isOk()) << "byte " << i;
  }
}

}  // namespace
}  // namespace prt
