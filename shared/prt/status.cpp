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
    case StatusCode::kUsage: return "usage";
    case StatusCode::kNotFound: return "not found";
    case StatusCode::kIoError: return "i/o error";
    case StatusCode::kUnavailable: return "unavailable";
    case StatusCode::kResourceExhausted: return "resource exhausted";
    case StatusCode::kInternal: return "internal";
  }
  return "unknown";
}

std::string Status::toString() const {
  if (isOk()) return "ok";
  return std::string(statusCodeName(code_)) + ": " + message_;
}

}  // namespace prt
