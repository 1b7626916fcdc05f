// libFuzzer entry point for the transfer codec's decoder (docs/transfer-codec.md). Built by
// tests/transfer_codec.cmake with -DPRT_FUZZ=ON under Clang, or by hand:
//   clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -ffp-contract=off -Ishared \
//     tests/fuzz/transfer_codec_fuzz.cpp shared/prt/*.cpp -o transfer_codec_fuzz
//   ./transfer_codec_fuzz -max_total_time=120 CORPUS_DIR
//
// Random bytes almost never pass a CRC, and almost never form a valid header, so the first
// input byte picks a mode:
//   bit 1 clear: the rest of the input is the blob;
//   bit 1 set:   the rest describes a transfer (setting, order, channels, vertex count, values)
//                that is encoded, and then the remaining bytes are (position, xor) edits of
//                the blob, so the fuzzer explores damage to well-formed blobs of every encoding;
//   bit 0 set:   the blob's checksums are recomputed before decoding (as the tests' reseal()
//                does), so damage reaches the content checks instead of stopping at a CRC;
//   bit 2 set:   (with bit 1) the transfer is per-vertex packed matrices (symmetric or full,
//                encodeTransferMatrix) instead of vectors; a CPCA setting then stores 8-bit
//                basis entries (version 1.2) when bit 2 of the description's channel byte is set.
//
// Beyond "no crash, no sanitizer report", it traps when results disagree: whatever
// decodes is finite; every band prefix of a decodable blob decodes to the first bands of
// the full decode; the CPCA structured decode expands to the same values; and float32 /
// float16 blobs re-encode to the same values (the encoder accepts what the decoder returns).
// Matrix blobs the same, with decodeTransferMatrix / decodeCpcaMatrixTransfer and the
// packed prefix rule; each layout's decoder refuses the other's blobs.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "prt/checksum.h"
#include "prt/transfer_codec.h"

