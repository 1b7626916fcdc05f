// Container writer and reader (docs/transfer-codec.md, "Container" and "What the decoder
// checks"). Reading order follows the asset reader's: magic and version first, then the
// header checksum before any header field is trusted, the table checksum before any entry
// is, and all offset arithmetic in 64 bits after comparisons that rule out overflow.
#include "transfer_codec_container.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "prt/checksum.h"
#include "prt/sh_basis.h"
#include "transfer_codec_streams.h"

namespace prt::transfer_codec {

int valueBytes(TransferEncoding encoding) {
  switch (encoding) {
    case TransferEncoding::kFloat32: return 4;
    case TransferEncoding::kFloat16:
    case TransferEncoding::kQuant16: return 2;
    case TransferEncoding::kQuant8: return 1;
    case TransferEncoding::kCpca: return 0;
  }
  return 0;
}

int quantLevels(int bits) { return (1 << (bits - 1)) - 1; }

int clusterIdBytes(std::uint32_t clusters) { return clusters <= 256 ? 1 : 2; }

std::uint64_t bandPartBytes(TransferEncoding encoding, int channels, int band, std::uint64_t vertices) {
  const std::uint64_t streams = static_cast<std::uint64_t>(channels) * static_cast<std::uint64_t>(2 * band + 1);
  const bool quantised = encoding == TransferEncoding::kQuant16 || encoding == TransferEncoding::kQuant8;
  return (quantised ? 4 * streams : 0) + streamGroupBytes(streams, vertices, valueBytes(encoding));
}

std::uint64_t clusterPartBytes(std::uint32_t clusters, std::uint64_t vertices) {
  return streamGroupBytes(1, vertices, clusterIdBytes(clusters));
}

std::uint64_t cpcaBandPartBytes(std::uint32_t clusters, int dims, int vectors, std::uint64_t vertices,
                                int weightBytes) {
  const std::uint64_t k = clusters, d = static_cast<std::uint64_t>(dims), n = static_cast<std::uint64_t>(vectors);
  return 4 + 4 * k + 4 * k * d + 2 * k * n * d + streamGroupBytes(n, vertices, weightBytes);
}

std::uint64_t shellEntries(int band, MatrixPacking packing) {
  return matrixEntryCount(band + 1, packing) - matrixEntryCount(band, packing);
}

std::uint64_t matrixShellPartBytes(TransferEncoding encoding, int channels, int band, MatrixPacking packing,
                                   std::uint64_t vertices) {
  const std::uint64_t streams = static_cast<std::uint64_t>(channels) * shellEntries(band, packing);
  const bool quantised = encoding == TransferEncoding::kQuant16 || encoding == TransferEncoding::kQuant8;
  return (quantised ? 4 * streams : 0) + streamGroupBytes(streams, vertices, valueBytes(encoding));
}

std::uint64_t matrixWeightsPartBytes(std::uint32_t clusters, int vectors, std::uint64_t vertices, int weightBytes) {
  return 4 * std::uint64_t{clusters} + streamGroupBytes(static_cast<std::uint64_t>(vectors), vertices, weightBytes);
}

std::uint64_t matrixCpcaShellPartBytes(std::uint32_t clusters, int vectors, int channels, int band, MatrixPacking packing,
                                       int basisBits) {
  const std::uint64_t perMatrix = static_cast<std::uint64_t>(channels) * shellEntries(band, packing);
  const std::uint64_t k = clusters, n = static_cast<std::uint64_t>(vectors);
  if (basisBits == 8) return k * perMatrix * (4 + n) + 4 * k * n;
  return k * perMatrix * (4 + 2 * n);
}

void assembleBlob(const BlobHeader& h, std::span<const PartPayload> parts, std::vector<std::uint8_t>* out) {
  const std::size_t tableEnd = kHeaderBytes + kPartEntryBytes * parts.size();
  std::size_t total = tableEnd;
  for (const PartPayload& p : parts) total += p.bytes.size();

  std::vector<std::uint8_t> blob;
  blob.reserve(total);
  for (std::uint8_t m : kMagic) putU8(blob, m);
  putU16(blob, kTransferCodecVersionMajor);
  // Each blob takes the lowest version that holds it, so older blobs stay byte for byte:
  // vector blobs 1.0, matrix blobs 1.1, 8-bit matrix CPCA basis entries 1.2.
  const bool basis8 = h.matrix && h.encoding == TransferEncoding::kCpca && h.basisBits == 8;
  putU16(blob, basis8 ? std::uint16_t{2} : h.matrix ? std::uint16_t{1} : std::uint16_t{0});
  putU8(blob, static_cast<std::uint8_t>(h.encoding));
  putU8(blob, static_cast<std::uint8_t>(h.weightBits));
  putU8(blob, static_cast<std::uint8_t>(h.order));
  putU8(blob, static_cast<std::uint8_t>(h.channels));
  putU32(blob, h.vertexCount);
  putU32(blob, h.clusterCount);
  putU32(blob, static_cast<std::uint32_t>(parts.size()));
  putU64(blob, total);
  putU32(blob, 0);  // table CRC, below
  putU8(blob, h.matrix ? 1 : 0);
  putU8(blob, h.matrix ? static_cast<std::uint8_t>(h.packing) : 0);
  putU16(blob, static_cast<std::uint16_t>(h.vectors));
  putU8(blob, basis8 ? 8 : 0);
  for (int i = 0; i < 3; ++i) putU8(blob, 0);  // reserved
  putU32(blob, 0);  // header CRC, below

  std::uint64_t offset = tableEnd;
  for (const PartPayload& p : parts) {
    putU16(blob, static_cast<std::uint16_t>(p.type));
    putU16(blob, static_cast<std::uint16_t>(p.band));
    putU32(blob, crc32c(p.bytes));
    putU64(blob, offset);
    putU64(blob, p.bytes.size());
    offset += p.bytes.size();
  }
  const std::uint32_t tableCrc = crc32c({blob.data() + kHeaderBytes, tableEnd - kHeaderBytes});
  for (int i = 0; i < 4; ++i) blob[layout::kTableCrc + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(tableCrc >> (8 * i));
  const std::uint32_t headerCrc = crc32c({blob.data(), layout::kHeaderCrc});
  for (int i = 0; i < 4; ++i) blob[layout::kHeaderCrc + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(headerCrc >> (8 * i));
  // Sized once, then copied: cheaper than growing, and it keeps GCC 12's -Wstringop-overflow quiet.
  std::size_t at = blob.size();
  blob.resize(total);
  for (const PartPayload& p : parts) {
    if (!p.bytes.empty()) std::memcpy(blob.data() + at, p.bytes.data(), p.bytes.size());
    at += p.bytes.size();
  }
  *out = std::move(blob);
}

namespace {

std::string num(std::uint64_t v) { return std::to_string(v); }

Status corrupt(std::string message) { return Status::error(StatusCode::kCorrupt, std::move(message)); }

std::string partLabel(std::size_t index, const TransferPartInfo& p) {
  return "part " + num(index) + (p.type == TransferPartType::kClusters ? " (clusters)"
                                 : p.type == TransferPartType::kWeights ? " (weights)"
                                                                        : " (band " + num(static_cast<std::uint64_t>(p.band)) + ")");
}

// Magic, version, checksum and fields of the 48-byte header.
Status readHeader(std::span<const std::uint8_t> bytes, TransferBlobInfo* info, std::uint32_t* partCount) {
  const std::uint8_t* b = bytes.data();
  const std::size_t magicBytes = std::min<std::size_t>(bytes.size(), 4);
  if (magicBytes > 0 && std::memcmp(b, kMagic, magicBytes) != 0) {
    return Status::error(StatusCode::kBadMagic, "not a transfer blob: it does not start with \"PRTT\"");
  }
  if (bytes.size() < 8) {
    return Status::error(StatusCode::kTruncated,
                         "transfer blob is " + num(bytes.size()) + " bytes, shorter than its " + num(kHeaderBytes) + "-byte header");
  }
  info->versionMajor = readLe16(b + layout::kVersionMajor);
  info->versionMinor = readLe16(b + layout::kVersionMinor);
  // Before the checksum: another major version may lay out its header differently.
  if (info->versionMajor != kTransferCodecVersionMajor) {
    return Status::error(StatusCode::kBadVersion,
                         "transfer codec version " + num(info->versionMajor) + "." + num(info->versionMinor) +
                             (info->versionMajor > kTransferCodecVersionMajor ? " is newer than" : " is not readable by") +
                             " this reader's " + num(kTransferCodecVersionMajor) + "." + num(kTransferCodecVersionMinor));
  }
  if (bytes.size() < kHeaderBytes) {
    return Status::error(StatusCode::kTruncated,
                         "transfer blob is " + num(bytes.size()) + " bytes, shorter than its " + num(kHeaderBytes) + "-byte header");
  }
  const std::uint32_t storedCrc = readLe32(b + layout::kHeaderCrc);
  const std::uint32_t crc = crc32c({b, layout::kHeaderCrc});
  if (storedCrc != crc) return Status::error(StatusCode::kChecksumMismatch, "transfer blob header checksum mismatch");

  const int encoding = b[layout::kEncoding];
  if (encoding < 1 || encoding > 5) return corrupt("unknown encoding " + num(static_cast<std::uint64_t>(encoding)));
  info->encoding = static_cast<TransferEncoding>(encoding);
  const bool cpca = info->encoding == TransferEncoding::kCpca;
  info->weightBits = b[layout::kWeightBits];
  if (cpca ? (info->weightBits != 8 && info->weightBits != 16) : info->weightBits != 0) {
    return corrupt("weight bits " + num(static_cast<std::uint64_t>(info->weightBits)) + " (expected " + (cpca ? "8 or 16" : "0") +
                   " for " + transferEncodingName(info->encoding) + ")");
  }
  // In 1.0 bytes 36..43 were all reserved; 1.1 gave 36..39 a meaning.
  if (info->versionMinor < 1) {
    for (std::size_t i = layout::kLayout; i < layout::kReserved; ++i) {
      if (b[i] != 0) return corrupt("reserved header byte " + num(i) + " is not zero (version 1.0)");
    }
  }
  const std::uint8_t layoutByte = b[layout::kLayout], packingByte = b[layout::kPacking];
  const std::uint16_t vectors = readLe16(b + layout::kVectors);
  if (layoutByte > 1 || (layoutByte == 1 && info->versionMinor < 1)) {
    return corrupt("layout " + num(layoutByte) + " (expected 0 for vector transfer, or 1 for matrix transfer since version 1.1)");
  }
  info->matrix = layoutByte == 1;
  if (info->matrix ? (packingByte != static_cast<std::uint8_t>(MatrixPacking::kSymmetric) &&
                      packingByte != static_cast<std::uint8_t>(MatrixPacking::kFull))
                   : packingByte != 0) {
    return corrupt("matrix packing " + num(packingByte) + (info->matrix ? " (expected 1 symmetric or 2 full)" : " (expected 0 for vector transfer)"));
  }
  info->packing = info->matrix ? static_cast<MatrixPacking>(packingByte) : MatrixPacking{};
  info->order = b[layout::kOrder];
  const int maxOrder = info->matrix ? kMaxMatrixOrder : kMaxShOrder;
  if (info->order < kMinShOrder || info->order > maxOrder) {
    return corrupt("order " + num(static_cast<std::uint64_t>(info->order)) + " is outside 1.." + num(static_cast<std::uint64_t>(maxOrder)) +
                   (info->matrix ? " for matrix transfer" : ""));
  }
  info->channels = b[layout::kChannels];
  if (info->channels != 1 && info->channels != 3) {
    return corrupt("channels " + num(static_cast<std::uint64_t>(info->channels)) + " (expected 1 or 3)");
  }
  info->vertexCount = readLe32(b + layout::kVertexCount);
  if (info->vertexCount < 1 || info->vertexCount > kMaxTransferVertices) {
    return corrupt("vertex count " + num(info->vertexCount) + " is outside 1.." + num(kMaxTransferVertices));
  }
  info->clusterCount = readLe32(b + layout::kClusterCount);
  if (cpca) {
    const std::uint32_t maxClusters = std::min(info->vertexCount, kMaxTransferClusters);
    if (info->clusterCount < 1 || info->clusterCount > maxClusters) {
      return corrupt("cluster count " + num(info->clusterCount) + " is outside 1.." + num(maxClusters));
    }
  } else if (info->clusterCount != 0) {
    return corrupt("cluster count " + num(info->clusterCount) + " (expected 0 for " + transferEncodingName(info->encoding) + ")");
  }
  const std::uint64_t dims = info->matrix ? static_cast<std::uint64_t>(info->channels) * matrixEntryCount(info->order, info->packing) : 0;
  if (info->matrix && cpca ? vectors > dims : vectors != 0) {
    return corrupt("vector count " + num(vectors) + (info->matrix && cpca ? " exceeds the matrix's " + num(dims) + " values"
                                                                          : " (expected 0 unless matrix CPCA)"));
  }
  info->vectors = vectors;
  // Byte 40 (since 1.2): 8-bit basis entries of matrix CPCA; 0 is binary16 (1.1's format).
  const std::uint8_t basisByte = b[layout::kBasisBits];
  if (basisByte != 0 && (basisByte != 8 || !info->matrix || !cpca || info->versionMinor < 2)) {
    return corrupt("basis bits " + num(basisByte) + " (expected 0, or 8 for matrix CPCA since version 1.2)");
  }
  info->basisBits = info->matrix && cpca ? (basisByte == 8 ? 8 : 16) : 0;
  *partCount = readLe32(b + layout::kPartCount);
  const std::uint32_t expectedParts = static_cast<std::uint32_t>(info->order) + (cpca ? (info->matrix ? 2u : 1u) : 0u);
  if (*partCount != expectedParts) {
    return corrupt("part count " + num(*partCount) + " (expected " + num(expectedParts) + " for order " +
                   num(static_cast<std::uint64_t>(info->order)) +
                   (cpca ? (info->matrix ? " with clusters and weights)" : " with clusters)") : ")"));
  }
  for (std::size_t i = layout::kReserved; i < layout::kHeaderCrc; ++i) {
    if (b[i] != 0) return corrupt("reserved header byte " + num(i) + " is not zero");
  }
  info->blobSize = readLe64(b + layout::kBlobSize);
  const std::uint64_t tableEnd = kHeaderBytes + kPartEntryBytes * std::uint64_t{*partCount};
  if (info->blobSize < tableEnd) {
    return corrupt("blob size " + num(info->blobSize) + " is smaller than header and part table (" + num(tableEnd) + ")");
  }
  return Status::ok();
}

}  // namespace
}  // namespace prt::transfer_codec

namespace prt {

using namespace transfer_codec;  // NOLINT: this file is the codec's own

Status readTransferBlobInfo(std::span<const std::uint8_t> bytes, TransferBlobInfo* out) {
  TransferBlobInfo info;
  std::uint32_t partCount = 0;
  if (Status s = readHeader(bytes, &info, &partCount); !s.isOk()) return s;
  const std::uint8_t* b = bytes.data();
  const std::uint64_t tableEnd = kHeaderBytes + kPartEntryBytes * std::uint64_t{partCount};
  if (bytes.size() < tableEnd) {
    return Status::error(StatusCode::kTruncated, "transfer blob is " + num(bytes.size()) +
                                                     " bytes, shorter than its header and part table (" + num(tableEnd) + ")");
  }
  if (bytes.size() > info.blobSize) {
    return corrupt("transfer blob is " + num(bytes.size()) + " bytes, longer than its declared size " + num(info.blobSize));
  }
  const std::size_t tableBytes = static_cast<std::size_t>(tableEnd) - kHeaderBytes;
  if (readLe32(b + layout::kTableCrc) != crc32c({b + kHeaderBytes, tableBytes})) {
    return Status::error(StatusCode::kChecksumMismatch, "transfer blob part table checksum mismatch");
  }

  const bool cpca = info.encoding == TransferEncoding::kCpca;
  std::uint64_t expectedOffset = tableEnd;
  info.parts.resize(partCount);
  for (std::uint32_t i = 0; i < partCount; ++i) {
    const std::uint8_t* e = b + kHeaderBytes + kPartEntryBytes * i;
    TransferPartInfo& p = info.parts[i];
    const std::uint16_t type = readLe16(e + layout::kPartType), band = readLe16(e + layout::kPartBand);
    const bool clusters = cpca && i == 0;
    const bool weights = cpca && info.matrix && i == 1;
    const std::uint32_t leading = cpca ? (info.matrix ? 2u : 1u) : 0u;
    const std::uint16_t wantType = static_cast<std::uint16_t>(clusters  ? TransferPartType::kClusters
                                                              : weights ? TransferPartType::kWeights
                                                                        : TransferPartType::kBand);
    const std::uint32_t wantBand = clusters || weights ? 0u : i - leading;
    if (type != wantType || band != wantBand) {
      return corrupt("part " + num(i) + " is type " + num(type) + " band " + num(band) + ", expected " +
                     (clusters  ? std::string("the clusters part (type 1, band 0)")
                      : weights ? std::string("the weights part (type 3, band 0)")
                                : "band " + num(wantBand) + " (type 2)"));
    }
    p.type = static_cast<TransferPartType>(type);
    p.band = band;
    p.crc = readLe32(e + layout::kPartCrc);
    p.offset = readLe64(e + layout::kPartOffset);
    p.size = readLe64(e + layout::kPartSize);
    if (p.offset != expectedOffset) {
      return corrupt(partLabel(i, p) + " starts at " + num(p.offset) + ", expected " + num(expectedOffset) +
                     " (parts follow the table back to back)");
    }
    if (p.size > info.blobSize - p.offset) {
      return corrupt(partLabel(i, p) + " (" + num(p.size) + " bytes at " + num(p.offset) + ") runs past the blob size " +
                     num(info.blobSize));
    }
    std::uint64_t want = 0;
    bool fixed = true;
    if (clusters) {
      want = clusterPartBytes(info.clusterCount, info.vertexCount);
    } else if (weights) {
      want = matrixWeightsPartBytes(info.clusterCount, info.vectors, info.vertexCount, info.weightBits / 8);
    } else if (info.matrix) {
      want = cpca ? matrixCpcaShellPartBytes(info.clusterCount, info.vectors, info.channels, p.band, info.packing, info.basisBits)
                  : matrixShellPartBytes(info.encoding, info.channels, p.band, info.packing, info.vertexCount);
    } else if (!cpca) {
      want = bandPartBytes(info.encoding, info.channels, p.band, info.vertexCount);
    } else {
      fixed = false;  // depends on the vector count stored in the part
    }
    if (fixed && p.size != want) {
      return corrupt(partLabel(i, p) + " is " + num(p.size) + " bytes, expected " + num(want));
    }
    expectedOffset = p.offset + p.size;
  }
  if (expectedOffset != info.blobSize) {
    return corrupt("parts end at " + num(expectedOffset) + ", not at the blob size " + num(info.blobSize));
  }
  // Leading bands whose parts (and the clusters part) lie inside `bytes`.
  info.bandsAvailable = 0;
  for (const TransferPartInfo& p : info.parts) {
    if (p.offset + p.size > bytes.size()) break;
    if (p.type == TransferPartType::kBand) ++info.bandsAvailable;
  }
  *out = std::move(info);
  return Status::ok();
}

}  // namespace prt
