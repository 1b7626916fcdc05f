#include "encoded_asset.h"

#include <stdexcept>
#include <string>

#include "prt/checksum.h"
#include "prt/transfer_codec.h"
#include "test_tree.h"

namespace prt::serve::test {
namespace {

void putU16(std::uint8_t* p, std::uint16_t v) {
  for (int i = 0; i < 2; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void putU32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void putU64(std::uint8_t* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

std::uint64_t alignUp(std::uint64_t x) { return (x + kAssetAlignment - 1) / kAssetAlignment * kAssetAlignment; }

std::vector<std::uint8_t> encode(std::span<const float> transfer, int order, int channels, const char* setting) {
  TransferCodecSettings settings;
  if (Status s = parseTransferSetting(setting, {}, &settings); !s.isOk()) throw std::runtime_error(s.toString());
  std::vector<std::uint8_t> blob;
  if (Status s = encodeTransfer(transfer, order, channels, settings, &blob); !s.isOk()) {
    throw std::runtime_error(std::string("encodeTransfer ") + setting + ": " + s.toString());
  }
  return blob;
}

}  // namespace

std::vector<std::uint8_t> appendSections(const std::vector<std::uint8_t>& asset, const std::vector<ExtraSection>& extra,
                                         std::vector<AssetSectionInfo>* table) {
  AssetSummary summary;
  if (Status s = peekAssetHeader(asset, &summary); !s.isOk()) throw std::runtime_error("peekAssetHeader: " + s.toString());
  struct Planned {
    std::uint32_t type, format;
    std::uint32_t args[3];
    std::span<const std::uint8_t> payload;
    std::uint64_t offset = 0;
  };
  std::vector<Planned> plan;
  for (const AssetSectionInfo& s : summary.sections) {
    plan.push_back({s.type, s.format, {s.arg0, s.arg1, s.arg2}, {asset.data() + s.offset, s.size}});
  }
  for (const ExtraSection& e : extra) {
    plan.push_back({static_cast<std::uint32_t>(e.type), static_cast<std::uint32_t>(AssetElementFormat::kBytes),
                    {e.args[0], e.args[1], e.args[2]}, e.payload});
  }
  const std::uint64_t tableEnd = kAssetHeaderSize + plan.size() * kAssetSectionEntrySize;
  std::uint64_t end = tableEnd;
  for (Planned& p : plan) {
    p.offset = alignUp(end);
    end = p.offset + p.payload.size();
  }
  std::vector<std::uint8_t> out(end, 0);
  std::copy(asset.begin(), asset.begin() + kAssetHeaderSize, out.begin());
  namespace L = asset_layout;
  std::uint8_t* entries = out.data() + kAssetHeaderSize;
  if (table) table->clear();
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Planned& p = plan[i];
    std::uint8_t* e = entries + i * kAssetSectionEntrySize;
    putU32(e + L::kEntryType, p.type);
    putU32(e + L::kEntryFormat, p.format);
    putU64(e + L::kEntryOffset, p.offset);
    putU64(e + L::kEntrySize, p.payload.size());
    putU32(e + L::kEntryArg0, p.args[0]);
    putU32(e + L::kEntryArg1, p.args[1]);
    putU32(e + L::kEntryArg2, p.args[2]);
    putU32(e + L::kEntryCrc, crc32c(p.payload));
    std::copy(p.payload.begin(), p.payload.end(), out.begin() + static_cast<std::ptrdiff_t>(p.offset));
    if (table) {
      table->push_back({p.type, p.format, p.offset, p.payload.size(), p.args[0], p.args[1], p.args[2], crc32c(p.payload)});
    }
  }
  putU16(out.data() + L::kVersionMinor, 2);  // encoded transfer is a 1.2 section type
  putU32(out.data() + L::kSectionCount, static_cast<std::uint32_t>(plan.size()));
  putU32(out.data() + L::kTableCrc, crc32c({entries, plan.size() * kAssetSectionEntrySize}));
  putU64(out.data() + L::kFileSize, out.size());
  putU32(out.data() + L::kHeaderCrc, crc32c({out.data(), L::kHeaderCrc}));
  return out;
}

EncodedTransferAsset makeEncodedTransferAsset(int vertices, int order, std::uint32_t seed) {
  const std::vector<std::uint8_t> plain = makeAssetBytes(vertices, order, seed, "encoded transfer");
  BakedAsset asset;
  if (Status s = decodeAsset(plain, &asset); !s.isOk()) throw std::runtime_error("decodeAsset: " + s.toString());
  // Unshadowed stays a float32 section; its coefficients, scaled, stand in for a shadowed
  // pass; the interreflected pass moves into a CPCA blob.
  const TransferPass unshadowed = *findPass(asset, TransferKind::kUnshadowed);
  const TransferPass interreflected = *findPass(asset, TransferKind::kInterreflected);
  asset.passes = {unshadowed};
  std::vector<std::uint8_t> base;
  if (Status s = encodeAsset(asset, &base); !s.isOk()) throw std::runtime_error("encodeAsset: " + s.toString());

  EncodedTransferAsset out;
  out.order = order;
  out.cpcaBlob = encode(interreflected.coeffs, order, 3, "cpca8@0.05");
  std::vector<float> shadowed = unshadowed.coeffs;
  for (float& x : shadowed) x *= 0.75f;
  out.quantBlob = encode(shadowed, order, 1, "q8");
  ExtraSection cpca, quant;
  cpca.args[0] = static_cast<std::uint32_t>(TransferKind::kInterreflected);
  cpca.args[1] = 3;
  cpca.args[2] = static_cast<std::uint32_t>(interreflected.bounces);
  cpca.payload = out.cpcaBlob;
  quant.args[0] = static_cast<std::uint32_t>(TransferKind::kShadowed);
  quant.args[1] = 1;
  quant.payload = out.quantBlob;
  out.bytes = appendSections(base, {cpca, quant});
  return out;
}

TexelTransferAsset makeTexelTransferAsset(int vertices, int order, std::uint32_t seed, bool withVisibility) {
  BakedAsset asset;
  if (Status s = decodeAsset(makeAssetBytes(vertices, order, seed, "texel transfer"), &asset); !s.isOk()) {
    throw std::runtime_error("decodeAsset: " + s.toString());
  }
  const auto triangles = static_cast<std::uint32_t>(asset.indices.size() / 3);
  TexelTransferAsset out;
  out.order = order;
  out.atlases = {{16, 8, 0, triangles / 2}, {8, 8, triangles / 2, triangles - triangles / 2}};
  asset.atlases = out.atlases;
  for (std::size_t v = 0; v < asset.positions.size(); ++v) {
    const float t = static_cast<float>(v) / static_cast<float>(asset.positions.size() - 1);
    asset.atlasUv.insert(asset.atlasUv.end(), {t, 1.0f - t});
  }
  const std::uint64_t texels = assetTexelCount(asset);
  asset.texelCoverage.assign(texels, static_cast<std::uint8_t>(TexelCoverage::kSampled));
  std::vector<float> coeffs;
  const auto n = static_cast<std::uint64_t>(order * order);
  for (std::uint64_t i = 0; i < texels * n; ++i) coeffs.push_back(0.25f + 0.125f * static_cast<float>((i * 7 + seed) % 5) / static_cast<float>(i % n + 1));
  out.blob = encode(coeffs, order, 1, "q8");
  TransferPass texel{TransferKind::kShadowed, 1, 0, {}, out.blob};
  texel.domain = TransferDomain::kTexel;
  asset.passes.push_back(std::move(texel));
  if (withVisibility) {
    const int m = 2 * order - 1;
    std::vector<float> v;
    for (std::uint64_t i = 0; i < texels * static_cast<std::uint64_t>(m * m); ++i) v.push_back(0.5f / static_cast<float>(i % 7 + 1));
    out.visibilityBlob = encode(v, m, 1, "q8");
    TransferPass visibility{TransferKind::kShadowed, 1, 0, {}, out.visibilityBlob, TransferForm::kVisibility, TransferDomain::kTexel, m};
    asset.passes.push_back(std::move(visibility));
    asset.specular.assign(asset.positions.size(), SpecularMaterial{{0.04f, 0.04f, 0.04f}, 20.0f, 1.0f});
  }
  if (Status s = encodeAsset(asset, &out.bytes); !s.isOk()) throw std::runtime_error("encodeAsset: " + s.toString());
  return out;
}

}  // namespace prt::serve::test
