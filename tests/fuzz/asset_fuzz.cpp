// libFuzzer entry point for the asset reader (docs/asset-format.md). Build, for example:
//   clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -Ishared -Ishared/prt/codec \
//     tests/fuzz/asset_fuzz.cpp shared/prt/*.cpp shared/prt/codec/*.cpp -o asset_fuzz
//   ./asset_fuzz -max_total_time=60 CORPUS_DIR
//
// Random bytes almost never pass a CRC, which would confine the fuzzer to the header
// checks. So the first input byte picks a mode: with bit 0 set, the rest of the input gets
// its checksums recomputed before decoding (as the tests' reseal() does), which lets the
// fuzzer reach the table, size, content and metadata checks; otherwise the bytes are
// decoded as they are.
//
// Beyond "no crash, no sanitizer report", it traps when the entry points disagree:
// decodeAsset and verifyAsset must return the same code; whatever decodes must also pass
// peekAssetHeader with the same summary, and must re-encode (the encoder accepts
// everything the decoder does) to bytes that decode to the same asset.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "prt/asset.h"
#include "prt/checksum.h"

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

bool sameAsset(const prt::BakedAsset& a, const prt::BakedAsset& b) {
  if (a.shOrder != b.shOrder || !sameBits(a.positions, b.positions) || !sameBits(a.normals, b.normals) ||
      !sameBits(a.albedo, b.albedo) || a.indices != b.indices || a.passes.size() != b.passes.size() ||
      a.samples != b.samples || a.seed != b.seed || a.sampling != b.sampling || a.name != b.name ||
      !sameLighting(a.lighting, b.lighting)) {
    return false;
  }
  for (std::size_t i = 0; i < a.passes.size(); ++i) {
    const prt::TransferPass &p = a.passes[i], &q = b.passes[i];
    if (p.kind != q.kind || p.channels != q.channels || p.bounces != q.bounces || !sameBits(p.coeffs, q.coeffs)) return false;
  }
  return true;
}

void check(bool condition) {
  if (!condition) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::vector<std::uint8_t> bytes(data + 1, data + size);
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

  std::vector<std::uint8_t> again;
  check(prt::encodeAsset(asset, &again).isOk());
  prt::BakedAsset back;
  check(prt::decodeAsset(again, &back).isOk());
  check(sameAsset(asset, back));
  return 0;
}
