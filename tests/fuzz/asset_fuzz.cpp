// libFuzzer entry point for the asset reader (docs/asset-format.md). Build, for example:
//   clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -Ishared -Ishared/prt/codec \
//     tests/fuzz/asset_fuzz.cpp shared/prt/*.cpp shared/prt/codec/*.cpp -o asset_fuzz
//   ./asset_fuzz -max_total_time=60 CORPUS_DIR
//
// Random bytes almost never pass a CRC, which would confine the fuzzer to the header
// checks. So the first input byte picks a mode: with bit 0 set, the rest of the input gets
// its checksums recomputed before decoding (as the tests' reseal() does), which lets the
// fuzzer reach the table, size, content and metadata checks; otherwise the bytes are
// decoded as they are. With bit 1 set, the input instead describes a small glossy asset
// (order, lighting model, a matrix pass float32 or encoded, specular materials) that is
// encoded and then damaged by (position, xor) edits, so that the matrix, encoded matrix and
// specular sections are explored from well-formed files. With bit 2 set (and bit 1 clear),
// the input describes a small asset with transfer textures (atlases, atlas uv, coverage, a
// texel pass float32 or encoded, optionally a vertex pass and a TPFL visibility pass of its
// own order with the specular materials it needs, and texel normals), likewise encoded and
// damaged, so that the atlas, texel, visibility and texel normals sections (formats 1.4 to
// 1.6) are explored from well-formed files.
//
// Beyond "no crash, no sanitizer report", it traps when the entry points disagree:
// decodeAsset and verifyAsset must return the same code; whatever decodes must also pass
// peekAssetHeader with the same summary, and must re-encode (the encoder accepts
// everything the decoder does) to bytes that decode to the same asset; every pass decodes
// progressively to the same floats, decodeAssetSpecular to the same materials and
// decodeAssetAtlases to the same atlases.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "prt/asset.h"
#include "prt/checksum.h"
#include "prt/transfer_codec.h"

