// The 64-bit content hash behind the server's content-addressed asset URLs and ETags.
// XXH64 (Yann Collet's xxHash, 64-bit variant), from Debian's libxxhash: fast (several
// GB/s, so hashing at scan time costs little next to reading the file), well distributed,
// and with implementations in every language, so a client or a CDN script can recompute a
// URL's hash. It names versions; it is not a defence against someone crafting collisions
// (assets come from the operator's disk).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace prt::serve {

// XXH64 of `bytes` with `seed` (XXH64 of no bytes with seed 0 is 0xef46db3751d8e999).
std::uint64_t xxh64(std::span<const std::uint8_t> bytes, std::uint64_t seed = 0) noexcept;

// 16 lower-case hex digits, most significant first: how hashes appear in URLs and ETags.
std::string hashHex(std::uint64_t hash);

}  // namespace prt::serve
