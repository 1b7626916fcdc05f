// Status: the error type every fallible entry point of the shared library returns.
// No exceptions cross shared/ boundaries, so the same code behaves identically in
// native builds and in Emscripten builds compiled without exception support.
#pragma once

#include <string>
#include <utility>

namespace prt {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  // a parameter is outside its documented range (order, size, direction)
  kSizeMismatch,     // a buffer is too small or sizes disagree
  kNotFinite,        // an input value is NaN or infinite
  // Decoding untrusted bytes (prt/asset.h):
  kTruncated,         // the data ends before the structure it declares
  kBadMagic,          // not this format at all
  kBadVersion,        // a format version this reader cannot read
  kChecksumMismatch,  // stored and computed checksums differ: damaged in storage or transit
  kCorrupt,           // checksums pass but the content is inconsistent or out of range
};

// Returns a stable lower-case name for a code ("ok", "invalid argument", ...).
const char* statusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;  // ok
  static Status ok() { return Status(); }
  static Status error(StatusCode code, std::string message) {
    Status s;
    s.code_ = code;
    s.message_ = std::move(message);
    return s;
  }

  bool isOk() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  // Human-readable message naming the problem; empty when ok.
  const std::string& message() const { return message_; }
  // "<code name>: <message>", or "ok".
  std::string toString() const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

}  // namespace prt
