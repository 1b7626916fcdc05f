#include "content_hash.h"

// The shared library rather than XXH_INLINE_ALL: one copy of the algorithm, updated with
// the system, and one call per buffer costs nothing next to hashing it.
#include <xxhash.h>

namespace prt::serve {

std::uint64_t xxh64(std::span<const std::uint8_t> bytes, std::uint64_t seed) noexcept {
  // XXH64 accepts a null pointer for a zero length, which an empty span may hold.
  return static_cast<std::uint64_t>(XXH64(bytes.data(), bytes.size(), static_cast<XXH64_hash_t>(seed)));
}

std::string hashHex(std::uint64_t hash) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i) {
    out[static_cast<std::size_t>(i)] = kDigits[hash & 0xf];
    hash >>= 4;
  }
  return out;
}

}  // namespace prt::serve
