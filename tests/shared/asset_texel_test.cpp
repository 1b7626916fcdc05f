// Asset format 1.4's transfer textures (docs/asset-format.md, "Transfer textures"): texel
// passes float32 and encoded next to vertex passes, the atlas uv, atlases and texel coverage
// sections, checkAsset's rules for them, the reader's refusals of crafted files, progressive
// decoding of an encoded texel pass band by band, and decodeAssetAtlases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/checksum.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/transfer_codec.h"
#include "shared/asset_raw_file.h"

namespace prt {
namespace {

using namespace prt::test;  // NOLINT: the raw-file helpers
namespace L = asset_layout;

constexpr std::uint32_t kTypeAtlasUv = 12, kTypeAtlases = 13, kTypeCoverage = 14, kTypeTexelTransfer = 15,
                        kTypeEncodedTexelTransfer = 16;

// ---- Test assets ----------------------------------------------------------------------------

// A strip of 12 vertices and 10 triangles in two atlases (4 x 3 texels for triangles 0-5,
// 2 x 5 for 6-9), a vertex shadowed pass and, per `texelKinds`, texel passes (float32;
// encodeTexelPasses makes them blobs). Coverage and uv use every allowed value, edges included.
BakedAsset texelAsset(int order, std::vector<TransferKind> texelKinds, bool vertexPass = true) {
  BakedAsset a;
  a.shOrder = order;
  const std::size_t V = 12, T = 10;
  Pcg32 rng(41);
  for (std::size_t v = 0; v < V; ++v) {
    const float t = static_cast<float>(v) / static_cast<float>(V - 1);
    a.positions.push_back({t, std::sin(4 * t), 0.5f * static_cast<float>(v % 2)});
    a.normals.push_back(squareToSphere(rng.nextFloat(), rng.nextFloat()));
    a.albedo.push_back({0.5f, 0.6f, 0.7f});
    a.atlasUv.push_back(t);                               // 0 and 1 exactly at the ends
    a.atlasUv.push_back(v % 3 == 0 ? 1.0f : rng.nextFloat());
  }
  for (std::uint32_t t = 0; t < T; ++t) a.indices.insert(a.indices.end(), {t, t + 1, t + 2});
  a.atlases = {{4, 3, 0, 6}, {2, 5, 6, 4}};
  const std::uint64_t texels = assetTexelCount(a);
  for (std::uint64_t i = 0; i < texels; ++i) a.texelCoverage.push_back(static_cast<std::uint8_t>(i % 3));
  const std::size_t n = static_cast<std::size_t>(order * order);
  auto smoothPass = [&](TransferKind kind, std::size_t rows, TransferDomain domain) {
    TransferPass p;
    p.kind = kind;
    p.channels = kind == TransferKind::kInterreflected ? 3 : 1;
    p.bounces = kind == TransferKind::kInterreflected ? 2 : 0;
    p.domain = domain;
    for (std::size_t r = 0; r < rows; ++r)
      for (int c = 0; c < p.channels; ++c)
        for (std::size_t i = 0; i < n; ++i)
          p.coeffs.push_back(std::cos(0.3f * static_cast<float>(r * (i + 1)) + static_cast<float>(c)) / static_cast<float>(i + 1));
    return p;
  };
  if (vertexPass) a.passes.push_back(smoothPass(TransferKind::kShadowed, V, TransferDomain::kVertex));
  for (TransferKind k : texelKinds) a.passes.push_back(smoothPass(k, static_cast<std::size_t>(texels), TransferDomain::kTexel));
  a.sampling = "hammersley";
  a.name = "texel";
  return a;
}

// Encodes the texel passes of `a` (texels as the codec's vertices) with `setting`.
void encodeTexelPasses(BakedAsset* a, const char* setting) {
  TransferCodecSettings settings;
  ASSERT_TRUE(parseTransferSetting(setting, TransferCodecSettings{}, &settings).isOk());
  for (TransferPass& p : a->passes) {
    if (p.domain != TransferDomain::kTexel) continue;
    ASSERT_TRUE(encodeTransfer(p.coeffs, a->shOrder, p.channels, settings, &p.encoded).isOk());
  }
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameAtlases(const BakedAsset& a, const BakedAsset& b) {
  EXPECT_TRUE(sameBits(a.atlasUv, b.atlasUv));
  ASSERT_EQ(a.atlases.size(), b.atlases.size());
  for (std::size_t i = 0; i < a.atlases.size(); ++i) {
    EXPECT_EQ(a.atlases[i].width, b.atlases[i].width) << i;
    EXPECT_EQ(a.atlases[i].height, b.atlases[i].height) << i;
    EXPECT_EQ(a.atlases[i].firstTriangle, b.atlases[i].firstTriangle) << i;
    EXPECT_EQ(a.atlases[i].triangleCount, b.atlases[i].triangleCount) << i;
  }
  EXPECT_EQ(a.texelCoverage, b.texelCoverage);
}

// decodeAsset and verifyAsset agree on every refusal.
void expectCorrupt(const Bytes& file, const std::string& fragment) {
  BakedAsset out;
  expectError(decodeAsset(file, &out), StatusCode::kCorrupt, fragment);
  AssetSummary summary;
  expectError(verifyAsset(file, &summary), StatusCode::kCorrupt, fragment);
}

void expectRefused(const BakedAsset& a, StatusCode code, const std::string& fragment) {
  expectError(checkAsset(a), code, fragment);
  Bytes out;
  EXPECT_FALSE(encodeAsset(a, &out).isOk());
}

// ---- Round trips ----------------------------------------------------------------------------

TEST(AssetTexel, FloatAndEncodedTexelPassesRoundTripWithVertexPasses) {
  BakedAsset a = texelAsset(3, {TransferKind::kShadowed});
  BakedAsset encodedPart = texelAsset(3, {TransferKind::kInterreflected});
  encodeTexelPasses(&encodedPart, "q16");
  a.passes.push_back(encodedPart.passes.back());  // texel interreflected, a q16 blob
  const Bytes file = encodeOrDie(a);
  EXPECT_EQ(rd32(file, L::kVersionMinor) & 0xFFFFu, 7u);

  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(file, &summary).isOk());
  EXPECT_EQ(summary.versionMinor, 7);
  EXPECT_EQ(summary.texelCount, assetTexelCount(a));
  ASSERT_EQ(summary.passes.size(), 3u);
  EXPECT_EQ(summary.passes[0].domain, TransferDomain::kVertex);
  EXPECT_EQ(summary.passes[1].domain, TransferDomain::kTexel);
  EXPECT_FALSE(summary.passes[1].encoded);
  EXPECT_EQ(summary.passes[2].domain, TransferDomain::kTexel);
  EXPECT_TRUE(summary.passes[2].encoded);
  EXPECT_EQ(summary.sections[summary.passes[1].section].type, kTypeTexelTransfer);
  EXPECT_EQ(summary.sections[summary.passes[2].section].type, kTypeEncodedTexelTransfer);
  // The atlas sections come after the geometry and before every pass, in this order.
  std::vector<std::uint32_t> types;
  for (const AssetSectionInfo& s : summary.sections) types.push_back(s.type);
  const std::vector<std::uint32_t> expectedTypes = {6, 7, 1, 2, 3, 4, kTypeAtlasUv, kTypeAtlases, kTypeCoverage, 5,
                                                    kTypeTexelTransfer, kTypeEncodedTexelTransfer};
  EXPECT_EQ(types, expectedTypes);
  const AssetSectionInfo& atlases = summary.sections[7];
  EXPECT_EQ(atlases.arg0, a.atlases.size());
  EXPECT_EQ(atlases.size, 16 * a.atlases.size());
  // The document's example of the atlases payload (docs/asset-format.md, "atlases").
  const Bytes documented = {0x04, 0, 0, 0, 0x03, 0, 0, 0, 0x00, 0, 0, 0, 0x06, 0, 0, 0,
                            0x02, 0, 0, 0, 0x05, 0, 0, 0, 0x06, 0, 0, 0, 0x04, 0, 0, 0};
  EXPECT_EQ(Bytes(file.begin() + static_cast<std::ptrdiff_t>(atlases.offset),
                  file.begin() + static_cast<std::ptrdiff_t>(atlases.offset + atlases.size)),
            documented);
  EXPECT_EQ(summary.sections[8].size, 22u);
  AssetSummary peeked;
  ASSERT_TRUE(peekAssetHeader(file, &peeked).isOk());
  EXPECT_EQ(peeked.texelCount, summary.texelCount);
  EXPECT_EQ(peeked.passes[2].domain, TransferDomain::kTexel);

  BakedAsset back;
  ASSERT_TRUE(decodeAsset(file, &back).isOk());
  ASSERT_EQ(back.passes.size(), 3u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back.passes[k].domain, a.passes[k].domain);
    EXPECT_TRUE(sameBits(back.passes[k].coeffs, a.passes[k].coeffs)) << "float32 pass " << k << " is bit-exact";
  }
  const TransferPass& enc = back.passes[2];
  EXPECT_EQ(enc.domain, TransferDomain::kTexel);
  EXPECT_EQ(enc.kind, TransferKind::kInterreflected);
  EXPECT_EQ(enc.channels, 3);
  EXPECT_EQ(enc.bounces, 2);
  EXPECT_EQ(enc.encoded, a.passes[2].encoded);
  ASSERT_EQ(enc.coeffs.size(), a.passes[2].coeffs.size());
  // q16: a step of max|x|/32767 per channel and coefficient (docs/transfer-codec.md).
  for (std::size_t i = 0; i < enc.coeffs.size(); ++i) ASSERT_NEAR(enc.coeffs[i], a.passes[2].coeffs[i], 1e-3f) << i;
  expectSameAtlases(a, back);
  // Re-encoding the decoded asset writes the same bytes.
  EXPECT_EQ(encodeOrDie(back), file);