namespace {

using Bytes = std::vector<std::uint8_t>;

// Decoded arrays above this many floats are skipped: a real client checks the header
// against its memory budget first, as this harness does.
constexpr std::uint64_t kMaxDecodedFloats = std::uint64_t{1} << 22;

void check(bool condition) {
  if (!condition) __builtin_trap();
}

std::uint32_t rd32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
std::uint64_t rd64(const Bytes& b, std::size_t at) {
  return static_cast<std::uint64_t>(rd32(b, at)) | static_cast<std::uint64_t>(rd32(b, at + 4)) << 32;
}
void wr32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Recomputes part, table and header checksums wherever they fit (layout: the document).
void reseal(Bytes& b) {
  if (b.size() < 48) return;
  const std::uint64_t parts = rd32(b, 20), tableEnd = 48 + 24 * parts;
  if (tableEnd <= b.size()) {
    for (std::uint64_t i = 0; i < parts; ++i) {
      const std::size_t e = 48 + 24 * static_cast<std::size_t>(i);
      const std::uint64_t off = rd64(b, e + 8), size = rd64(b, e + 16);
      if (off <= b.size() && size <= b.size() - off) wr32(b, e + 4, prt::crc32c({b.data() + off, static_cast<std::size_t>(size)}));
    }
    wr32(b, 32, prt::crc32c({b.data() + 48, static_cast<std::size_t>(tableEnd) - 48}));
  }
  wr32(b, 44, prt::crc32c({b.data(), 44}));
}

// Builds a blob from a description: [setting][order][channels][vertices][values...] and
// returns how many input bytes it used (0 when the description does not encode).
std::size_t encodeFromInput(const std::uint8_t* data, std::size_t size, Bytes* blob, bool matrix) {
  if (size < 4) return 0;
  static const char* const kSettings[] = {"f32", "f16", "q16", "q8", "cpca8@0.05", "cpca16@0.01", "cpca8@0.2", "cpca16@0.002"};
  prt::TransferCodecSettings s;
  if (!prt::parseTransferSetting(kSettings[data[0] % 8], {}, &s).isOk()) return 0;
  s.cpcaMaxClusters = 8;
  if (matrix && s.encoding == prt::TransferEncoding::kCpca && (data[2] & 4)) s.cpcaBasisBits = 8;
  const int order = matrix ? 1 + data[1] % 3 : 1 + data[1] % 4, channels = (data[2] & 1) ? 3 : 1;
  const prt::MatrixPacking packing = (data[2] & 2) ? prt::MatrixPacking::kFull : prt::MatrixPacking::kSymmetric;
  const std::size_t perChannel = matrix ? prt::matrixEntryCount(order, packing) : static_cast<std::size_t>(order * order);
  const std::size_t vertices = 1 + data[3] % 24, count = vertices * static_cast<std::size_t>(channels) * perChannel;
  std::size_t used = 4;
  std::vector<float> transfer(count);
  for (float& x : transfer) {
    // Small signed values from one byte each (wrapping around the input), scaled so every
    // magnitude class appears.
    const std::uint8_t b = used < size ? data[used] : static_cast<std::uint8_t>(used * 37);
    ++used;
    x = static_cast<float>(static_cast<int>(b) - 128) * (b & 1 ? 1.0f / 64.0f : 1.0f / 4096.0f);
  }
  const prt::Status st = matrix ? prt::encodeTransferMatrix(transfer, order, packing, channels, s, blob)
                                : prt::encodeTransfer(transfer, order, channels, s, blob);
  if (!st.isOk()) return 0;
  return std::min(used, size);
}

void decodeMatrixAndCheck(const Bytes& blob, const prt::TransferBlobInfo& info) {
  std::vector<float> full;
  check(prt::decodeTransfer(blob, 1, &full).code() == prt::StatusCode::kInvalidArgument);
  const std::uint64_t rows = std::uint64_t{info.vertexCount} * static_cast<std::uint64_t>(info.channels);
  const std::size_t E = prt::matrixEntryCount(info.order, info.packing);
  if (rows * E > kMaxDecodedFloats) return;
  const prt::Status fullStatus = prt::decodeTransferMatrix(blob, info.order, &full);
  if (fullStatus.isOk()) check(info.bandsAvailable == info.order);
  if (!fullStatus.isOk()) check(!fullStatus.message().empty());
  for (float x : full) check(std::isfinite(x) && std::fabs(x) <= prt::kMaxTransferMagnitude * 1.0001f);
  for (int b = 1; b <= info.order; ++b) {
    std::vector<float> part;
    const prt::Status s = prt::decodeTransferMatrix(blob, b, &part);
    if (b > info.bandsAvailable) {
      check(s.code() == prt::StatusCode::kTruncated);
      continue;
    }
    if (!s.isOk()) {
      check(!s.message().empty() && !fullStatus.isOk());
      continue;
    }
    for (float x : part) check(std::isfinite(x));
    if (!fullStatus.isOk()) continue;
    const std::size_t Eb = prt::matrixEntryCount(b, info.packing);
    for (std::size_t row = 0; row < rows; ++row) check(std::memcmp(&part[row * Eb], &full[row * E], Eb * sizeof(float)) == 0);
  }
  if (info.encoding == prt::TransferEncoding::kCpca && fullStatus.isOk()) {
    prt::CpcaMatrixTransfer cpca;
    check(prt::decodeCpcaMatrixTransfer(blob, info.order, &cpca).isOk());
    check(cpca.basisBits == info.basisBits && (info.basisBits == 8 || info.basisBits == 16));
    check(info.basisBits == 16 || info.versionMinor >= 2);
    for (float x : cpca.matrices) check(std::isfinite(x) && std::fabs(x) <= prt::kMaxTransferMagnitude * 1.0001f);
    std::vector<float> again(full.size());
    check(prt::cpcaMatrixReconstruct(cpca, again).isOk());
    check(std::memcmp(again.data(), full.data(), full.size() * sizeof(float)) == 0);
  }
  if (fullStatus.isOk() &&
      (info.encoding == prt::TransferEncoding::kFloat32 || info.encoding == prt::TransferEncoding::kFloat16)) {
    prt::TransferCodecSettings s;
    s.encoding = info.encoding;
    Bytes again;
    check(prt::encodeTransferMatrix(full, info.order, info.packing, info.channels, s, &again).isOk());
    std::vector<float> back;
    check(prt::decodeTransferMatrix(again, info.order, &back).isOk());
    check(back.size() == full.size() && std::memcmp(back.data(), full.data(), full.size() * sizeof(float)) == 0);
  }
}

void decodeAndCheck(const Bytes& blob) {
  prt::TransferBlobInfo info;
  const prt::Status infoStatus = prt::readTransferBlobInfo(blob, &info);
  std::vector<float> full;
  if (!infoStatus.isOk()) {
    check(!infoStatus.message().empty());
    const prt::Status s = prt::decodeTransfer(blob, 1, &full);
    check(!s.isOk() && s.code() == infoStatus.code());
    return;
  }
  if (info.matrix) {
    decodeMatrixAndCheck(blob, info);
    return;
  }
  check(prt::decodeTransferMatrix(blob, 1, &full).code() == prt::StatusCode::kInvalidArgument);
  const std::uint64_t perBandFloats = std::uint64_t{info.vertexCount} * static_cast<std::uint64_t>(info.channels);
  if (perBandFloats * static_cast<std::uint64_t>(info.order * info.order) > kMaxDecodedFloats) return;
  const prt::Status fullStatus = prt::decodeTransfer(blob, info.order, &full);
  if (fullStatus.isOk()) check(info.bandsAvailable == info.order);
  if (!fullStatus.isOk()) check(!fullStatus.message().empty());
  for (float x : full) check(std::isfinite(x));
  const std::size_t n2 = static_cast<std::size_t>(info.order * info.order);
  for (int b = 1; b <= info.order; ++b) {
    std::vector<float> part;
    const prt::Status s = prt::decodeTransfer(blob, b, &part);
    if (b > info.bandsAvailable) {
      check(s.code() == prt::StatusCode::kTruncated);
      continue;
    }
    if (!s.isOk()) {
      check(!s.message().empty() && !fullStatus.isOk());
      continue;
    }
    for (float x : part) check(std::isfinite(x));
    if (!fullStatus.isOk()) continue;
    const std::size_t b2 = static_cast<std::size_t>(b * b);
    for (std::size_t row = 0; row < perBandFloats; ++row) {
      check(std::memcmp(&part[row * b2], &full[row * n2], b2 * sizeof(float)) == 0);
    }
  }
  if (info.encoding == prt::TransferEncoding::kCpca && fullStatus.isOk()) {
    prt::CpcaTransfer cpca;
    check(prt::decodeCpcaTransfer(blob, info.order, &cpca).isOk());
    std::vector<float> again(full.size());
    check(prt::cpcaReconstruct(cpca, again).isOk());
    check(std::memcmp(again.data(), full.data(), full.size() * sizeof(float)) == 0);
  }
  if (fullStatus.isOk() &&
      (info.encoding == prt::TransferEncoding::kFloat32 || info.encoding == prt::TransferEncoding::kFloat16)) {
    prt::TransferCodecSettings s;
    s.encoding = info.encoding;
    Bytes again;
    check(prt::encodeTransfer(full, info.order, info.channels, s, &again).isOk());
    std::vector<float> back;
    check(prt::decodeTransfer(again, info.order, &back).isOk());
    check(back.size() == full.size() && std::memcmp(back.data(), full.data(), full.size() * sizeof(float)) == 0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  ++data;
  --size;
  Bytes blob;
  if (mode & 2u) {
    const std::size_t used = encodeFromInput(data, size, &blob, (mode & 4u) != 0);
    if (used == 0) return 0;
    // Edits: (position low, position high, xor) triples.
    for (std::size_t i = used; i + 2 < size && !blob.empty(); i += 3) {
      const std::size_t at = (static_cast<std::size_t>(data[i]) | static_cast<std::size_t>(data[i + 1]) << 8) % blob.size();
      blob[at] ^= data[i + 2];
    }
    // A last byte with its top bit set also truncates the blob to (its low bits)/128 of its size.
    if (size > used && (data[size - 1] & 0x80u)) blob.resize(blob.size() * (data[size - 1] & 0x7fu) / 128);
  } else {
    blob.assign(data, data + size);
  }
  if (mode & 1u) reseal(blob);
  decodeAndCheck(blob);
  return 0;
}
