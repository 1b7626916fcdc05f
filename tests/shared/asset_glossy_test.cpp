// Asset format 1.3's glossy sections (docs/asset-format.md): float32 and encoded matrix
// passes, the specular materials, checkAsset's rules for them, the worked example's bytes,
// progressive decoding of a matrix pass band by band, and every cut and byte flip of a file
// with matrix passes rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"

namespace prt {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes encodeOrDie(const BakedAsset& a) {
  Bytes b;
  const Status s = encodeAsset(a, &b);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return b;
}

TransferPass matrixPass(TransferKind kind, int channels, int bounces, std::size_t V, int order, MatrixPacking packing,
                        float scale) {
  TransferPass p;
  p.kind = kind;
  p.channels = channels;
  p.bounces = bounces;
  p.form = TransferForm::kMatrix;
  const std::size_t E = matrixEntryCount(order, packing);
  p.coeffs.resize(V * static_cast<std::size_t>(channels) * E);
  for (std::size_t i = 0; i < p.coeffs.size(); ++i) {
    const std::size_t v = i / (static_cast<std::size_t>(channels) * E), e = i % E;
    p.coeffs[i] = scale * static_cast<float>(std::cos(0.05 * static_cast<double>(v) + 0.3 * static_cast<double>(e))) /
                  static_cast<float>(1 + e % 7);
  }
  return p;
}

// A small glossy asset: a vector shadowed pass, a shadowed matrix pass and (for kFull
// lighting) an interreflected one, specular materials per vertex.
BakedAsset glossyAsset(int order, std::size_t V, LightingModel model) {
  BakedAsset a;
  a.shOrder = order;
  for (std::size_t v = 0; v < V; ++v) {
    const float t = static_cast<float>(v);
    a.positions.push_back({t, 0.5f * t, -t});
    a.normals.push_back({0.0f, 1.0f, 0.0f});
    a.albedo.push_back({0.5f, 0.4f, 0.3f});
    a.specular.push_back({{0.04f, 0.04f + 0.001f * t, 0.5f}, 10.0f + t, 1.0f - 0.01f * t});
  }
  for (std::size_t v = 0; v + 2 < V; ++v) {
    a.indices.push_back(static_cast<std::uint32_t>(v));
    a.indices.push_back(static_cast<std::uint32_t>(v + 1));
    a.indices.push_back(static_cast<std::uint32_t>(v + 2));
  }
  TransferPass vec;
  vec.kind = TransferKind::kShadowed;
  vec.coeffs.assign(V * static_cast<std::size_t>(order * order), 0.25f);
  a.passes.push_back(vec);
  if (model != LightingModel::kDistant) a.lighting = {model, {0.0f, 1.0f, 0.0f}, 5.0f};
  a.passes.push_back(matrixPass(TransferKind::kShadowed, 1, 0, V, order, matrixPackingFor(TransferKind::kShadowed, model), 1.0f));
  a.passes.push_back(matrixPass(TransferKind::kInterreflected, 3, 2, V, order, MatrixPacking::kFull, 0.2f));
  a.sampling = "hammersley";
  a.name = "glossy";
  return a;
}

void expectSameAsset(const BakedAsset& a, const BakedAsset& b) {
  ASSERT_EQ(a.passes.size(), b.passes.size());
  for (std::size_t p = 0; p < a.passes.size(); ++p) {
    EXPECT_EQ(a.passes[p].kind, b.passes[p].kind);
    EXPECT_EQ(a.passes[p].form, b.passes[p].form);
    EXPECT_EQ(a.passes[p].channels, b.passes[p].channels);
    EXPECT_EQ(a.passes[p].bounces, b.passes[p].bounces);
    EXPECT_EQ(a.passes[p].coeffs, b.passes[p].coeffs);
  }
  ASSERT_EQ(a.specular.size(), b.specular.size());
  for (std::size_t v = 0; v < a.specular.size(); ++v) {
    EXPECT_EQ(a.specular[v].f0.r, b.specular[v].f0.r);
    EXPECT_EQ(a.specular[v].f0.g, b.specular[v].f0.g);
    EXPECT_EQ(a.specular[v].f0.b, b.specular[v].f0.b);
    EXPECT_EQ(a.specular[v].exponent, b.specular[v].exponent);
    EXPECT_EQ(a.specular[v].f90, b.specular[v].f90);
  }
}

TEST(AssetGlossy, FloatMatrixPassesRoundTripUnderBothLightingModels) {
  for (LightingModel model : {LightingModel::kDistant, LightingModel::kLocalSphere}) {
    const BakedAsset a = glossyAsset(3, 9, model);
    const Bytes file = encodeOrDie(a);
    BakedAsset b;
    const Status s = decodeAsset(file, &b);
    ASSERT_TRUE(s.isOk()) << s.toString();
    expectSameAsset(a, b);
    AssetSummary sum;
    ASSERT_TRUE(verifyAsset(file, &sum).isOk());
    EXPECT_EQ(sum.versionMinor, 7);
    ASSERT_EQ(sum.passes.size(), 3u);
    EXPECT_EQ(sum.passes[0].form, TransferForm::kVector);
    EXPECT_EQ(sum.passes[1].form, TransferForm::kMatrix);
    EXPECT_EQ(sum.passes[2].form, TransferForm::kMatrix);
    // Sizes: shadowed symmetric under distant lighting (45 entries at order 3), full otherwise (81).
    const std::uint64_t entries = model == LightingModel::kDistant ? 45 : 81;
    EXPECT_EQ(sum.passes[1].bytes, 9u * entries * 4);
    EXPECT_EQ(sum.passes[2].bytes, 9u * 3 * 81 * 4);
    AssetSummary peeked;
    ASSERT_TRUE(peekAssetHeader(file, &peeked).isOk());
    EXPECT_EQ(peeked.passes[1].form, TransferForm::kMatrix);
    std::vector<SpecularMaterial> spec;
    ASSERT_TRUE(decodeAssetSpecular(file, &spec).isOk());
    EXPECT_EQ(spec.size(), 9u);
    EXPECT_EQ(spec[3].exponent, 13.0f);
  }
}

TEST(AssetGlossy, EncodedMatrixPassesKeepTheirBlobAndDecode) {
  BakedAsset a = glossyAsset(3, 40, LightingModel::kDistant);
  TransferCodecSettings s;
  ASSERT_TRUE(parseTransferSetting("cpca16@0.02", {}, &s).isOk());
  s.cpcaMaxClusters = 4;
  for (std::size_t p = 1; p < a.passes.size(); ++p) {
    TransferPass& pass = a.passes[p];
    ASSERT_TRUE(encodeTransferMatrix(pass.coeffs, 3, matrixPackingFor(pass.kind, a.lighting.model), pass.channels,
                                     s, &pass.encoded).isOk());
  }
  const Bytes file = encodeOrDie(a);
  BakedAsset b;
  ASSERT_TRUE(decodeAsset(file, &b).isOk());
  for (std::size_t p = 1; p < a.passes.size(); ++p) {
    EXPECT_EQ(b.passes[p].encoded, a.passes[p].encoded);
    EXPECT_EQ(b.passes[p].form, TransferForm::kMatrix);
    std::vector<float> expect;
    ASSERT_TRUE(decodeTransferMatrix(a.passes[p].encoded, 3, &expect).isOk());
    EXPECT_EQ(b.passes[p].coeffs, expect);
  }
  EXPECT_EQ(encodeOrDie(b), file);  // the blob is kept, not re-made
  AssetSummary sum;
  ASSERT_TRUE(verifyAsset(file, &sum).isOk());
  EXPECT_TRUE(sum.passes[1].encoded);

  // The unexpanded CPCA form of pass 2 from the whole file, every band count.
  for (int bands = 0; bands <= 3; ++bands) {
    CpcaMatrixTransfer cpca;
    TransferPass info;
    const Status st = decodeAssetPassCpcaMatrix(file, 2, bands, &cpca, &info);
    ASSERT_TRUE(st.isOk()) << st.toString();
    EXPECT_EQ(cpca.bands, bands == 0 ? 3 : bands);
    EXPECT_EQ(info.kind, TransferKind::kInterreflected);
    EXPECT_EQ(info.form, TransferForm::kMatrix);
    EXPECT_EQ(info.bounces, 2);
  }
  CpcaTransfer vcpca;
  TransferPass vinfo;
  EXPECT_EQ(decodeAssetPassCpca(file, 2, 0, &vcpca, &vinfo).code(), StatusCode::kInvalidArgument);
  CpcaMatrixTransfer mcpca;
  EXPECT_EQ(decodeAssetPassCpcaMatrix(file, 0, 0, &mcpca, &vinfo).code(), StatusCode::kInvalidArgument);
}

TEST(AssetGlossy, CheckAssetEnforcesTheMatrixAndSpecularRules) {
  const BakedAsset good = glossyAsset(2, 5, LightingModel::kDistant);
  ASSERT_TRUE(checkAsset(good).isOk());
  auto expectRefused = [&](const BakedAsset& a, StatusCode code, const char* needle) {
    const Status s = checkAsset(a);
    EXPECT_EQ(s.code(), code) << needle << ": " << s.toString();
    EXPECT_NE(s.message().find(needle), std::string::npos) << s.message();
  };
  BakedAsset a = good;
  a.passes[1].channels = 3;
  a.passes[1].coeffs.resize(a.passes[1].coeffs.size() * 3);
  expectRefused(a, StatusCode::kInvalidArgument, "shadowed matrix passes have 1");
  a = good;
  a.passes[2] = matrixPass(TransferKind::kInterreflected, 1, 1, 5, 2, MatrixPacking::kFull, 1.0f);
  expectRefused(a, StatusCode::kInvalidArgument, "interreflected matrix passes have 3");
  a = good;
  a.passes[1].coeffs.resize(5 * 16);  // full packing where distant shadowed is symmetric (10 entries)
  expectRefused(a, StatusCode::kSizeMismatch, "symmetric packed entries");
  a = good;
  a.specular.pop_back();
  expectRefused(a, StatusCode::kSizeMismatch, "one per vertex");
  a = good;
  a.passes.resize(1);
  expectRefused(a, StatusCode::kInvalidArgument, "no matrix or visibility pass");
  a = good;
  a.specular[2].f0.g = 1.5f;
  expectRefused(a, StatusCode::kInvalidArgument, "outside [0, 1]");
  a = good;
  a.specular[2].f90 = -0.5f;
  expectRefused(a, StatusCode::kInvalidArgument, "f90");
  a = good;
  a.specular[2].f90 = NAN;
  expectRefused(a, StatusCode::kNotFinite, "f90");
  a = good;
  a.specular[2].exponent = -1.0f;
  expectRefused(a, StatusCode::kInvalidArgument, "must be >= 0");
  a = good;
  a.specular[2].exponent = INFINITY;
  expectRefused(a, StatusCode::kNotFinite, "exponent");
  a = good;
  a.passes.push_back(a.passes[1]);
  expectRefused(a, StatusCode::kInvalidArgument, "at most one per kind, form and domain");
  a = good;
  a.passes[1].coeffs[3] = NAN;
  expectRefused(a, StatusCode::kNotFinite, "not finite");
  a = good;
  a.passes[1].coeffs[3] = 1e6f;
  expectRefused(a, StatusCode::kInvalidArgument, "65504");
  a = good;
  a.shOrder = 9;
  a.passes.erase(a.passes.begin());  // the matrix pass first: its order is checked before any size
  for (TransferPass& p : a.passes) p.coeffs.clear();
  expectRefused(a, StatusCode::kInvalidArgument, "matrix passes need order <= 8");
  // Six vertex passes (three kinds, two forms) are allowed, a seventh repeats one; a blob of
  // the wrong packing is refused.
  a = good;
  TransferPass un = matrixPass(TransferKind::kUnshadowed, 1, 0, 5, 2, MatrixPacking::kSymmetric, 1.0f);
  a.passes.push_back(un);
  TransferPass vun;
  vun.kind = TransferKind::kUnshadowed;
  vun.coeffs.assign(5 * 4, 0.5f);
  a.passes.push_back(vun);
  TransferPass vin;
  vin.kind = TransferKind::kInterreflected;
  vin.channels = 3;
  vin.coeffs.assign(5 * 3 * 4, 0.5f);
  a.passes.push_back(vin);
  EXPECT_TRUE(checkAsset(a).isOk()) << checkAsset(a).toString();
  a.passes.push_back(vin);
  expectRefused(a, StatusCode::kInvalidArgument, "repeats the kind of pass");
  a = good;
  TransferCodecSettings f16;
  f16.encoding = TransferEncoding::kFloat16;
  ASSERT_TRUE(encodeTransferMatrix(std::vector<float>(5 * 16, 0.5f), 2, MatrixPacking::kFull, 1, f16, &a.passes[1].encoded).isOk());
  expectRefused(a, StatusCode::kInvalidArgument, "the pass needs symmetric matrices");
  ASSERT_TRUE(encodeTransfer(std::vector<float>(5 * 4, 0.5f), 2, 1, f16, &a.passes[1].encoded).isOk());
  expectRefused(a, StatusCode::kInvalidArgument, "holds vectors");
}

// docs/asset-format.md, "Worked example: a matrix pass": order 2, one vertex, distant
// lighting, a shadowed vector pass, a shadowed matrix pass (symmetric: 10 entries) and one
// specular material. The test checks the table entries and payloads the document prints.
TEST(AssetGlossy, MatchesTheMatrixWorkedExampleInTheDocument) {
  BakedAsset g;
  g.shOrder = 2;
  g.positions = {{1.0f, 2.0f, 3.0f}};
  g.normals = {{0.0f, 1.0f, 0.0f}};
  g.albedo = {{0.5f, 0.25f, 0.125f}};
  g.indices = {0, 0, 0};
  g.passes = {TransferPass{TransferKind::kShadowed, 1, 0, {0.75f, 0.0f, 0.5f, 0.0f}, {}}};
  TransferPass m{TransferKind::kShadowed, 1, 0, {}, {}};
  m.form = TransferForm::kMatrix;
  for (int i = 0; i < 10; ++i) m.coeffs.push_back(0.125f * static_cast<float>(i));
  g.passes.push_back(m);
  g.specular = {{{0.04f, 0.04f, 0.04f}, 32.0f}};
  g.samples = 1024;
  g.seed = 7;
  g.sampling = "hammersley";
  g.name = "tiny";
  const Bytes file = encodeOrDie(g);
  ASSERT_EQ(file.size(), 664u);
  auto at = [&](std::size_t offset, std::initializer_list<int> bytes) {
    std::size_t i = offset;
    for (int b : bytes) {
      ASSERT_EQ(file[i], b) << "offset " << i;
      ++i;
    }
  };
  // Header: version 1.7, order 2, 9 sections, file size 664.
  at(0x00, {0x50, 0x52, 0x54, 0x41, 0x01, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00});
  at(0x18, {0x09, 0x00, 0x00, 0x00});
  at(0x20, {0x98, 0x02, 0x00, 0x00});
  // Entry 6: specular, float32, offset 0x240, 20 bytes, args 0, crc.
  at(0x130, {0x0b, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x40, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
             0x14, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
             0x00, 0x00, 0x00, 0x00, 0x01, 0x5e, 0xe3, 0xcc});
  // Entry 8: matrix transfer, float32, offset 0x270, 40 bytes, kind 1 (shadowed), 1 channel, 0 bounces, crc.
  at(0x180, {0x09, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x70, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
             0x28, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
             0x00, 0x00, 0x00, 0x00, 0xa3, 0xa2, 0x96, 0x1b});
  // Specular payload: f0 0.04 x 3, f90 1, exponent 32.
  at(0x240, {0x0a, 0xd7, 0x23, 0x3d, 0x0a, 0xd7, 0x23, 0x3d, 0x0a, 0xd7, 0x23, 0x3d, 0x00, 0x00, 0x80, 0x3f,
             0x00, 0x00, 0x00, 0x42});
  // Matrix payload: entries (0,0), (1,0), (1,1), (2,0), ... = 0, 0.125, 0.25, 0.375, ...
  at(0x270, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x3e, 0x00, 0x00, 0x80, 0x3e, 0x00, 0x00, 0xc0, 0x3e});
  BakedAsset back;
  ASSERT_TRUE(decodeAsset(file, &back).isOk());
  expectSameAsset(g, back);
}

