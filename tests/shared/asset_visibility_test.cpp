// Asset format 1.5's TPFL visibility passes (docs/asset-format.md, "texel visibility"): a
// texel pass of its own order, float32 (type 17) and encoded (type 18), round trips and
// summaries, checkAsset's rules, the reader's refusals of crafted files, and progressive
// decoding band by band in the pass's own bands.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/sampling.h"
#include "prt/transfer_codec.h"
#include "shared/asset_raw_file.h"

namespace prt {
namespace {

using namespace prt::test;  // NOLINT: the raw-file helpers

constexpr std::uint32_t kTypeTexelTransfer = 15, kTypeTexelVisibility = 17,
                        kTypeEncodedTexelVisibility = 18, kTypeLighting = 7;
constexpr int kOrder = 3, kVisibilityOrder = 5;  // 2n - 1: TPFL's exact order

// A strip of 12 vertices and 10 triangles in two atlases (4 x 3 and 2 x 5 texels, 22 in
// all) with a specular material per vertex, a texel shadowed vector pass and a visibility
// pass of order 5 (float32; encodeVisibility makes it a blob).
BakedAsset visibilityAsset() {
  BakedAsset a;
  a.shOrder = kOrder;
  const std::size_t V = 12, T = 10;
  Pcg32 rng(7);
  for (std::size_t v = 0; v < V; ++v) {
    const float t = static_cast<float>(v) / static_cast<float>(V - 1);
    a.positions.push_back({t, std::sin(3 * t), 0.5f * static_cast<float>(v % 2)});
    a.normals.push_back(squareToSphere(rng.nextFloat(), rng.nextFloat()));
    a.albedo.push_back({0.5f, 0.6f, 0.7f});
    a.specular.push_back({{0.04f, 0.05f, t}, 20.0f * t, 1.0f});
    a.atlasUv.push_back(t);
    a.atlasUv.push_back(rng.nextFloat());
  }
  for (std::uint32_t t = 0; t < T; ++t) a.indices.insert(a.indices.end(), {t, t + 1, t + 2});
  a.atlases = {{4, 3, 0, 6}, {2, 5, 6, 4}};
  const std::size_t texels = static_cast<std::size_t>(assetTexelCount(a));
  for (std::size_t i = 0; i < texels; ++i) a.texelCoverage.push_back(static_cast<std::uint8_t>(i % 3));
  auto smooth = [](std::size_t rows, int order) {
    std::vector<float> c;
    const std::size_t n = static_cast<std::size_t>(order * order);
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t i = 0; i < n; ++i) c.push_back(std::cos(0.4f * static_cast<float>(r * (i + 1))) / static_cast<float>(i + 1));
    return c;
  };
  TransferPass diffuse{TransferKind::kShadowed, 1, 0, smooth(texels, kOrder), {}};
  diffuse.domain = TransferDomain::kTexel;
  a.passes.push_back(std::move(diffuse));
  TransferPass v{TransferKind::kShadowed, 1, 0, smooth(texels, kVisibilityOrder), {}, TransferForm::kVisibility,
                 TransferDomain::kTexel, kVisibilityOrder};
  a.passes.push_back(std::move(v));
  a.sampling = "hammersley";
  a.name = "tpfl";
  return a;
}

void encodeVisibility(BakedAsset* a, const char* setting) {
  TransferCodecSettings settings;
  ASSERT_TRUE(parseTransferSetting(setting, TransferCodecSettings{}, &settings).isOk());
  TransferPass& v = a->passes.back();
  ASSERT_TRUE(encodeTransfer(v.coeffs, v.order, 1, settings, &v.encoded).isOk());
}

void expectRefused(const BakedAsset& a, StatusCode code, const std::string& fragment) {
  expectError(checkAsset(a), code, fragment);
  Bytes out;
  EXPECT_FALSE(encodeAsset(a, &out).isOk());
}

// decodeAsset and verifyAsset agree on every refusal.
void expectCorrupt(const Bytes& file, const std::string& fragment) {
  BakedAsset out;
  expectError(decodeAsset(file, &out), StatusCode::kCorrupt, fragment);
  AssetSummary summary;
  expectError(verifyAsset(file, &summary), StatusCode::kCorrupt, fragment);
}

TEST(AssetVisibility, FloatAndEncodedVisibilityPassesRoundTrip) {
  const BakedAsset a = visibilityAsset();
  const Bytes file = encodeOrDie(a);
  AssetSummary summary, peeked;
  ASSERT_TRUE(verifyAsset(file, &summary).isOk());
  ASSERT_TRUE(peekAssetHeader(file, &peeked).isOk());
  EXPECT_EQ(summary.versionMinor, 7);
  for (const AssetSummary* s : {&summary, &peeked}) {
    ASSERT_EQ(s->passes.size(), 2u);
    const AssetPassInfo& v = s->passes[1];
    EXPECT_EQ(v.form, TransferForm::kVisibility);
    EXPECT_EQ(v.domain, TransferDomain::kTexel);
    EXPECT_EQ(v.kind, TransferKind::kShadowed);
    EXPECT_EQ(v.order, kVisibilityOrder);
    EXPECT_EQ(v.bounces, 0);
    EXPECT_EQ(v.bytes, 22u * 25u * 4u);
    EXPECT_EQ(s->passes[0].order, 0);
    const AssetSectionInfo& e = s->sections[v.section];
    EXPECT_EQ(e.type, kTypeTexelVisibility);
    EXPECT_EQ(e.arg0, 1u);
    EXPECT_EQ(e.arg1, 1u);
    EXPECT_EQ(e.arg2, static_cast<std::uint32_t>(kVisibilityOrder));
  }
  // The table entry as docs/asset-format.md shows it ("texel visibility").
  const std::size_t at = entryAt(summary.passes[1].section);
  const Bytes head(file.begin() + static_cast<std::ptrdiff_t>(at), file.begin() + static_cast<std::ptrdiff_t>(at + 8));
  const Bytes tail(file.begin() + static_cast<std::ptrdiff_t>(at + 16), file.begin() + static_cast<std::ptrdiff_t>(at + 36));
  EXPECT_EQ(head, (Bytes{0x11, 0, 0, 0, 0x01, 0, 0, 0}));
  EXPECT_EQ(tail, (Bytes{0x98, 0x08, 0, 0, 0, 0, 0, 0, 0x01, 0, 0, 0, 0x01, 0, 0, 0, 0x05, 0, 0, 0}));
  BakedAsset back;
  ASSERT_TRUE(decodeAsset(file, &back).isOk());
  ASSERT_EQ(back.passes.size(), 2u);
  const TransferPass& v = back.passes[1];
  EXPECT_EQ(v.form, TransferForm::kVisibility);
  EXPECT_EQ(v.order, kVisibilityOrder);
  EXPECT_EQ(v.bounces, 0);
  EXPECT_EQ(v.coeffs, a.passes[1].coeffs);
  EXPECT_EQ(back.specular.size(), a.specular.size());
  EXPECT_EQ(encodeOrDie(back), file) << "re-encoding writes the same bytes";
  EXPECT_EQ(findPass(back, TransferKind::kShadowed, TransferForm::kVisibility, TransferDomain::kTexel), &back.passes[1]);
  EXPECT_STREQ(transferFormName(TransferForm::kVisibility), "visibility");

  BakedAsset packed = visibilityAsset();
  encodeVisibility(&packed, "q16");
  const Bytes packedFile = encodeOrDie(packed);
  ASSERT_TRUE(verifyAsset(packedFile, &summary).isOk());
  EXPECT_TRUE(summary.passes[1].encoded);
  EXPECT_EQ(summary.passes[1].order, kVisibilityOrder);
  EXPECT_EQ(summary.sections[summary.passes[1].section].type, kTypeEncodedTexelVisibility);
  ASSERT_TRUE(decodeAsset(packedFile, &back).isOk());
  EXPECT_EQ(back.passes[1].encoded, packed.passes[1].encoded);
  ASSERT_EQ(back.passes[1].coeffs.size(), a.passes[1].coeffs.size());
  for (std::size_t i = 0; i < a.passes[1].coeffs.size(); ++i) ASSERT_NEAR(back.passes[1].coeffs[i], a.passes[1].coeffs[i], 1e-3f) << i;
  EXPECT_EQ(encodeOrDie(back), packedFile);
}

TEST(AssetVisibility, CheckAssetRefusesEveryBrokenVisibilityRule) {
  const BakedAsset good = visibilityAsset();
  ASSERT_TRUE(checkAsset(good).isOk()) << checkAsset(good).toString();
  BakedAsset a = good;
  a.passes[1].domain = TransferDomain::kVertex;
  expectRefused(a, StatusCode::kInvalidArgument, "transfer pass 1 (visibility shadowed): visibility passes are texel passes only");
  a = good;
  a.passes[1].kind = TransferKind::kUnshadowed;
  expectRefused(a, StatusCode::kInvalidArgument, "visibility passes are shadowed");
  a = good;
  a.passes[1].channels = 3;
  expectRefused(a, StatusCode::kInvalidArgument, "3 channels; visibility passes have 1");
  for (int order : {0, 1, 17}) {
    a = good;
    a.passes[1].order = order;
    expectRefused(a, StatusCode::kInvalidArgument, "has order " + std::to_string(order) + "; 2 to 16 are allowed");
  }
  a = good;
  a.passes[0].order = 5;
  expectRefused(a, StatusCode::kInvalidArgument, "transfer pass 0 (texel shadowed) has order 5; only visibility passes");
  a = good;
  a.passes[1].bounces = 1;
  expectRefused(a, StatusCode::kInvalidArgument, "only interreflection has bounces");
  a = good;
  a.passes[1].coeffs.resize(22 * 9);  // order 3's size for an order-5 pass
  expectRefused(a, StatusCode::kSizeMismatch, "198 coefficients, 550 expected (texels * the pass's order^2)");
  a = good;
  a.passes[1].coeffs[3] = std::numeric_limits<float>::infinity();
  expectRefused(a, StatusCode::kNotFinite, "coefficient 3 is not finite");
  a = good;
  a.passes.push_back(a.passes[1]);
  expectRefused(a, StatusCode::kInvalidArgument, "repeats the kind of pass 1");
  a = good;
  a.specular.clear();
  expectRefused(a, StatusCode::kSizeMismatch, "a matrix or visibility pass needs one per vertex");
  a = good;
  a.lighting = {LightingModel::kLocalSphere, {0, 0, 0}, 5.0f};
  expectRefused(a, StatusCode::kInvalidArgument, "visibility passes need distant lighting, the asset is local-sphere");
  // An encoded pass's blob must be of the pass's order (not the asset's), 1 channel, a row per texel.
  a = good;
  {
    TransferCodecSettings f16;
    f16.encoding = TransferEncoding::kFloat16;
    std::vector<float> order3(22 * 9, 0.25f);
    ASSERT_TRUE(encodeTransfer(order3, 3, 1, f16, &a.passes[1].encoded).isOk());
    expectRefused(a, StatusCode::kSizeMismatch, "encoded blob is order 3, 1 channels, 22 rows");
    expectRefused(a, StatusCode::kSizeMismatch, "the pass needs order 5, 1 channels, 22 texels");
    std::vector<float> vertexRows(12 * 25, 0.25f);
    ASSERT_TRUE(encodeTransfer(vertexRows, 5, 1, f16, &a.passes[1].encoded).isOk());
    expectRefused(a, StatusCode::kSizeMismatch, "12 rows");
  }
  // Without any glossy pass the materials are refused, with the rule's new wording.
  a = good;
  a.passes.pop_back();
  expectRefused(a, StatusCode::kInvalidArgument, "specular materials but no matrix or visibility pass");
}

TEST(AssetVisibility, ReaderRefusesCraftedVisibilityFiles) {
  const Bytes file = encodeOrDie(visibilityAsset());
  const RawAsset good = split(file);
  ASSERT_EQ(build(good), file) << "the test's builder lays files out as the writer does";
  RawAsset r = good;
  findSection(r, kTypeTexelVisibility)->arg0 = 0;
  expectCorrupt(build(r), "(texel visibility unshadowed) has transfer kind 0; visibility sections are shadowed (1)");
  r = good;
  findSection(r, kTypeTexelVisibility)->arg1 = 3;
  expectCorrupt(build(r), "has 3 channels; visibility sections have 1");
  for (std::uint32_t order : {1u, 17u}) {
    r = good;
    findSection(r, kTypeTexelVisibility)->arg2 = order;
    expectCorrupt(build(r), "has visibility order " + std::to_string(order) + "; 2 to 16 expected");
  }
  r = good;
  findSection(r, kTypeTexelVisibility)->arg2 = 4;
  expectCorrupt(build(r), "is 2200 bytes; 1408 expected (4 bytes per texel and coefficient, 22 texels, visibility order 4)");
  r = good;
  findSection(r, kTypeTexelVisibility)->format = 3;
  expectCorrupt(build(r), "(texel visibility shadowed) has element format 3; float32 expected");
  r = good;
  r.sections.push_back(*findSection(r, kTypeTexelVisibility));
  expectCorrupt(build(r), "repeats the visibility pass of section 11; at most one is allowed");
  // The specular section is required with a visibility pass, and only with a glossy pass.
  r = good;
  r.sections.erase(r.sections.begin() + 6);
  ASSERT_EQ(r.sections[5].type, 4u);  // albedo before it
  expectCorrupt(build(r), "the asset has a matrix or visibility transfer section but no specular section");
  // What a 1.4 reader sees: the visibility section skipped as unknown, so the specular one
  // stands alone and the file is refused (not misread).
  r = good;
  findSection(r, kTypeTexelVisibility)->type = 99;
  expectCorrupt(build(r), "(specular) is present without a matrix or visibility transfer section");
  // A visibility pass is a texel pass: it alone keeps the atlas sections valid.
  r = good;
  findSection(r, kTypeTexelTransfer)->type = 99;
  BakedAsset out;
  ASSERT_TRUE(decodeAsset(build(r), &out).isOk());
  ASSERT_EQ(out.passes.size(), 1u);
  EXPECT_EQ(out.passes[0].form, TransferForm::kVisibility);
  // Local lighting: TPFL multiplies V with distant light only.
  r = good;
  {
    Bytes& light = findSection(r, kTypeLighting)->payload;
    wr32(light, 0, 1);
    wr32(light, 16, bitsOf(5.0f));
  }
  expectCorrupt(build(r), "(texel visibility shadowed) needs distant lighting; the lighting section says local-sphere");
  // An encoded blob of another order than the section's arg2.
  BakedAsset packed = visibilityAsset();
  encodeVisibility(&packed, "f16");
  RawAsset e = split(encodeOrDie(packed));
  findSection(e, kTypeEncodedTexelVisibility)->arg2 = 4;
  expectCorrupt(build(e), "its blob is order 5, 1 channels, 22 rows; the section says order 4, 1 channels, 22 texels");

  // Every truncation and every flipped byte is refused.
  for (std::size_t cut = 0; cut < file.size(); ++cut) {
    ASSERT_FALSE(decodeAsset(std::span<const std::uint8_t>(file).first(cut), &out).isOk()) << "prefix " << cut;
  }
  for (std::size_t i = 0; i < file.size(); ++i) {
    Bytes damaged = file;
    damaged[i] ^= 0x10;
    ASSERT_FALSE(decodeAsset(damaged, &out).isOk()) << "byte " << i;
  }
}

// A progressive client: the encoded visibility pass decodes band by band in its own bands
// (5, past the asset's 3), each prefix the first b bands of the full decode; CPCA unexpanded
// gives the same floats; a float32 pass decodes whole only.
TEST(AssetVisibility, EncodedVisibilityDecodesInItsOwnBands) {
  BakedAsset a = visibilityAsset();
  encodeVisibility(&a, "q16");
  const Bytes file = encodeOrDie(a);
  AssetSummary summary;
  ASSERT_TRUE(peekAssetHeader(file, &summary).isOk());
  const AssetSectionInfo& section = summary.sections[summary.passes[1].section];
  const auto blob = std::span<const std::uint8_t>(file).subspan(section.offset, section.size);
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
  std::vector<float> full;
  ASSERT_TRUE(decodeTransfer(blob, kVisibilityOrder, &full).isOk());
  Bytes buffer(file.size(), 0);
  auto arrive = [&](std::uint64_t offset, std::uint64_t size) {
    std::copy_n(file.begin() + static_cast<std::ptrdiff_t>(offset), size, buffer.begin() + static_cast<std::ptrdiff_t>(offset));
  };
  arrive(0, summary.tableEnd);
  arrive(summary.sections[1].offset, summary.sections[1].size);  // lighting: the pass needs it to be distant
  ASSERT_EQ(summary.sections[1].type, kTypeLighting);
  arrive(section.offset, info.parts.front().offset);
  TransferPass out;
  int bands = -1;
  int band = 0;
  const std::size_t texels = 22, M = 25;
  for (const TransferPartInfo& part : info.parts) {
    arrive(section.offset + part.offset, part.size);
    if (part.type != TransferPartType::kBand) continue;
    ++band;
    const Status s = decodeAssetPass(buffer, 1, band, &out, &bands);
    ASSERT_TRUE(s.isOk()) << "band " << band << ": " << s.message();
    EXPECT_EQ(bands, band);
    EXPECT_EQ(out.form, TransferForm::kVisibility);
    EXPECT_EQ(out.order, kVisibilityOrder);
    const std::size_t n = static_cast<std::size_t>(band * band);
    ASSERT_EQ(out.coeffs.size(), texels * n);
    for (std::size_t t = 0; t < texels; ++t)
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(out.coeffs[t * n + i], full[t * M + i]);
  }
  EXPECT_EQ(band, kVisibilityOrder);
  expectError(decodeAssetPass(buffer, 1, kVisibilityOrder + 1, &out, &bands), StatusCode::kInvalidArgument, "bands 6 outside 0..5");
  // The vector texel pass keeps the header's bands.
  expectError(decodeAssetPass(buffer, 0, kOrder + 1, &out, &bands), StatusCode::kInvalidArgument, "bands 4 outside 0..3");

  BakedAsset cpcaAsset = visibilityAsset();
  encodeVisibility(&cpcaAsset, "cpca8@0.05");
  const Bytes cpcaFile = encodeOrDie(cpcaAsset);
  for (int b : {1, 3, 5}) {
    CpcaTransfer cpca;
    TransferPass header;
    ASSERT_TRUE(decodeAssetPassCpca(cpcaFile, 1, b, &cpca, &header).isOk());
    EXPECT_EQ(header.form, TransferForm::kVisibility);
    EXPECT_EQ(header.order, kVisibilityOrder);
    std::vector<float> expanded(texels * static_cast<std::size_t>(b * b));
    ASSERT_TRUE(cpcaReconstruct(cpca, expanded).isOk());
    TransferPass reference;
    ASSERT_TRUE(decodeAssetPass(cpcaFile, 1, b, &reference, &bands).isOk());
    EXPECT_EQ(expanded, reference.coeffs) << b << " bands";
  }

  const Bytes floatFile = encodeOrDie(visibilityAsset());
  expectError(decodeAssetPass(floatFile, 1, 3, &out, &bands), StatusCode::kInvalidArgument, "is float32: only all bands decode");
  ASSERT_TRUE(decodeAssetPass(floatFile, 1, kVisibilityOrder, &out, &bands).isOk());
  EXPECT_EQ(out.coeffs, visibilityAsset().passes[1].coeffs);
  std::vector<SpecularMaterial> specular;
  ASSERT_TRUE(decodeAssetSpecular(floatFile, &specular).isOk());
  EXPECT_EQ(specular.size(), 12u);
}

}  // namespace
}  // namespace prt
