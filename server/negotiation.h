// Parsing the request headers that choose what a response holds: Accept-Encoding,
// If-None-Match / If-Range and Range. Pure string work, no I/O.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "compression.h"

namespace prt::serve {

struct EncodingOffer {
  Encoding encoding;
  std::uint64_t size;
};

// Index into `offers` (identity first) of the representation to send: among the codings
// Accept-Encoding allows (q > 0, '*' included), the highest q, then the smallest.
// Identity when the header is absent or allows nothing we have (RFC 9110 lets a server
// send identity rather than 406); identity not named in the header ranks below every
// coding that is.
std::size_t chooseEncoding(std::string_view acceptEncoding, std::span<const EncodingOffer> offers);

// True when If-None-Match is "*" or lists `etag` (weak comparison: W/ ignored, as RFC 9110
// §13.1.2 prescribes for this header).
bool ifNoneMatchHits(std::string_view ifNoneMatch, std::string_view etag);

struct ByteRange {
  std::uint64_t first = 0;
  std::uint64_t length = 0;
};

enum class RangeOutcome {
  kWhole,          // no usable Range: absent, not bytes, malformed or several ranges
  kPartial,        // one satisfiable range, in *range
  kUnsatisfiable,  // one range that starts at or past the end: 416
};

// Interprets a Range header for a representation of `size` bytes. Several ranges are
// answered with the whole representation (allowed by RFC 9110 §14.2), which spares a
// multipart/byteranges body nobody here needs.
RangeOutcome parseRange(std::string_view range, std::uint64_t size, ByteRange* out);

}  // namespace prt::serve