  // findPass tells the domains apart.
  EXPECT_EQ(findPass(back, TransferKind::kShadowed), &back.passes[0]);
  EXPECT_EQ(findPass(back, TransferKind::kShadowed, TransferForm::kVector, TransferDomain::kTexel), &back.passes[1]);
  EXPECT_EQ(findPass(back, TransferKind::kInterreflected), nullptr);
  EXPECT_EQ(findPass(back, TransferKind::kInterreflected, TransferForm::kVector, TransferDomain::kTexel), &back.passes[2]);
  EXPECT_EQ(findPass(back, TransferKind::kUnshadowed, TransferForm::kVector, TransferDomain::kTexel), nullptr);
  EXPECT_STREQ(transferDomainName(TransferDomain::kVertex), "vertex");
  EXPECT_STREQ(transferDomainName(TransferDomain::kTexel), "texel");
  EXPECT_STREQ(transferDomainName(static_cast<TransferDomain>(7)), "unknown");
}

TEST(AssetTexel, AssetsWithOnlyTexelPassesAndWithoutAnyKeepTheirLayouts) {
  const BakedAsset only = texelAsset(2, {TransferKind::kUnshadowed, TransferKind::kShadowed, TransferKind::kInterreflected}, false);
  const Bytes file = encodeOrDie(only);
  BakedAsset back;
  ASSERT_TRUE(decodeAsset(file, &back).isOk());
  ASSERT_EQ(back.passes.size(), 3u);
  for (const TransferPass& p : back.passes) EXPECT_EQ(p.domain, TransferDomain::kTexel);
  expectSameAtlases(only, back);

  // Without texel passes: no atlas sections, and the decoded asset has none.
  BakedAsset plain = texelAsset(2, {});
  plain.atlases.clear();
  plain.atlasUv.clear();
  plain.texelCoverage.clear();
  const Bytes plainFile = encodeOrDie(plain);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(plainFile, &summary).isOk());
  EXPECT_EQ(summary.texelCount, 0u);
  for (const AssetSectionInfo& s : summary.sections) EXPECT_TRUE(s.type < kTypeAtlasUv || s.type > kTypeEncodedTexelTransfer);
  ASSERT_TRUE(decodeAsset(plainFile, &back).isOk());
  EXPECT_TRUE(back.atlases.empty() && back.atlasUv.empty() && back.texelCoverage.empty());
}

