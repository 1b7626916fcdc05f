// CRC-32C (Castagnoli), the checksum of the asset format (docs/asset-format.md).
// Chosen over a 64-bit hash because it is standardised (iSCSI, ext4, Btrfs), so an
// independent reader in any language finds a reference implementation, and because a CRC
// provably detects every error burst up to 32 bits: any single corrupted byte is caught,
// not just caught with high probability.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace prt {

// CRC-32C of `bytes` (reflected polynomial 0x82F63B78, initial value and final xor
// 0xFFFFFFFF; crc32c of "123456789" is 0xE3069283). Pass the previous result as `crc` to
// continue over data split into pieces: crc32c(b, crc32c(a)) == crc32c(a ++ b).
// Uses the CPU's crc32 instruction where there is one (x86-64 with SSE4.2), else the tables.
std::uint32_t crc32c(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0) noexcept;

// The CRC-32C of a ++ b from crc32c(a), crc32c(b) and b's length, without the bytes (zlib's
// crc32_combine for this polynomial): pieces checksummed separately, in parallel or as they
// are read, give the checksum of the whole. O(log bBytes).
std::uint32_t crc32cCombine(std::uint32_t crcA, std::uint32_t crcB, std::uint64_t bBytes) noexcept;

// The same by the slicing-by-8 tables alone, on any host: the reference the fast path is
// tested against.
std::uint32_t crc32cTables(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0) noexcept;

}  // namespace prt
