// The content codings the server offers (RFC 9110 §8.4.1) and one-shot encoders for them.
// Variants are made once per file version (at scan time or on a static file's first
// request) and then sent as they are, so the levels favour size over speed, within reason.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "prt/status.h"

namespace prt::serve {

enum class Encoding { kIdentity, kGzip, kZstd, kBrotli };

// The Accept-Encoding / Content-Encoding token: "identity", "gzip", "zstd", "br".
const char* encodingToken(Encoding encoding);

// Short suffix that tells the variants' ETags apart: "", "gz", "zst", "br".
const char* encodingTag(Encoding encoding);

// Compresses `bytes` into *out (replaced). kInvalidArgument for kIdentity or on an
// encoder failure (out of memory inside the library).
Status compressBytes(Encoding encoding, std::span<const std::uint8_t> bytes, std::string* out);

}  // namespace prt::serve