// ---- checkAsset -----------------------------------------------------------------------------

TEST(AssetTexel, CheckAssetRefusesEveryBrokenTexelRule) {
  const BakedAsset good = texelAsset(2, {TransferKind::kShadowed, TransferKind::kInterreflected});
  ASSERT_TRUE(checkAsset(good).isOk()) << checkAsset(good).toString();
  const std::size_t texelPass = 1;  // texel shadowed
  BakedAsset a = good;

  a.passes[texelPass].form = TransferForm::kMatrix;
  expectRefused(a, StatusCode::kInvalidArgument, "texel passes are vector or visibility form");
  a = good;
  a.passes[texelPass].domain = static_cast<TransferDomain>(5);
  expectRefused(a, StatusCode::kInvalidArgument, "unknown domain 5");
  a = good;
  a.passes[texelPass].channels = 2;
  expectRefused(a, StatusCode::kInvalidArgument, "2 channels; 1 or 3");
  a = good;
  a.passes[texelPass].bounces = 1;
  expectRefused(a, StatusCode::kInvalidArgument, "only interreflection has bounces");
  a = good;
  a.passes[texelPass].coeffs.pop_back();
  expectRefused(a, StatusCode::kSizeMismatch, "texels * channels * order^2");
  a = good;
  a.passes[texelPass].coeffs[5] = std::numeric_limits<float>::quiet_NaN();
  expectRefused(a, StatusCode::kNotFinite, "coefficient 5 is not finite");
  a = good;
  a.passes.push_back(a.passes[texelPass]);
  expectRefused(a, StatusCode::kInvalidArgument, "repeats the kind of pass 1; at most one per kind, form and domain");
  a = good;
  while (a.passes.size() <= kMaxAssetPasses) a.passes.push_back(a.passes[0]);
  expectRefused(a, StatusCode::kInvalidArgument, "1 to " + std::to_string(kMaxAssetPasses));
  // An encoded texel pass's blob must have one row per texel.
  a = good;
  {
    TransferCodecSettings f16;
    f16.encoding = TransferEncoding::kFloat16;
    std::vector<float> vertexRows(a.positions.size() * 4, 0.5f);
    ASSERT_TRUE(encodeTransfer(vertexRows, 2, 1, f16, &a.passes[texelPass].encoded).isOk());
    expectRefused(a, StatusCode::kSizeMismatch, "12 rows");
    expectRefused(a, StatusCode::kSizeMismatch, std::to_string(assetTexelCount(a)) + " texels");
  }

  // Atlases.
  a = good;
  a.atlases.clear();
  expectRefused(a, StatusCode::kInvalidArgument, "0 atlases; a texel pass needs 1 to 1024");
  a = good;
  a.atlases.assign(kMaxAssetAtlases + 1, {1, 1, 0, 1});
  expectRefused(a, StatusCode::kInvalidArgument, "1025 atlases");
  a = good;
  a.atlases[1].width = 0;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas 1 is 0 x 5 texels");
  a = good;
  a.atlases[0].height = kMaxAssetAtlasSize + 1;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas 0 is 4 x 16385 texels; each side must be 1 to 16384");
  a = good;
  a.atlases[1].triangleCount = 0;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas 1 covers no triangles");
  a = good;
  a.atlases[0].firstTriangle = 1;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas 0 starts at triangle 1, expected 0");
  a = good;
  a.atlases[1].firstTriangle = 5;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas 1 starts at triangle 5, expected 6");
  a = good;
  a.atlases[1].triangleCount = 3;
  expectRefused(a, StatusCode::kInvalidArgument, "the atlases cover 9 of the 10 triangles");
  a = good;
  a.atlases[1].triangleCount = 5;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas 1 ends at triangle 11, past the 10 triangles");
  a = good;
  a.atlases = {{16384, 16384, 0, 5}, {2, 1, 5, 5}};  // 2^28 + 2 texels (checked before any array of that size)
  expectRefused(a, StatusCode::kInvalidArgument, "268435458 texels; at most 268435456");

  // Atlas uv.
  a = good;
  a.atlasUv.pop_back();
  expectRefused(a, StatusCode::kSizeMismatch, "23 atlas uv floats for 12 vertices");
  a = good;
  a.atlasUv[7] = 1.0001f;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas uv of vertex 3 (v) is 1.000100, outside [0, 1]");
  a = good;
  a.atlasUv[4] = -0.5f;
  expectRefused(a, StatusCode::kInvalidArgument, "atlas uv of vertex 2 (u)");
  a = good;
  a.atlasUv[2] = std::numeric_limits<float>::infinity();
  expectRefused(a, StatusCode::kNotFinite, "atlas uv of vertex 1 (u) is not finite");

  // Coverage.
  a = good;
  a.texelCoverage.push_back(0);
  expectRefused(a, StatusCode::kSizeMismatch, "23 texel coverage values for 22 texels");
  a = good;
  a.texelCoverage[9] = 3;
  expectRefused(a, StatusCode::kInvalidArgument, "texel coverage 9 is 3");

  // Without a texel pass, no atlas data.
  BakedAsset plain = good;
  plain.passes.resize(1);  // the vertex pass
  expectRefused(plain, StatusCode::kInvalidArgument, "2 atlases but no texel pass");
  plain.atlases.clear();
  expectRefused(plain, StatusCode::kInvalidArgument, "24 atlas uv floats but no texel pass");
  plain.atlasUv.clear();
  expectRefused(plain, StatusCode::kInvalidArgument, "22 texel coverage values but no texel pass");
  plain.texelCoverage.clear();
  EXPECT_TRUE(checkAsset(plain).isOk());
}

