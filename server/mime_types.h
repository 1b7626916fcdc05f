// Content-Type by file extension for the web client's static files.
#pragma once

#include <string_view>

namespace prt::serve {

// The media type for `fileName`'s extension (case-insensitive): text types carry
// "charset=utf-8"; .wasm is application/wasm (browsers refuse to stream-compile anything
// else); .js and .mjs are text/javascript (modules need a JavaScript type). Unknown
// extensions get application/octet-stream, which browsers will not render or run.
std::string_view contentTypeFor(std::string_view fileName);

// True for the static types worth compressing on the fly (text, JSON, JavaScript, wasm,
// SVG, glTF); not for already-compressed images, nor for unknown types, whose size and
// compressibility say nothing (the catalogue compresses baked assets itself).
bool isCompressibleType(std::string_view contentType);

}  // namespace prt::serve
