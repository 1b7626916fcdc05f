#include "prt/status.h"

namespace prt {

const char* statusCodeName(StatusCode code) {
  switch (code) {
    case StatusCode::kOk: return "ok";
    case StatusCode::kInvalidArgument: return "invalid argument";
    case StatusCode::kSizeMismatch: return "size mismatch";
    case StatusCode::kNotFinite: return "not finite";
    case StatusCode::kTruncated: return "truncated";
    case StatusCode::kBadMagic: return "bad magic";
    case StatusCode::kBadVersion: return "bad version";
    case StatusCode::kChecksumMismatch: return "checksum mismatch";
    case StatusCode::kCorrupt: return "corrupt";
  }
  return "unknown";
}

std::string Status::toString() const {
  if (isOk()) return "ok";
  return std::string(statusCodeName(code_)) + ": " + message_;
}

}  // namespace prt
