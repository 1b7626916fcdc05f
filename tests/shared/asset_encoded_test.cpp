// Encoded transfer sections (type 8, a transfer-codec blob) and progressive decoding:
// decodeAssetGeometry and decodeAssetPass on a buffer in which only some sections arrived.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/asset.h"
#include "prt/sampling.h"
#include "prt/transfer_codec.h"

namespace prt {
namespace {

using Bytes = std::vector<std::uint8_t>;

// A smooth transfer field (what a codec is for): each coefficient a low-order function of
// the vertex index, so quantisation and CPCA both have something to find.
BakedAsset makeSmoothAsset(int order, std::size_t vertexCount) {
  BakedAsset a;
  a.shOrder = order;
  Pcg32 rng(7);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const float t = static_cast<float>(v) / static_cast<float>(vertexCount);
    a.positions.push_back({t, std::sin(6 * t), std::cos(6 * t)});
    a.normals.push_back(squareToSphere(rng.nextFloat(), rng.nextFloat()));
    a.albedo.push_back({0.5f, 0.6f, 0.7f});
  }
  for (std::size_t t = 0; t + 2 < vertexCount; ++t) {
    a.indices.insert(a.indices.end(), {static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(t + 1),
                                       static_cast<std::uint32_t>(t + 2)});
  }
  const std::size_t n = static_cast<std::size_t>(order * order);
  for (TransferKind kind : {TransferKind::kShadowed, TransferKind::kInterreflected}) {
    TransferPass p;
    p.kind = kind;
    p.channels = kind == TransferKind::kInterreflected ? 3 : 1;
    p.bounces = kind == TransferKind::kInterreflected ? 2 : 0;
    for (std::size_t v = 0; v < vertexCount; ++v) {
      const float t = static_cast<float>(v) / static_cast<float>(vertexCount);
      for (int c = 0; c < p.channels; ++c)
        for (std::size_t i = 0; i < n; ++i)
          p.coeffs.push_back(std::cos(3.0f * t * static_cast<float>(i + 1) + static_cast<float>(c)) /
                             static_cast<float>(i + 1));
    }
    a.passes.push_back(std::move(p));
  }
  a.sampling = "hammersley";
  a.name = "encoded";
  return a;
}

Bytes encodeOrDie(const BakedAsset& a) {
  Bytes out;
  const Status s = encodeAsset(a, &out);
  EXPECT_TRUE(s.isOk()) << s.message();
  return out;
}

// Encodes every pass of `a` with `setting` into pass.encoded.
void encodePasses(BakedAsset* a, const char* setting) {
  TransferCodecSettings settings;
  ASSERT_TRUE(parseTransferSetting(setting, TransferCodecSettings{}, &settings).isOk());
  for (TransferPass& p : a->passes) {
    const Status s = encodeTransfer(p.coeffs, a->shOrder, p.channels, settings, &p.encoded);
    ASSERT_TRUE(s.isOk()) << s.message();
  }
}

TEST(AssetEncoded, RoundTripKeepsTheBlobAndDecodesItsFloats) {
  BakedAsset a = makeSmoothAsset(4, 200);
  encodePasses(&a, "q16");
  const Bytes file = encodeOrDie(a);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(file, &summary).isOk());
  EXPECT_EQ(summary.versionMinor, 7);
  ASSERT_EQ(summary.passes.size(), 2u);
  EXPECT_TRUE(summary.passes[0].encoded);
  EXPECT_EQ(summary.passes[0].bytes, a.passes[0].encoded.size());

  BakedAsset b;
  const Status s = decodeAsset(file, &b);
  ASSERT_TRUE(s.isOk()) << s.message();
  for (std::size_t k = 0; k < a.passes.size(); ++k) {
    EXPECT_EQ(b.passes[k].encoded, a.passes[k].encoded);
    std::vector<float> expected;
    ASSERT_TRUE(decodeTransfer(a.passes[k].encoded, a.shOrder, &expected).isOk());
    EXPECT_EQ(b.passes[k].coeffs, expected);
    // q16: a step of max|x|/32767 per channel and coefficient, so well under 1e-3 here.
    for (std::size_t i = 0; i < expected.size(); ++i) ASSERT_NEAR(expected[i], a.passes[k].coeffs[i], 1e-3f);
  }
  // Re-encoding the decoded asset writes the same bytes (the blob is kept, not re-made).
  EXPECT_EQ(encodeOrDie(b), file);
}

