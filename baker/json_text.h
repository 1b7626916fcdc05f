// Minimal JSON text helpers for the CLI's --json outputs.
#pragma once

#include <string>

namespace prt {

// A JSON string literal; bytes that are not valid UTF-8 are escaped as Latin-1 code points
// so the output always parses, whatever bytes a file name holds.
std::string jsonString(const std::string& s);

// A number with 9 significant digits (round-trips a float); non-finite values as null.
std::string jsonNumber(double v);

}  // namespace prt
