// Byte-level building blocks of the transfer codec (docs/transfer-codec.md, "Streams"):
// little-endian fields, and integer streams stored the way general entropy coders like them:
// an optional delta filter, zig-zag signs, and byte planes (all most significant bytes
// first). Internal to the codec; the tests use it directly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/little_endian.h"

namespace prt::transfer_codec {

// ---- Little-endian fields ----------------------------------------------------------------

void putU8(std::vector<std::uint8_t>& out, std::uint8_t v);
void putU16(std::vector<std::uint8_t>& out, std::uint16_t v);
void putU32(std::vector<std::uint8_t>& out, std::uint32_t v);
void putU64(std::vector<std::uint8_t>& out, std::uint64_t v);
void putF32(std::vector<std::uint8_t>& out, float v);

// Readers of fields at a pointer, and floatBits/floatFromBits: prt/little_endian.h.

// ---- Integer streams ---------------------------------------------------------------------

// Filter of one stream: none, or each value minus the previous one (modulo 2^(8*width)).
enum class StreamFilter : std::uint8_t { kNone = 0, kDelta = 1 };

// Zig-zag of a `width`-byte two's-complement value held sign-extended in an int32:
// 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...; the result fits `width` bytes.
std::uint32_t zigzag(std::int32_t value, int width);
// Inverse of zigzag, sign-extended.
std::int32_t unzigzag(std::uint32_t code);
// `value` reduced modulo 2^(8*width) and sign-extended (two's-complement wrap).
std::int32_t wrapToWidth(std::int64_t value, int width);

// A group of `streams` integer streams of `count` values each, `width` (1, 2 or 4) bytes
// per value, every value already in the signed range of `width` bytes. `values` is
// [stream][index]. Layout: `streams` filter bytes, then the byte planes: for each byte
// position p from most to least significant, for each stream, `count` bytes.
// Each stream's filter is the one with the smaller order-0 entropy estimate.
void putStreamGroup(std::span<const std::int32_t> values, std::size_t streams, std::size_t count, int width,
                    std::vector<std::uint8_t>& out);

// Bytes putStreamGroup writes.
std::uint64_t streamGroupBytes(std::uint64_t streams, std::uint64_t count, int width);

// Estimated size in bytes of the group after a general entropy coder: the sum over byte
// planes of their order-0 entropy (each stream with its better filter), plus the filters.
double estimateStreamGroupBytes(std::span<const std::int32_t> values, std::size_t streams, std::size_t count,
                                int width);

// Reads stream `stream` of a group laid out by putStreamGroup at `group` (already bounds
// checked: streamGroupBytes(streams, count, width) bytes) into `out` (count values,
// sign-extended). Returns false when the stream's filter byte is not a known filter (or, a
// caller error, when out is shorter than count or width is not 1, 2 or 4).
bool getStream(const std::uint8_t* group, std::size_t streams, std::size_t count, int width, std::size_t stream,
               std::span<std::int32_t> out);

}  // namespace prt::transfer_codec
