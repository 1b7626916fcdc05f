// JSON text helpers for prt-bake's --json outputs and prt-serve's documents.
#pragma once

#include <string>
#include <string_view>

namespace prt {

// A JSON string literal. Bytes that are not well-formed UTF-8 (file names may hold any
// bytes) become \u00XX escapes of their Latin-1 reading, so the document always parses.
std::string jsonString(std::string_view s);

// A number with 9 significant digits (round-trips a float); non-finite values as null.
std::string jsonNumber(double v);

}  // namespace prt
