// JSON text for the server's documents (/api/scenes, /api/lights, error bodies).
#pragma once

#include <string>
#include <string_view>

namespace prt::serve {

// A JSON string literal. Bytes that are not well-formed UTF-8 (file names may hold any
// bytes) become \u00XX escapes of their Latin-1 reading, so the document always parses.
std::string jsonString(std::string_view s);

// A number with 9 significant digits (round-trips a float); non-finite values as null.
std::string jsonNumber(double v);

}  // namespace prt::serve