// ---- The reader on crafted files --------------------------------------------------------------

TEST(AssetTexel, ReaderRefusesCraftedTexelFiles) {
  const Bytes file = encodeOrDie(texelAsset(2, {TransferKind::kShadowed}));
  const RawAsset good = split(file);
  ASSERT_EQ(build(good), file) << "the test's builder lays files out as the writer does";

  // Atlas sections without a texel pass: the texel pass turned into an unknown type.
  RawAsset r = good;
  findSection(r, kTypeTexelTransfer)->type = 99;
  expectCorrupt(build(r), "section 6 (atlas uv) is present without a texel transfer section");
  // A texel pass missing one of its sections, or with one twice.
  r = good;
  r.sections.erase(r.sections.begin() + 7);  // atlases
  expectCorrupt(build(r), "a texel transfer section but no atlases section");
  r = good;
  r.sections.push_back(*findSection(r, kTypeCoverage));
  expectCorrupt(build(r), "(texel coverage) repeats section 8");
  // Coverage of another size than the float32 pass's texels.
  r = good;
  findSection(r, kTypeCoverage)->payload.push_back(1);
  expectCorrupt(build(r), "23 texels");
  // Atlases whose texels disagree with the coverage (an encoded pass, so the table step passes).
  BakedAsset encoded = texelAsset(2, {TransferKind::kShadowed});
  encodeTexelPasses(&encoded, "q16");
  RawAsset e = split(encodeOrDie(encoded));
  RawAsset f = e;
  wr32(findSection(f, kTypeAtlases)->payload, 16 + 4, 4);  // atlas 1: 2 x 4 instead of 2 x 5
  expectCorrupt(build(f), "the atlases hold 20 texels, the texel coverage section 22");
  f = e;
  findSection(f, kTypeCoverage)->payload.pop_back();
  expectCorrupt(build(f), "the atlases hold 22 texels, the texel coverage section 21");
  // Atlases and coverage agreeing on 20 texels, the blob holding 22.
  wr32(findSection(f, kTypeAtlases)->payload, 16 + 4, 4);
  findSection(f, kTypeCoverage)->payload.pop_back();
  expectCorrupt(build(f), "its blob is order 2, 1 channels, 22 rows; the asset says order 2, 1 channels, 20 texels");

  // Atlases that do not tile the triangles.
  r = good;
  wr32(findSection(r, kTypeAtlases)->payload, 16 + 8, 7);
  expectCorrupt(build(r), "atlas 1 starts at triangle 7, expected 6");
  r = good;
  wr32(findSection(r, kTypeAtlases)->payload, 16 + 12, 3);
  expectCorrupt(build(r), "the atlases cover 9 triangles, the header says 10");
  r = good;
  wr32(findSection(r, kTypeAtlases)->payload, 12, 0);
  expectCorrupt(build(r), "atlas 0 covers no triangles");
  r = good;
  wr32(findSection(r, kTypeAtlases)->payload, 0, kMaxAssetAtlasSize + 1);
  expectCorrupt(build(r), "atlas 0 is 16385 x 3 texels");
  r = good;
  findSection(r, kTypeAtlases)->arg0 = 3;
  expectCorrupt(build(r), "16 bytes per atlas");
  r = good;
  findSection(r, kTypeAtlases)->arg0 = 0;
  expectCorrupt(build(r), "declares 0 atlases");

  // Bad coverage values and uv outside [0, 1].
  r = good;
  findSection(r, kTypeCoverage)->payload[13] = 3;
  expectCorrupt(build(r), "texel 13 has coverage 3; 0, 1 or 2 expected");
  r = good;
  wr32(findSection(r, kTypeAtlasUv)->payload, 4 * 5, bitsOf(1.5f));
  expectCorrupt(build(r), "vertex 2 v is 1.500000, not in [0, 1]");
  r = good;
  wr32(findSection(r, kTypeAtlasUv)->payload, 4 * 6, bitsOf(std::numeric_limits<float>::quiet_NaN()));
  expectCorrupt(build(r), "vertex 3 u is");
  r = good;
  findSection(r, kTypeAtlasUv)->payload.resize(8 * 11);
  expectCorrupt(build(r), "(atlas uv) is 88 bytes; 96 expected");
  r = good;
  findSection(r, kTypeTexelTransfer)->format = 3;
  expectCorrupt(build(r), "(texel transfer shadowed) has element format 3; float32 expected");

  // Every truncation and every flipped byte is refused (the checksums cover the new sections).
  for (std::size_t cut = 0; cut < file.size(); ++cut) {
    BakedAsset out;
    ASSERT_FALSE(decodeAsset(std::span<const std::uint8_t>(file).first(cut), &out).isOk()) << "prefix " << cut;
  }
  for (std::size_t i = 0; i < file.size(); ++i) {
    Bytes damaged = file;
    damaged[i] ^= 0x20;
    BakedAsset out;
    ASSERT_FALSE(decodeAsset(damaged, &out).isOk()) << "byte " << i;
  }
}