TEST(AssetEncoded, FilesWithoutEncodedPassesCarryTheCurrentMinorVersionToo) {
  // Since 1.3 the writer always writes the current minor version, 1.4 now (docs/asset-format.md).
  const Bytes file = encodeOrDie(makeSmoothAsset(3, 50));
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(file, &summary).isOk());
  EXPECT_EQ(summary.versionMinor, 7);
  EXPECT_FALSE(summary.passes[0].encoded);
}

TEST(AssetEncoded, WriterRejectsABlobOfAnotherShape) {
  BakedAsset a = makeSmoothAsset(4, 100);
  encodePasses(&a, "q8");
  BakedAsset wrongOrder = a;
  wrongOrder.shOrder = 3;  // blob says 4
  EXPECT_FALSE(checkAsset(wrongOrder).isOk());
  BakedAsset wrongChannels = a;
  wrongChannels.passes[0].channels = 3;
  EXPECT_FALSE(checkAsset(wrongChannels).isOk());
  BakedAsset garbage = a;
  garbage.passes[0].encoded = {1, 2, 3, 4};
  EXPECT_FALSE(checkAsset(garbage).isOk());
}

TEST(AssetEncoded, EveryByteFlipInAnEncodedSectionIsRejected) {
  BakedAsset a = makeSmoothAsset(3, 40);
  encodePasses(&a, "cpca8@0.05");
  const Bytes file = encodeOrDie(a);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(file, &summary).isOk());
  const AssetSectionInfo& section = summary.sections[summary.passes[1].section];
  for (std::uint64_t i = section.offset; i < section.offset + section.size; ++i) {
    Bytes bad = file;
    bad[static_cast<std::size_t>(i)] ^= 0x20;
    BakedAsset out;
    ASSERT_FALSE(decodeAsset(bad, &out).isOk()) << "flip at " << i;
    ASSERT_FALSE(verifyAsset(bad, nullptr).isOk()) << "flip at " << i;
  }
}

// The progressive client's view: a zeroed buffer of the file's size, filled piece by piece.
TEST(AssetEncoded, ProgressiveDecodingBandByBand) {
  BakedAsset a = makeSmoothAsset(5, 300);
  encodePasses(&a, "q16");
  const Bytes file = encodeOrDie(a);
  AssetSummary summary;
  ASSERT_TRUE(peekAssetHeader(file, &summary).isOk());

  Bytes buffer(file.size(), 0);
  auto arrive = [&](std::uint64_t offset, std::uint64_t size) {
    std::copy(file.begin() + static_cast<std::ptrdiff_t>(offset), file.begin() + static_cast<std::ptrdiff_t>(offset + size),
              buffer.begin() + static_cast<std::ptrdiff_t>(offset));
  };
  arrive(0, summary.tableEnd);
  BakedAsset geometry;
  EXPECT_FALSE(decodeAssetGeometry(buffer, &geometry).isOk()) << "geometry has not arrived";
  for (const AssetSectionInfo& s : summary.sections) {
    if (s.type != static_cast<std::uint32_t>(AssetSectionType::kEncodedTransfer)) arrive(s.offset, s.size);
  }
  ASSERT_TRUE(decodeAssetGeometry(buffer, &geometry).isOk());
  ASSERT_EQ(geometry.positions.size(), a.positions.size());
  for (std::size_t v = 0; v < a.positions.size(); ++v) {
    ASSERT_EQ(geometry.positions[v].x, a.positions[v].x);
    ASSERT_EQ(geometry.positions[v].z, a.positions[v].z);
  }
  EXPECT_EQ(geometry.indices, a.indices);
  EXPECT_TRUE(geometry.passes.empty());

  const int pass = 1;  // interreflected, 3 channels
  const AssetSectionInfo& section = summary.sections[summary.passes[pass].section];
  const auto blob = std::span<const std::uint8_t>(file).subspan(static_cast<std::size_t>(section.offset),
                                                               static_cast<std::size_t>(section.size));
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
  std::vector<float> full;
  ASSERT_TRUE(decodeTransfer(blob, a.shOrder, &full).isOk());

  TransferPass out;
  int bands = -1;
  EXPECT_FALSE(decodeAssetPass(buffer, pass, 1, &out, &bands).isOk()) << "nothing of the blob has arrived";
  // Blob header and table first, then each part in order.
  std::uint64_t headEnd = info.parts.front().offset;
  arrive(section.offset, headEnd);
  int band = 0;
  for (const TransferPartInfo& part : info.parts) {
    arrive(section.offset + part.offset, part.size);
    if (part.type != TransferPartType::kBand) continue;
    ++band;
    const Status s = decodeAssetPass(buffer, pass, band, &out, &bands);
    ASSERT_TRUE(s.isOk()) << "band " << band << ": " << s.message();
    EXPECT_EQ(bands, band);
    EXPECT_EQ(out.channels, 3);
    const std::size_t n = static_cast<std::size_t>(band * band), N = static_cast<std::size_t>(a.shOrder * a.shOrder);
    ASSERT_EQ(out.coeffs.size(), a.positions.size() * 3 * n);
    for (std::size_t v = 0; v < a.positions.size(); ++v)
      for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(out.coeffs[(v * 3 + c) * n + i], full[(v * 3 + c) * N + i]);
    // One band further has not arrived: its part checksum fails on the zeros.
    if (band < a.shOrder) EXPECT_FALSE(decodeAssetPass(buffer, pass, band + 1, &out, &bands).isOk());
  }
  EXPECT_EQ(band, a.shOrder);
}