namespace {

std::uint32_t rd32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
std::uint64_t rd64(const std::vector<std::uint8_t>& b, std::size_t at) {
  return static_cast<std::uint64_t>(rd32(b, at)) | static_cast<std::uint64_t>(rd32(b, at + 4)) << 32;
}
void wr32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Recomputes the section, table and header checksums wherever they fit in the input.
void reseal(std::vector<std::uint8_t>& b) {
  namespace L = prt::asset_layout;
  if (b.size() < prt::kAssetHeaderSize) return;
  const std::uint64_t n = rd32(b, L::kSectionCount);
  const std::uint64_t tableEnd = prt::kAssetHeaderSize + n * prt::kAssetSectionEntrySize;
  if (tableEnd <= b.size()) {
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::size_t e = prt::kAssetHeaderSize + static_cast<std::size_t>(i) * prt::kAssetSectionEntrySize;
      const std::uint64_t off = rd64(b, e + L::kEntryOffset), size = rd64(b, e + L::kEntrySize);
      if (off <= b.size() && size <= b.size() - off) {
        wr32(b, e + L::kEntryCrc, prt::crc32c({b.data() + off, static_cast<std::size_t>(size)}));
      }
    }
    wr32(b, L::kTableCrc,
         prt::crc32c({b.data() + prt::kAssetHeaderSize, static_cast<std::size_t>(tableEnd) - prt::kAssetHeaderSize}));
  }
  wr32(b, L::kHeaderCrc, prt::crc32c({b.data(), L::kHeaderCrc}));
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameLighting(const prt::LightingInfo& a, const prt::LightingInfo& b) {
  return a.model == b.model && std::memcmp(&a.center, &b.center, sizeof a.center) == 0 &&
         std::memcmp(&a.radius, &b.radius, sizeof a.radius) == 0;
}

bool sameAtlases(const prt::BakedAsset& a, const prt::BakedAsset& b) {
  if (!sameBits(a.atlasUv, b.atlasUv) || a.texelCoverage != b.texelCoverage || a.texelNormals != b.texelNormals ||
      a.atlases.size() != b.atlases.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.atlases.size(); ++i) {
    const prt::TextureAtlas &x = a.atlases[i], &y = b.atlases[i];
    if (x.width != y.width || x.height != y.height || x.firstTriangle != y.firstTriangle || x.triangleCount != y.triangleCount) {
      return false;
    }
  }
  return true;
}

bool sameAsset(const prt::BakedAsset& a, const prt::BakedAsset& b) {
  if (a.shOrder != b.shOrder || !sameBits(a.positions, b.positions) || !sameBits(a.normals, b.normals) ||
      !sameBits(a.albedo, b.albedo) || a.indices != b.indices || a.passes.size() != b.passes.size() ||
      a.samples != b.samples || a.seed != b.seed || a.sampling != b.sampling || a.name != b.name ||
      !sameLighting(a.lighting, b.lighting)) {
    return false;
  }
  for (std::size_t i = 0; i < a.passes.size(); ++i) {
    const prt::TransferPass &p = a.passes[i], &q = b.passes[i];
    if (p.kind != q.kind || p.channels != q.channels || p.bounces != q.bounces || p.form != q.form ||
        p.domain != q.domain || p.order != q.order || !sameBits(p.coeffs, q.coeffs) || p.encoded != q.encoded) {
      return false;
    }
  }
  if (a.specular.size() != b.specular.size() || !sameAtlases(a, b)) return false;
  return a.specular.empty() || std::memcmp(a.specular.data(), b.specular.data(), a.specular.size() * sizeof(prt::SpecularMaterial)) == 0;
}

// A glossy asset from the input: [order][flags][vertices][values...]; the rest are edits.
std::size_t glossyFromInput(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>* file) {
  if (size < 3) return 0;
  prt::BakedAsset a;
  a.shOrder = 1 + data[0] % 3;
  const std::uint8_t flags = data[1];
  const std::size_t V = 1 + data[2] % 6;
  std::size_t used = 3;
  auto next = [&]() { return used < size ? data[used++] : static_cast<std::uint8_t>(used++ * 29); };
  for (std::size_t v = 0; v < V; ++v) {
    a.positions.push_back({static_cast<float>(v), 0.0f, 1.0f});
    a.normals.push_back({0.0f, 0.0f, 1.0f});
    a.albedo.push_back({0.5f, 0.5f, 0.5f});
    a.specular.push_back({{next() / 255.0f, next() / 255.0f, next() / 255.0f}, static_cast<float>(next())});
  }
  a.indices = {0, 0, 0};
  if (flags & 1) a.lighting = {prt::LightingModel::kLocalSphere, {0.0f, 0.0f, 0.0f}, 3.0f};
  prt::TransferPass m;
  m.kind = (flags & 2) ? prt::TransferKind::kInterreflected : prt::TransferKind::kShadowed;
  m.channels = (flags & 2) ? 3 : 1;
  m.bounces = (flags & 2) ? 1 : 0;
  m.form = prt::TransferForm::kMatrix;
  const prt::MatrixPacking packing = prt::matrixPackingFor(m.kind, a.lighting.model);
  m.coeffs.resize(V * static_cast<std::size_t>(m.channels) * prt::matrixEntryCount(a.shOrder, packing));
  for (float& x : m.coeffs) x = static_cast<float>(static_cast<int>(next()) - 128) / 32.0f;
  if (flags & 4) {
    static const char* const kSettings[] = {"f32", "f16", "q8", "cpca8@0.1", "cpca16@0.01"};
    prt::TransferCodecSettings s;
    if (!prt::parseTransferSetting(kSettings[(flags >> 3) % 5], {}, &s).isOk()) return 0;
    s.cpcaMaxClusters = 3;
    if (!prt::encodeTransferMatrix(m.coeffs, a.shOrder, packing, m.channels, s, &m.encoded).isOk()) return 0;
  }
  a.passes.push_back(std::move(m));
  if (!prt::encodeAsset(a, file).isOk()) return 0;
  return std::min(used, size);
}

// An asset with transfer textures from the input: [order][flags][triangles][atlas sizes...]
// [values...]; the rest are edits. One or two atlases of up to 8 x 8 texels over 1 to 4
// triangles, a texel pass (kind and encoding from the flags), a vertex pass when flags & 1,
// and, per one more input byte, a visibility pass of order 2 to 5, float32 or encoded, and per
// another texel normals.
std::size_t texelFromInput(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>* file) {
  if (size < 3) return 0;
  prt::BakedAsset a;
  a.shOrder = 1 + data[0] % 3;
  const std::uint8_t flags = data[1];
  const std::uint32_t T = 1 + data[2] % 4, V = T + 2;
  std::size_t used = 3;
  auto next = [&]() { return used < size ? data[used++] : static_cast<std::uint8_t>(used++ * 29); };
  for (std::uint32_t v = 0; v < V; ++v) {
    a.positions.push_back({static_cast<float>(v), static_cast<float>(v % 2), 0.0f});
    a.normals.push_back({0.0f, 0.0f, 1.0f});
    a.albedo.push_back({0.5f, 0.5f, 0.5f});
    a.atlasUv.push_back(next() / 255.0f);
    a.atlasUv.push_back(next() / 255.0f);
  }
  for (std::uint32_t t = 0; t < T; ++t) a.indices.insert(a.indices.end(), {t, t + 1, t + 2});
  const std::uint32_t split = (flags & 8) && T > 1 ? 1 + next() % (T - 1) : T;
  a.atlases.push_back({1u + next() % 8u, 1u + next() % 8u, 0, split});
  if (split < T) a.atlases.push_back({1u + next() % 8u, 1u + next() % 8u, split, T - split});
  for (std::uint64_t i = 0; i < prt::assetTexelCount(a); ++i) a.texelCoverage.push_back(next() % 3);
  const std::size_t n = static_cast<std::size_t>(a.shOrder * a.shOrder);
  auto pass = [&](prt::TransferKind kind, std::size_t rows, prt::TransferDomain domain) {
    prt::TransferPass p;
    p.kind = kind;
    p.channels = kind == prt::TransferKind::kInterreflected ? 3 : 1;
    p.bounces = kind == prt::TransferKind::kInterreflected ? 1 : 0;
    p.domain = domain;
    p.coeffs.resize(rows * static_cast<std::size_t>(p.channels) * n);
    for (float& x : p.coeffs) x = static_cast<float>(static_cast<int>(next()) - 128) / 32.0f;
    return p;
  };
  if (flags & 1) a.passes.push_back(pass(prt::TransferKind::kShadowed, V, prt::TransferDomain::kVertex));
  prt::TransferPass texel = pass((flags & 2) ? prt::TransferKind::kInterreflected : prt::TransferKind::kShadowed,
                                 static_cast<std::size_t>(prt::assetTexelCount(a)), prt::TransferDomain::kTexel);
  if (flags & 4) {
    static const char* const kSettings[] = {"f32", "f16", "q8", "cpca8@0.1", "cpca16@0.01"};
    prt::TransferCodecSettings s;
    if (!prt::parseTransferSetting(kSettings[(flags >> 4) % 5], {}, &s).isOk()) return 0;
    s.cpcaMaxClusters = 3;
    if (!prt::encodeTransfer(texel.coeffs, a.shOrder, texel.channels, s, &texel.encoded).isOk()) return 0;
  }
  a.passes.push_back(std::move(texel));
  if (const std::uint8_t visibility = next(); visibility & 1) {
    prt::TransferPass v;
    v.kind = prt::TransferKind::kShadowed;
    v.form = prt::TransferForm::kVisibility;
    v.domain = prt::TransferDomain::kTexel;
    v.order = 2 + (visibility >> 2) % 4;
    v.coeffs.resize(static_cast<std::size_t>(prt::assetTexelCount(a)) * static_cast<std::size_t>(v.order * v.order));
    for (float& x : v.coeffs) x = static_cast<float>(static_cast<int>(next()) - 128) / 32.0f;
    if (visibility & 2) {
      static const char* const kSettings[] = {"f16", "q8", "cpca8@0.1"};
      prt::TransferCodecSettings s;
      if (!prt::parseTransferSetting(kSettings[(visibility >> 4) % 3], {}, &s).isOk()) return 0;
      s.cpcaMaxClusters = 3;
      if (!prt::encodeTransfer(v.coeffs, v.order, 1, s, &v.encoded).isOk()) return 0;
    }
    a.passes.push_back(std::move(v));
    for (std::uint32_t i = 0; i < V; ++i) a.specular.push_back({{next() / 255.0f, 0.04f, 1.0f}, static_cast<float>(next()), next() / 255.0f});
  }
  if (next() & 1) {  // texel normals (format 1.6): any code but -32768, (0, 0) at empty texels
    for (std::uint8_t coverage : a.texelCoverage) {
      for (int k = 0; k < 2; ++k) {
        const auto code = static_cast<std::int16_t>(static_cast<std::uint16_t>(next() << 8 | next()));
        a.texelNormals.push_back(coverage == 0 ? 0 : std::max<std::int16_t>(code, -32767));
      }
    }
  }
  if (!prt::encodeAsset(a, file).isOk()) return 0;
  return std::min(used, size);
}

void check(bool condition) {
  if (!condition) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::vector<std::uint8_t> bytes;
  if (data[0] & 6u) {
    const std::size_t used = (data[0] & 2u) ? glossyFromInput(data + 1, size - 1, &bytes) : texelFromInput(data + 1, size - 1, &bytes);
    if (used == 0) return 0;
    for (std::size_t i = 1 + used; i + 2 < size && !bytes.empty(); i += 3) {
      const std::size_t at = (static_cast<std::size_t>(data[i]) | static_cast<std::size_t>(data[i + 1]) << 8) % bytes.size();
      bytes[at] ^= data[i + 2];
    }
  } else {
    bytes.assign(data + 1, data + size);
  }
  if (data[0] & 1u) reseal(bytes);

  prt::BakedAsset asset;
  const prt::Status decoded = prt::decodeAsset(bytes, &asset);
  prt::AssetSummary verified;
  const prt::Status verifiedStatus = prt::verifyAsset(bytes, &verified);
  check(decoded.code() == verifiedStatus.code());
  prt::AssetSummary peeked;
  const prt::Status peekedStatus = prt::peekAssetHeader(bytes, &peeked);
  if (!decoded.isOk()) {
    check(!decoded.message().empty());
    return 0;
  }
  check(peekedStatus.isOk());
  check(peeked.shOrder == verified.shOrder && peeked.vertexCount == verified.vertexCount &&
        peeked.triangleCount == verified.triangleCount && peeked.passes.size() == verified.passes.size() &&
        peeked.name == verified.name && peeked.fileSize == bytes.size() &&
        sameLighting(peeked.lighting, verified.lighting) && sameLighting(asset.lighting, verified.lighting));
  check(asset.positions.size() == verified.vertexCount && asset.indices.size() == 3u * verified.triangleCount);

  for (std::size_t i = 0; i < verified.passes.size(); ++i) {
    check(peeked.passes[i].form == verified.passes[i].form && asset.passes[i].form == verified.passes[i].form);
    check(peeked.passes[i].domain == verified.passes[i].domain && asset.passes[i].domain == verified.passes[i].domain);
    check(peeked.passes[i].order == verified.passes[i].order && asset.passes[i].order == verified.passes[i].order);
    prt::TransferPass pass;
    int bands = 0;
    check(prt::decodeAssetPass(bytes, static_cast<int>(i), 0, &pass, &bands).isOk());
    // A visibility pass's bands are its own order; every other pass has the asset's.
    const int order = asset.passes[i].form == prt::TransferForm::kVisibility ? asset.passes[i].order : asset.shOrder;
    check(bands == order && pass.order == asset.passes[i].order && sameBits(pass.coeffs, asset.passes[i].coeffs));
  }
  std::vector<prt::SpecularMaterial> specular;
  check(prt::decodeAssetSpecular(bytes, &specular).isOk() && specular.size() == asset.specular.size());
  prt::BakedAsset atlases;
  check(prt::decodeAssetAtlases(bytes, &atlases).isOk() && sameAtlases(atlases, asset));
  check(peeked.texelCount == prt::assetTexelCount(asset) && verified.texelCount == peeked.texelCount);

  std::vector<std::uint8_t> again;
  check(prt::encodeAsset(asset, &again).isOk());
  prt::BakedAsset back;
  check(prt::decodeAsset(again, &back).isOk());
  check(sameAsset(asset, back));
  return 0;
}
