// The transfer codec's container (docs/transfer-codec.md, "Container"): a 48-byte header,
// a table of parts, the parts back to back. Layout constants, part-size formulas and the
// blob writer; readTransferBlobInfo (prt/transfer_codec.h) is the matching reader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/transfer_codec.h"

namespace prt::transfer_codec {

inline constexpr std::uint8_t kMagic[4] = {'P', 'R', 'T', 'T'};
inline constexpr std::size_t kHeaderBytes = 48;
inline constexpr std::size_t kPartEntryBytes = 24;

namespace layout {
inline constexpr std::size_t kMagic = 0;         // 4 bytes "PRTT"
inline constexpr std::size_t kVersionMajor = 4;  // u16
inline constexpr std::size_t kVersionMinor = 6;  // u16
inline constexpr std::size_t kEncoding = 8;      // u8 TransferEncoding
inline constexpr std::size_t kWeightBits = 9;    // u8: CPCA 8 or 16, else 0
inline constexpr std::size_t kOrder = 10;        // u8, 1..16
inline constexpr std::size_t kChannels = 11;     // u8, 1 or 3
inline constexpr std::size_t kVertexCount = 12;  // u32
inline constexpr std::size_t kClusterCount = 16; // u32: CPCA 1..min(V, 65536), else 0
inline constexpr std::size_t kPartCount = 20;    // u32: order (+1 for CPCA, +2 for matrix CPCA)
inline constexpr std::size_t kBlobSize = 24;     // u64
inline constexpr std::size_t kTableCrc = 32;     // u32, CRC-32C of the part table
inline constexpr std::size_t kLayout = 36;       // u8 (since 1.1): 0 vector transfer, 1 matrix transfer
inline constexpr std::size_t kPacking = 37;      // u8 (since 1.1): matrix MatrixPacking (1 symmetric, 2 full), else 0
inline constexpr std::size_t kVectors = 38;      // u16 (since 1.1): matrix CPCA basis matrices per cluster, else 0
inline constexpr std::size_t kBasisBits = 40;    // u8 (since 1.2): matrix CPCA 8 for 8-bit basis entries, else 0 (binary16)
inline constexpr std::size_t kReserved = 41;     // 3 bytes, zero (36..43 were all reserved in 1.0, 40..43 in 1.1)
inline constexpr std::size_t kHeaderCrc = 44;    // u32, CRC-32C of header bytes 0..43

inline constexpr std::size_t kPartType = 0;    // u16 TransferPartType
inline constexpr std::size_t kPartBand = 2;    // u16
inline constexpr std::size_t kPartCrc = 4;     // u32, CRC-32C of the payload
inline constexpr std::size_t kPartOffset = 8;  // u64, from the start of the blob
inline constexpr std::size_t kPartSize = 16;   // u64
}  // namespace layout

// Bytes per stored value of the non-CPCA encodings (4, 2, 2, 1).
int valueBytes(TransferEncoding encoding);
// Largest quantisation level Q = 2^(bits-1) - 1 of a quantised encoding or weight width.
int quantLevels(int bits);
// Bytes per cluster id: 1 up to 256 clusters, else 2.
int clusterIdBytes(std::uint32_t clusters);

// Payload size of band `band` of a non-CPCA encoding: per stream (channel, coefficient of
// the band) a step (quantised encodings only), a filter byte and `vertices` values.
std::uint64_t bandPartBytes(TransferEncoding encoding, int channels, int band, std::uint64_t vertices);
// Payload size of the CPCA cluster part.
std::uint64_t clusterPartBytes(std::uint32_t clusters, std::uint64_t vertices);
// Payload size of a CPCA band part with `vectors` principal vectors of `dims` dimensions.
std::uint64_t cpcaBandPartBytes(std::uint32_t clusters, int dims, int vectors, std::uint64_t vertices,
                                int weightBytes);

// Matrix transfer (docs/transfer-codec.md "Matrices"): entries of shell b, the packed
// entries from matrixEntryCount(b) to matrixEntryCount(b + 1).
std::uint64_t shellEntries(int band, MatrixPacking packing);
// Payload size of shell `band` of a non-CPCA matrix encoding: as a vector band with
// channels * shellEntries streams.
std::uint64_t matrixShellPartBytes(TransferEncoding encoding, int channels, int band, MatrixPacking packing,
                                   std::uint64_t vertices);
// Payload size of the matrix CPCA weights part: a step per cluster, `vectors` streams.
std::uint64_t matrixWeightsPartBytes(std::uint32_t clusters, int vectors, std::uint64_t vertices, int weightBytes);
// Payload size of matrix CPCA shell `band`: every cluster's mean (float32) and basis
// matrices restricted to that shell, basisBits 16: binary16 entries; 8: a float32 scale
// per (cluster, basis matrix) and int8 entries.
std::uint64_t matrixCpcaShellPartBytes(std::uint32_t clusters, int vectors, int channels, int band, MatrixPacking packing,
                                       int basisBits);

struct BlobHeader {
  TransferEncoding encoding = TransferEncoding::kFloat32;
  bool matrix = false;  // matrix layout: written as version 1.1 with packing and vectors
  MatrixPacking packing = MatrixPacking::kFull;
  int vectors = 0;
  int basisBits = 16;  // matrix CPCA: 8 is written as version 1.2 with header byte 40 = 8
  int weightBits = 0;
  int order = 0;
  int channels = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t clusterCount = 0;
};

struct PartPayload {
  TransferPartType type = TransferPartType::kBand;
  int band = 0;
  std::vector<std::uint8_t> bytes;
};

// Writes header, table and `parts` (in the order the format requires) into *out.
void assembleBlob(const BlobHeader& header, std::span<const PartPayload> parts, std::vector<std::uint8_t>* out);

}  // namespace prt::transfer_codec