TEST(AssetEncoded, FloatPassesDecodeOnlyWhole) {
  const BakedAsset a = makeSmoothAsset(3, 30);
  const Bytes file = encodeOrDie(a);
  TransferPass out;
  int bands = 0;
  EXPECT_FALSE(decodeAssetPass(file, 0, 2, &out, &bands).isOk());
  ASSERT_TRUE(decodeAssetPass(file, 0, 0, &out, &bands).isOk());
  EXPECT_EQ(bands, 3);
  EXPECT_EQ(out.coeffs, a.passes[0].coeffs);
  EXPECT_FALSE(decodeAssetPass(file, 5, 0, &out, &bands).isOk());
  Bytes damaged = file;
  damaged[damaged.size() - 1] ^= 1;  // the last section is a transfer pass
  EXPECT_FALSE(decodeAssetPass(damaged, 1, 0, &out, &bands).isOk());
}

// The unexpanded CPCA form of a pass, as the web client renders it, from a progressive
// buffer: each band prefix expands to what decodeAssetPass gives; other encodings and
// float32 passes are refused by name.
TEST(AssetEncoded, CpcaPassDecodesUnexpandedFromEveryBandPrefix) {
  BakedAsset a = makeSmoothAsset(4, 400);
  encodePasses(&a, "cpca8@0.02");
  const Bytes file = encodeOrDie(a);
  for (int pass = 0; pass < 2; ++pass) {
    for (int bands = 1; bands <= a.shOrder; ++bands) {
      CpcaTransfer cpca;
      TransferPass info;
      const Status s = decodeAssetPassCpca(file, pass, bands, &cpca, &info);
      ASSERT_TRUE(s.isOk()) << s.message();
      EXPECT_EQ(info.kind, a.passes[static_cast<std::size_t>(pass)].kind);
      EXPECT_EQ(info.channels, a.passes[static_cast<std::size_t>(pass)].channels);
      EXPECT_TRUE(info.coeffs.empty());
      ASSERT_EQ(cpca.bands.size(), static_cast<std::size_t>(bands));
      std::vector<float> expanded(a.positions.size() * static_cast<std::size_t>(info.channels * bands * bands));
      ASSERT_TRUE(cpcaReconstruct(cpca, expanded).isOk());
      TransferPass reference;
      int decoded = 0;
      ASSERT_TRUE(decodeAssetPass(file, pass, bands, &reference, &decoded).isOk());
      EXPECT_EQ(expanded, reference.coeffs) << "pass " << pass << ", " << bands << " bands";
    }
  }
  CpcaTransfer cpca;
  TransferPass info;
  EXPECT_EQ(decodeAssetPassCpca(file, 2, 0, &cpca, &info).code(), StatusCode::kInvalidArgument);
  Bytes damaged = file;
  damaged[damaged.size() - 1] ^= 1;
  EXPECT_FALSE(decodeAssetPassCpca(damaged, 1, 0, &cpca, &info).isOk());

  BakedAsset q = makeSmoothAsset(3, 40);
  encodePasses(&q, "q8");
  Status s = decodeAssetPassCpca(encodeOrDie(q), 0, 0, &cpca, &info);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("not CPCA"), std::string::npos) << s.message();
  s = decodeAssetPassCpca(encodeOrDie(makeSmoothAsset(3, 40)), 0, 0, &cpca, &info);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("float32"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace prt