// ---- Progressive decoding -------------------------------------------------------------------

TEST(AssetTexel, EncodedTexelPassDecodesBandByBandAndAtlasesOnTheirOwn) {
  BakedAsset a = texelAsset(4, {TransferKind::kInterreflected});
  encodeTexelPasses(&a, "q16");
  const Bytes file = encodeOrDie(a);
  AssetSummary summary;
  ASSERT_TRUE(peekAssetHeader(file, &summary).isOk());
  Bytes buffer(file.size(), 0);
  auto arrive = [&](std::uint64_t offset, std::uint64_t size) {
    std::copy_n(file.begin() + static_cast<std::ptrdiff_t>(offset), size, buffer.begin() + static_cast<std::ptrdiff_t>(offset));
  };
  arrive(0, summary.tableEnd);

  // The atlases decode once their three sections have arrived, and only then.
  BakedAsset atlases;
  atlases.name = "kept";
  EXPECT_EQ(decodeAssetAtlases(buffer, &atlases).code(), StatusCode::kChecksumMismatch);
  EXPECT_TRUE(atlases.atlases.empty());
  for (const AssetSectionInfo& s : summary.sections) {
    if (s.type >= kTypeAtlasUv && s.type <= kTypeCoverage) arrive(s.offset, s.size);
  }
  ASSERT_TRUE(decodeAssetAtlases(buffer, &atlases).isOk());
  expectSameAtlases(a, atlases);
  EXPECT_EQ(atlases.name, "kept") << "decodeAssetAtlases leaves the rest of *out alone";

  const int pass = 1;  // the texel pass
  ASSERT_EQ(summary.passes[pass].domain, TransferDomain::kTexel);
  const AssetSectionInfo& section = summary.sections[summary.passes[pass].section];
  const auto blob = std::span<const std::uint8_t>(file).subspan(section.offset, section.size);
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
  std::vector<float> full;
  ASSERT_TRUE(decodeTransfer(blob, a.shOrder, &full).isOk());
  TransferPass out;
  int bands = -1;
  EXPECT_FALSE(decodeAssetPass(buffer, pass, 1, &out, &bands).isOk()) << "nothing of the blob has arrived";
  arrive(section.offset, info.parts.front().offset);
  const std::size_t texels = assetTexelCount(a), N = static_cast<std::size_t>(a.shOrder * a.shOrder);
  int band = 0;
  for (const TransferPartInfo& part : info.parts) {
    arrive(section.offset + part.offset, part.size);
    if (part.type != TransferPartType::kBand) continue;
    ++band;
    const Status s = decodeAssetPass(buffer, pass, band, &out, &bands);
    ASSERT_TRUE(s.isOk()) << "band " << band << ": " << s.message();
    EXPECT_EQ(bands, band);
    EXPECT_EQ(out.domain, TransferDomain::kTexel);
    EXPECT_EQ(out.channels, 3);
    const std::size_t n = static_cast<std::size_t>(band * band);
    ASSERT_EQ(out.coeffs.size(), texels * 3 * n);
    for (std::size_t t = 0; t < texels; ++t)
      for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(out.coeffs[(t * 3 + c) * n + i], full[(t * 3 + c) * N + i]);
    if (band < a.shOrder) EXPECT_FALSE(decodeAssetPass(buffer, pass, band + 1, &out, &bands).isOk());
  }
  EXPECT_EQ(band, a.shOrder);

  // Damaged coverage: refused, *out untouched.
  Bytes damaged = file;
  const AssetSectionInfo& coverage = summary.sections[8];
  ASSERT_EQ(coverage.type, kTypeCoverage);
  damaged[coverage.offset] ^= 1;
  BakedAsset untouched = atlases;
  EXPECT_EQ(decodeAssetAtlases(damaged, &untouched).code(), StatusCode::kChecksumMismatch);
  expectSameAtlases(atlases, untouched);

  // A file without texel passes: decodeAssetAtlases empties the three arrays.
  BakedAsset plain = texelAsset(2, {});
  plain.atlases.clear();
  plain.atlasUv.clear();
  plain.texelCoverage.clear();
  ASSERT_TRUE(decodeAssetAtlases(encodeOrDie(plain), &untouched).isOk());
  EXPECT_TRUE(untouched.atlases.empty() && untouched.atlasUv.empty() && untouched.texelCoverage.empty());
  EXPECT_EQ(decodeAssetAtlases(file, nullptr).code(), StatusCode::kInvalidArgument);
}

