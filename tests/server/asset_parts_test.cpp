// cutAssetParts against the layout docs/asset-format.md and docs/transfer-codec.md
// specify: where the head ends, that the parts tile the file, and that an encoded
// transfer's parts, fetched as a prefix, decode band by band like the whole blob.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "asset_parts.h"
#include "encoded_asset.h"
#include "prt/transfer_codec.h"
#include "test_tree.h"

namespace prt::serve::test {
namespace {

std::uint64_t alignUp(std::uint64_t x) { return (x + 15) / 16 * 16; }

AssetSummary verified(const std::vector<std::uint8_t>& file) {
  AssetSummary summary;
  const Status s = verifyAsset(file, &summary);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return summary;
}

// The parts start at 0, follow each other without gap or overlap, end at the file's end,
// and none is empty.
void expectTiling(const std::vector<AssetPart>& parts, std::uint64_t fileSize) {
  ASSERT_FALSE(parts.empty());
  std::uint64_t at = 0;
  for (const AssetPart& p : parts) {
    EXPECT_EQ(p.offset, at);
    EXPECT_GT(p.size, 0u);
    at = p.offset + p.size;
  }
  EXPECT_EQ(at, fileSize);
}

// The table index of the (last) section of `type`, or -1.
int sectionOfType(const AssetSummary& summary, AssetSectionType type) {
  int found = -1;
  for (std::size_t i = 0; i < summary.sections.size(); ++i) {
    if (summary.sections[i].type == static_cast<std::uint32_t>(type)) found = static_cast<int>(i);
  }
  return found;
}

std::vector<const AssetPart*> partsOfSection(const std::vector<AssetPart>& parts, int section) {
  std::vector<const AssetPart*> out;
  for (const AssetPart& p : parts) {
    if (p.section == section) out.push_back(&p);
  }
  return out;
}

TEST(AssetParts, PlainAssetIsCutAtEveryPayload) {
  const std::vector<std::uint8_t> file = makeAssetBytes(100, 3, 1, "plain");
  const AssetSummary summary = verified(file);
  const std::vector<AssetPart> parts = cutAssetParts(file, summary);
  expectTiling(parts, file.size());
  const std::size_t n = summary.sections.size();
  ASSERT_EQ(parts.size(), n + 1);
  // encodeAsset's layout: the first payload at 64 + 40 n rounded up to 16.
  EXPECT_EQ(parts[0].kind, AssetPartKind::kHead);
  EXPECT_EQ(parts[0].section, -1);
  EXPECT_EQ(parts[0].size, alignUp(64 + 40 * n));
  int transferParts = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const AssetSectionInfo& s = summary.sections[i];
    const auto mine = partsOfSection(parts, static_cast<int>(i));
    ASSERT_EQ(mine.size(), 1u) << "section " << i;
    const AssetPart& p = *mine[0];
    EXPECT_EQ(p.kind, AssetPartKind::kSection);
    EXPECT_EQ(p.offset, s.offset);
    // The payload plus the zero padding up to the next one (none after the last).
    EXPECT_EQ(p.size, p.offset + p.size == file.size() ? s.size : alignUp(s.size));
    EXPECT_EQ(p.band, -1);
    EXPECT_EQ(p.hasPass, s.type == static_cast<std::uint32_t>(AssetSectionType::kTransfer));
    if (p.hasPass) {
      ++transferParts;
      EXPECT_EQ(static_cast<std::uint32_t>(p.pass), s.arg0);
    }
  }
  EXPECT_EQ(transferParts, 2);
  EXPECT_STREQ(assetPartKindName(AssetPartKind::kHead), "head");
  EXPECT_STREQ(assetPartKindName(AssetPartKind::kTransferBand), "transfer-band");
}

// Concatenates the bytes of `parts` (file order, contiguous).
std::vector<std::uint8_t> joined(const std::vector<std::uint8_t>& file, const std::vector<const AssetPart*>& parts) {
  std::vector<std::uint8_t> out;
  for (const AssetPart* p : parts) out.insert(out.end(), file.begin() + p->offset, file.begin() + p->offset + p->size);
  return out;
}

void expectCutAtBlobParts(const std::vector<std::uint8_t>& file, const std::vector<AssetPart>& parts, int section,
                          const std::vector<std::uint8_t>& blob, int order, int channels, bool clusters,
                          TransferKind pass) {
  SCOPED_TRACE("section " + std::to_string(section));
  const auto mine = partsOfSection(parts, section);
  ASSERT_EQ(mine.size(), static_cast<std::size_t>(1 + (clusters ? 1 : 0) + order));
  std::size_t k = 0;
  EXPECT_EQ(mine[k]->kind, AssetPartKind::kTransferHead);
  // docs/transfer-codec.md: a 48-byte header, then 24 bytes per part (one per band, one more
  // for the clusters).
  EXPECT_EQ(mine[k]->size, 48u + 24u * static_cast<std::uint64_t>(order + (clusters ? 1 : 0)));
  ++k;
  if (clusters) {
    EXPECT_EQ(mine[k++]->kind, AssetPartKind::kTransferClusters);
  }
  for (int l = 0; l < order; ++l, ++k) {
    EXPECT_EQ(mine[k]->kind, AssetPartKind::kTransferBand);
    EXPECT_EQ(mine[k]->band, l);
  }
  for (const AssetPart* p : mine) {
    EXPECT_TRUE(p->hasPass);
    EXPECT_EQ(p->pass, pass);
  }
  // The section's parts hold the blob (and any padding after it).
  std::vector<std::uint8_t> whole = joined(file, mine);
  ASSERT_GE(whole.size(), blob.size());
  EXPECT_TRUE(std::equal(blob.begin(), blob.end(), whole.begin()));
  // What a progressive client does: head, clusters, bands 0..b-1, decode b bands; the
  // result equals decoding b bands of the whole blob.
  for (int b = 1; b <= order; ++b) {
    const std::vector<const AssetPart*> prefixParts(mine.begin(), mine.begin() + 1 + (clusters ? 1 : 0) + b);
    std::vector<std::uint8_t> prefix = joined(file, prefixParts);
    if (b == order) prefix.resize(blob.size());  // the blob without the section's padding
    std::vector<float> fromPrefix, fromWhole;
    const Status sp = decodeTransfer(prefix, b, &fromPrefix);
    ASSERT_TRUE(sp.isOk()) << "bands " << b << ": " << sp.toString();
    ASSERT_TRUE(decodeTransfer(blob, b, &fromWhole).isOk());
    ASSERT_EQ(fromPrefix.size(), fromWhole.size());
    EXPECT_EQ(fromPrefix.size() % static_cast<std::size_t>(channels * b * b), 0u);
    EXPECT_TRUE(fromPrefix == fromWhole) << "bands " << b;
  }
}

TEST(AssetParts, EncodedTransferIsCutAtItsBlobParts) {
  const EncodedTransferAsset a = makeEncodedTransferAsset(400, 4, 3);
  const AssetSummary summary = verified(a.bytes);
  const std::vector<AssetPart> parts = cutAssetParts(a.bytes, summary);
  expectTiling(parts, a.bytes.size());
  int encoded = 0;
  for (std::size_t i = 0; i < summary.sections.size(); ++i) {
    const AssetSectionInfo& s = summary.sections[i];
    if (s.type != static_cast<std::uint32_t>(AssetSectionType::kEncodedTransfer)) {
      EXPECT_EQ(partsOfSection(parts, static_cast<int>(i)).size(), 1u);
      continue;
    }
    ++encoded;
    const bool cpca = s.arg0 == static_cast<std::uint32_t>(TransferKind::kInterreflected);
    expectCutAtBlobParts(a.bytes, parts, static_cast<int>(i), cpca ? a.cpcaBlob : a.quantBlob, a.order, cpca ? 3 : 1,
                         cpca, static_cast<TransferKind>(s.arg0));
  }
  EXPECT_EQ(encoded, 2);
}

// A glossy asset (docs/glossy.md): its CPCA matrix blob is cut like a vector one, the cluster
// ids and the weights (both needed before any shell) as clusters parts, then one part per
// shell; every part of it is marked as a matrix pass, and each shell prefix decodes as the
// leading blocks of the whole blob.
TEST(AssetParts, EncodedMatrixTransferIsCutAtItsShells) {
  const int order = 3, vertices = 300;
  BakedAsset a;
  a.shOrder = order;
  a.name = "glossy";
  for (int v = 0; v < vertices; ++v) {
    const float t = static_cast<float>(v);
    a.positions.push_back({t, 0.0f, 0.5f * t});
    a.normals.push_back({0.0f, 1.0f, 0.0f});
    a.albedo.push_back({0.5f, 0.5f, 0.5f});
    a.specular.push_back({{0.04f, 0.04f, 0.04f}, 8.0f});
  }
  for (int v = 0; v + 2 < vertices; ++v) a.indices.insert(a.indices.end(), {std::uint32_t(v), std::uint32_t(v + 1), std::uint32_t(v + 2)});
  TransferPass diffuse{TransferKind::kShadowed, 1, 0, std::vector<float>(static_cast<std::size_t>(vertices * order * order), 0.25f), {}};
  a.passes.push_back(diffuse);
  TransferPass m{TransferKind::kShadowed, 1, 0, {}, {}};
  m.form = TransferForm::kMatrix;
  const std::size_t entries = matrixEntryCount(order, MatrixPacking::kSymmetric);
  for (int v = 0; v < vertices; ++v) {
    for (std::size_t e = 0; e < entries; ++e) m.coeffs.push_back(0.1f * std::sin(0.05f * v + 0.7f * e) + (e == 0 ? 0.5f : 0.0f));
  }
  TransferCodecSettings settings;
  ASSERT_TRUE(parseTransferSetting("cpca8@0.05", {}, &settings).isOk());
  ASSERT_TRUE(encodeTransferMatrix(m.coeffs, order, MatrixPacking::kSymmetric, 1, settings, &m.encoded).isOk());
  const std::vector<std::uint8_t> blob = m.encoded;
  a.passes.push_back(m);
  std::vector<std::uint8_t> file;
  ASSERT_TRUE(encodeAsset(a, &file).isOk());
  const AssetSummary summary = verified(file);
  const std::vector<AssetPart> parts = cutAssetParts(file, summary);
  expectTiling(parts, file.size());
  const int matrixSection = sectionOfType(summary, AssetSectionType::kEncodedMatrixTransfer);
  ASSERT_GE(matrixSection, 0);
  const auto mine = partsOfSection(parts, matrixSection);
  ASSERT_EQ(mine.size(), static_cast<std::size_t>(1 + 2 + order));  // head, ids, weights, shells
  EXPECT_EQ(mine[0]->kind, AssetPartKind::kTransferHead);
  EXPECT_EQ(mine[1]->kind, AssetPartKind::kTransferClusters);
  EXPECT_EQ(mine[2]->kind, AssetPartKind::kTransferClusters);
  for (int l = 0; l < order; ++l) {
    EXPECT_EQ(mine[3 + l]->kind, AssetPartKind::kTransferBand);
    EXPECT_EQ(mine[3 + l]->band, l);
  }
  for (const AssetPart* p : mine) {
    EXPECT_TRUE(p->hasPass && p->matrix);
    EXPECT_EQ(p->pass, TransferKind::kShadowed);
  }
  for (const AssetPart& p : parts) {
    if (p.section != matrixSection) {
      EXPECT_FALSE(p.matrix) << "section " << p.section;
    }
  }
  for (int b = 1; b <= order; ++b) {
    std::vector<std::uint8_t> prefix = joined(file, {mine.begin(), mine.begin() + 3 + b});
    if (b == order) prefix.resize(blob.size());
    std::vector<float> fromPrefix, fromWhole;
    const Status sp = decodeTransferMatrix(prefix, b, &fromPrefix);
    ASSERT_TRUE(sp.isOk()) << "bands " << b << ": " << sp.toString();
    ASSERT_TRUE(decodeTransferMatrix(blob, b, &fromWhole).isOk());
    EXPECT_EQ(fromPrefix.size(), static_cast<std::size_t>(vertices) * matrixEntryCount(b, MatrixPacking::kSymmetric));
    EXPECT_TRUE(fromPrefix == fromWhole) << "bands " << b;
  }
}

// Transfer textures (format 1.4): an encoded texel pass is cut at its bands like a vertex
// one; its parts and the atlas sections' are marked texel, the vertex passes' vertex.
TEST(AssetParts, EncodedTexelTransferIsCutAtItsBandsAndMarkedTexel) {
  const TexelTransferAsset texel = makeTexelTransferAsset(60, 3, 5);
  const AssetSummary summary = verified(texel.bytes);
  const std::vector<AssetPart> parts = cutAssetParts(texel.bytes, summary);
  expectTiling(parts, texel.bytes.size());
  const int texelSection = sectionOfType(summary, AssetSectionType::kEncodedTexelTransfer);
  ASSERT_GE(texelSection, 0);
  const auto mine = partsOfSection(parts, texelSection);
  ASSERT_EQ(mine.size(), static_cast<std::size_t>(1 + texel.order));  // blob head, bands (q8: no clusters)
  EXPECT_EQ(mine[0]->kind, AssetPartKind::kTransferHead);
  for (int l = 0; l < texel.order; ++l) {
    EXPECT_EQ(mine[1 + static_cast<std::size_t>(l)]->kind, AssetPartKind::kTransferBand);
    EXPECT_EQ(mine[1 + static_cast<std::size_t>(l)]->band, l);
  }
  for (const AssetPart& p : parts) {
    if (p.section < 0) continue;
    const std::uint32_t type = summary.sections[static_cast<std::size_t>(p.section)].type;
    const bool texelData = type >= static_cast<std::uint32_t>(AssetSectionType::kAtlasUv);
    EXPECT_EQ(p.domain, texelData ? TransferDomain::kTexel : TransferDomain::kVertex) << "section " << p.section;
    EXPECT_EQ(p.hasPass, p.section == texelSection || type == static_cast<std::uint32_t>(AssetSectionType::kTransfer))
        << "section " << p.section;
    if (p.section == texelSection) {
      EXPECT_EQ(p.pass, TransferKind::kShadowed);
    }
    EXPECT_FALSE(p.matrix);
  }
  // Head and bands 0..b-1 form a blob prefix that decodes like the whole blob at b bands.
  for (int b = 1; b <= texel.order; ++b) {
    std::vector<std::uint8_t> prefix = joined(texel.bytes, {mine.begin(), mine.begin() + 1 + b});
    if (b == texel.order) prefix.resize(texel.blob.size());
    std::vector<float> fromPrefix, fromWhole;
    ASSERT_TRUE(decodeTransfer(prefix, b, &fromPrefix).isOk()) << b << " bands";
    ASSERT_TRUE(decodeTransfer(texel.blob, b, &fromWhole).isOk());
    EXPECT_EQ(fromPrefix.size(), summary.texelCount * static_cast<std::size_t>(b * b));
    EXPECT_TRUE(fromPrefix == fromWhole) << b << " bands";
  }
}

// Texel normals (format 1.6) travel like the atlas sections: one part of their own, marked
// texel and without a pass, so the page fetches them with the geometry.
TEST(AssetParts, TexelNormalsAreOneTexelPartWithoutAPass) {
  const TexelTransferAsset texel = makeTexelTransferAsset(60, 3, 5);
  BakedAsset asset;
  ASSERT_TRUE(decodeAsset(texel.bytes, &asset).isOk());
  asset.texelNormals.assign(2 * asset.texelCoverage.size(), 0);  // +z at every (sampled) texel
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(encodeAsset(asset, &bytes).isOk());
  const AssetSummary summary = verified(bytes);
  const std::vector<AssetPart> parts = cutAssetParts(bytes, summary);
  expectTiling(parts, bytes.size());
  const int normals = sectionOfType(summary, AssetSectionType::kTexelNormals);
  ASSERT_GE(normals, 0);
  const auto mine = partsOfSection(parts, normals);
  ASSERT_EQ(mine.size(), 1u);
  EXPECT_EQ(mine[0]->kind, AssetPartKind::kSection);
  EXPECT_EQ(mine[0]->domain, TransferDomain::kTexel);
  EXPECT_FALSE(mine[0]->hasPass);
  EXPECT_GE(mine[0]->size, 4 * summary.texelCount);
}

// A TPFL visibility pass (format 1.5) is cut at its own bands (order 2n - 1, not the asset's
// n) and its parts are marked visibility and texel, so a client without a TPFL shader can
// leave them alone; the texel vector pass beside it keeps its plain listing.
TEST(AssetParts, EncodedVisibilityPassIsCutAtItsOwnBandsAndMarked) {
  const TexelTransferAsset texel = makeTexelTransferAsset(60, 3, 5, true);
  const AssetSummary summary = verified(texel.bytes);
  const std::vector<AssetPart> parts = cutAssetParts(texel.bytes, summary);
  expectTiling(parts, texel.bytes.size());
  const int visibilitySection = sectionOfType(summary, AssetSectionType::kEncodedTexelVisibility);
  const int texelSection = sectionOfType(summary, AssetSectionType::kEncodedTexelTransfer);
  ASSERT_GE(visibilitySection, 0);
  ASSERT_GE(texelSection, 0);
  const int m = 2 * texel.order - 1;
  const auto mine = partsOfSection(parts, visibilitySection);
  ASSERT_EQ(mine.size(), static_cast<std::size_t>(1 + m));  // blob head, then bands 0..m-1 (q8: no clusters)
  for (int l = 0; l < m; ++l) EXPECT_EQ(mine[1 + static_cast<std::size_t>(l)]->band, l);
  for (const AssetPart* p : mine) {
    EXPECT_TRUE(p->hasPass && p->visibility && !p->matrix);
    EXPECT_EQ(p->domain, TransferDomain::kTexel);
    EXPECT_EQ(p->pass, TransferKind::kShadowed);
  }
  for (const AssetPart* p : partsOfSection(parts, texelSection)) EXPECT_FALSE(p->visibility);
}

TEST(AssetParts, UnreadableBlobsAndEmptySectionsStayWhole) {
  const std::vector<std::uint8_t> plain = makeAssetBytes(40, 2, 4, "odd sections");
  ExtraSection garbage;  // a type-8 payload that is no blob
  garbage.args[0] = static_cast<std::uint32_t>(TransferKind::kShadowed);
  garbage.args[1] = 1;
  garbage.payload.assign(200, 0x5a);
  EncodedTransferAsset donor = makeEncodedTransferAsset(40, 2, 4);
  ExtraSection shortBlob = garbage;  // a real blob missing its last byte
  shortBlob.args[0] = static_cast<std::uint32_t>(TransferKind::kInterreflected);
  shortBlob.args[1] = 3;
  shortBlob.payload.assign(donor.cpcaBlob.begin(), donor.cpcaBlob.end() - 1);
  ExtraSection empty;  // an unknown type with no payload
  empty.type = static_cast<AssetSectionType>(99);
  // The reader rejects such a file; cutting only needs the table (verifyAsset comes first
  // in the server, so this is the defensive path).
  AssetSummary summary;
  const std::vector<std::uint8_t> file = appendSections(plain, {garbage, empty, shortBlob}, &summary.sections);
  summary.tableEnd = kAssetHeaderSize + summary.sections.size() * kAssetSectionEntrySize;
  EXPECT_FALSE(verifyAsset(file, nullptr).isOk());
  const std::vector<AssetPart> parts = cutAssetParts(file, summary);
  expectTiling(parts, file.size());
  const int n = static_cast<int>(summary.sections.size());
  ASSERT_EQ(parts.size(), static_cast<std::size_t>(n));  // head + every section but the empty one
  EXPECT_EQ(partsOfSection(parts, n - 1).size(), 1u);
  EXPECT_EQ(partsOfSection(parts, n - 1)[0]->kind, AssetPartKind::kSection);
  EXPECT_EQ(partsOfSection(parts, n - 2).size(), 0u);
  EXPECT_EQ(partsOfSection(parts, n - 3).size(), 1u);
  EXPECT_EQ(partsOfSection(parts, n - 3)[0]->kind, AssetPartKind::kSection);
}

TEST(AssetParts, ATableThatDoesNotFitGivesNoParts) {
  const std::vector<std::uint8_t> file = makeAssetBytes(40, 2, 4, "short");
  const AssetSummary summary = verified(file);
  const std::vector<std::uint8_t> cut(file.begin(), file.end() - 1);
  EXPECT_TRUE(cutAssetParts(cut, summary).empty());
  AssetSummary none = summary;
  none.sections.clear();
  EXPECT_TRUE(cutAssetParts(file, none).empty());
}

}  // namespace
}  // namespace prt::serve::test