// A progressive client: a zeroed buffer of the file's size, the encoded matrix pass arriving
// shell by shell; each band prefix decodes as the leading blocks of the full decode.
TEST(AssetGlossy, EncodedMatrixPassDecodesBandByBand) {
  BakedAsset a = glossyAsset(4, 30, LightingModel::kLocalSphere);
  TransferCodecSettings s;
  ASSERT_TRUE(parseTransferSetting("cpca8@0.05", {}, &s).isOk());
  s.cpcaMaxClusters = 4;
  TransferPass& pass = a.passes[2];
  ASSERT_TRUE(encodeTransferMatrix(pass.coeffs, 4, MatrixPacking::kFull, 3, s, &pass.encoded).isOk());
  const Bytes file = encodeOrDie(a);
  AssetSummary summary;
  ASSERT_TRUE(peekAssetHeader(file, &summary).isOk());
  Bytes buffer(file.size(), 0);
  auto arrive = [&](std::uint64_t offset, std::uint64_t size) {
    std::copy_n(file.begin() + static_cast<std::ptrdiff_t>(offset), size, buffer.begin() + static_cast<std::ptrdiff_t>(offset));
  };
  arrive(0, summary.tableEnd);
  for (const AssetSectionInfo& sec : summary.sections) {
    if (sec.type != static_cast<std::uint32_t>(AssetSectionType::kEncodedMatrixTransfer)) arrive(sec.offset, sec.size);
  }
  std::vector<SpecularMaterial> spec;
  const Status specStatus = decodeAssetSpecular(buffer, &spec);
  ASSERT_TRUE(specStatus.isOk()) << specStatus.toString();
  EXPECT_EQ(spec.size(), 30u);
  const AssetSectionInfo& section = summary.sections[summary.passes[2].section];
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(pass.encoded, &info).isOk());
  std::vector<float> full;
  ASSERT_TRUE(decodeTransferMatrix(pass.encoded, 4, &full).isOk());
  TransferPass out;
  int bands = -1;
  EXPECT_FALSE(decodeAssetPass(buffer, 2, 1, &out, &bands).isOk());
  arrive(section.offset, info.parts.front().offset);
  int band = 0;
  for (const TransferPartInfo& part : info.parts) {
    arrive(section.offset + part.offset, part.size);
    if (part.type != TransferPartType::kBand) continue;
    ++band;
    const Status st = decodeAssetPass(buffer, 2, band, &out, &bands);
    ASSERT_TRUE(st.isOk()) << "band " << band << ": " << st.toString();
    EXPECT_EQ(bands, band);
    EXPECT_EQ(out.form, TransferForm::kMatrix);
    const std::size_t Eb = matrixEntryCount(band, MatrixPacking::kFull), E = matrixEntryCount(4, MatrixPacking::kFull);
    ASSERT_EQ(out.coeffs.size(), 30u * 3 * Eb);
    for (std::size_t r = 0; r < 30 * 3; ++r)
      for (std::size_t e = 0; e < Eb; ++e) ASSERT_EQ(out.coeffs[r * Eb + e], full[r * E + e]);
    CpcaMatrixTransfer cpca;
    TransferPass hdr;
    ASSERT_TRUE(decodeAssetPassCpcaMatrix(buffer, 2, band, &cpca, &hdr).isOk());
    EXPECT_EQ(cpca.bands, band);
    if (band < 4) {
      EXPECT_FALSE(decodeAssetPass(buffer, 2, band + 1, &out, &bands).isOk());
    }
  }
  EXPECT_EQ(band, 4);
  // Float32 matrix passes decode only whole.
  EXPECT_EQ(decodeAssetPass(file, 1, 2, &out, &bands).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(decodeAssetPass(file, 1, 0, &out, &bands).isOk());
  EXPECT_EQ(out.coeffs, a.passes[1].coeffs);
}

TEST(AssetGlossy, EveryPrefixAndByteFlipOfAGlossyFileIsRejected) {
  BakedAsset a = glossyAsset(2, 4, LightingModel::kDistant);
  TransferCodecSettings s;
  ASSERT_TRUE(parseTransferSetting("cpca8@0.05", {}, &s).isOk());
  s.cpcaMaxClusters = 2;
  ASSERT_TRUE(encodeTransferMatrix(a.passes[2].coeffs, 2, MatrixPacking::kFull, 3, s, &a.passes[2].encoded).isOk());
  const Bytes file = encodeOrDie(a);
  BakedAsset out;
  for (std::size_t n = 0; n < file.size(); ++n) {
    const Bytes cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(n));
    ASSERT_FALSE(decodeAsset(cut, &out).isOk()) << "prefix " << n;
    ASSERT_FALSE(verifyAsset(cut, nullptr).isOk()) << "prefix " << n;
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