// A float32 texel pass decodes whole only; a CPCA texel blob decodes unexpanded as a vertex one.
TEST(AssetTexel, FloatTexelPassesDecodeWholeAndCpcaTexelPassesUnexpanded) {
  BakedAsset a = texelAsset(3, {TransferKind::kShadowed});
  const Bytes file = encodeOrDie(a);
  TransferPass out;
  int bands = 0;
  EXPECT_EQ(decodeAssetPass(file, 1, 2, &out, &bands).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(decodeAssetPass(file, 1, 0, &out, &bands).isOk());
  EXPECT_EQ(out.domain, TransferDomain::kTexel);
  EXPECT_TRUE(sameBits(out.coeffs, a.passes[1].coeffs));

  encodeTexelPasses(&a, "cpca8@0.05");
  const Bytes cpcaFile = encodeOrDie(a);
  for (int b = 1; b <= a.shOrder; ++b) {
    CpcaTransfer cpca;
    TransferPass info;
    const Status s = decodeAssetPassCpca(cpcaFile, 1, b, &cpca, &info);
    ASSERT_TRUE(s.isOk()) << s.message();
    EXPECT_EQ(info.domain, TransferDomain::kTexel);
    EXPECT_EQ(cpca.clusterOf.size(), assetTexelCount(a));
    std::vector<float> expanded(assetTexelCount(a) * static_cast<std::size_t>(b * b));
    ASSERT_TRUE(cpcaReconstruct(cpca, expanded).isOk());
    TransferPass reference;
    int decoded = 0;
    ASSERT_TRUE(decodeAssetPass(cpcaFile, 1, b, &reference, &decoded).isOk());
    EXPECT_EQ(expanded, reference.coeffs) << b << " bands";
  }
}

}  // namespace
}  // namespace prt
