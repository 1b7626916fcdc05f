// Whole-file reads and atomic writes for the baker's outputs.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "prt/status.h"

namespace prt {

// Reads all of `path` into *out; fails (naming the path) when it is missing, not a regular
// file, unreadable, or larger than maxBytes.
Status readFileBytes(const std::string& path, std::uint64_t maxBytes, std::vector<std::uint8_t>* out);

// Writes `bytes` to a temporary file beside `path`, flushes it to disk, then renames it
// over `path`: readers see the old file or the complete new one, never a partial one, and
// an interrupted write leaves `path` untouched (the temporary is removed on failure).
Status writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes);

}  // namespace prt
