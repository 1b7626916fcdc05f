// Making a resource's precompressed variants from its bytes.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "resource.h"

namespace prt::serve {

enum class VariantStorage { kTempFile, kMemory };

// Compresses `bytes` with br, zstd and gzip and returns the variants that are at least
// 5% smaller than the original (a smaller saving is not worth a decompression), ETags
// `baseTag` + "." + the encoding's tag, stored as `storage` says. An encoder or temp-file
// failure drops that variant and leaves its message in *problems (the identity always works).
std::vector<Variant> makeEncodedVariants(std::span<const std::uint8_t> bytes, const std::string& baseTag,
                                         VariantStorage storage, std::string* problems);

// The quoted strong ETag "\"<tag>\"" or, for an encoding, "\"<tag>.<enc>\"".
std::string etagFor(const std::string& baseTag, Encoding encoding);

}  // namespace prt::serve
